// glrefcheck identify: which Model explains a GL implementation best. Builds its own probes,
// renders them on GL and on the exact reference under every candidate, and prints the evidence
// per choice (subpixel bits, attribute planes, tie-break rule, default provoking vertex, 24-bit
// depth rounding), a one-line summary and DIR/identify.json.
//
// Most probes are drawn in a viewport of (-64, -64, 128, 128) on a 64x64 framebuffer: there the
// viewport transform is x_w = 64·x_c with no rounding at all (a power-of-two scale, offset 0),
// so GL and the reference start from the very same window positions, and a position chosen on a
// fine grid reaches the rasterizer unchanged.
#include "cli/identify.hpp"

#include <fmt/core.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cli/model_cache.hpp"
#include "compare/compare.hpp"
#include "core/frame.hpp"
#include "ref/reference.hpp"

namespace glrc::cli {
namespace {

using json = nlohmann::json;

constexpr int kFramebuffer = 64;
constexpr double kViewportScale = 64;  // x_w = 64·x_c in the probe viewport

// Deterministic on every platform (the standard distributions are not).
class Random {
 public:
  explicit Random(uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(rng_() >> 11) * 0x1p-53; }
  int integer(int lo, int hi) { return lo + int(rng_() % uint64_t(hi - lo + 1)); }  // inclusive
  bool coin() { return (rng_() >> 63) != 0; }

 private:
  std::mt19937_64 rng_;
};

struct Point {
  double x = 0, y = 0;
};
struct FPoint {  // a window position that is a float32 by its type
  float x = 0, y = 0;
  operator Point() const { return {x, y}; }
};

Case probe_case(const std::string& name, const std::string& description) {
  Case c;
  c.name = name;
  c.description = description;
  c.source_path = "(glrefcheck identify)";
  c.fb_width = c.fb_height = kFramebuffer;
  c.viewport = {-kFramebuffer, -kFramebuffer, 2 * kFramebuffer, 2 * kFramebuffer};
  return c;
}

float exact_float(double v, const char* what) {
  const float f = float(v);
  if (double(f) != v)
    throw std::logic_error(fmt::format("identify: inexact probe {} {:.17g}", what, v));
  return f;
}

// A vertex at window position p (each coordinate a float that x_c = x_w / 64 keeps exactly),
// window depth z_w (depth range 0..1: z_c = 2·z_w - 1, exact for the values used) and w_c = 1.
Vertex window_vertex(Point p, double z_w = 0.5, std::vector<float> values = {}) {
  Vertex v;
  v.clip = {exact_float(p.x / kViewportScale, "x"), exact_float(p.y / kViewportScale, "y"),
            exact_float(2 * z_w - 1, "z"), 1.0f};
  v.values = std::move(values);
  return v;
}

void add_triangle(Case& c, const std::array<Vertex, 3>& v) {
  const auto first = uint32_t(c.vertices.size());
  for (const Vertex& x : v)
    c.vertices.push_back(x);
  c.triangles.push_back({first, first + 1, first + 2});
}

// Cells of a square grid over the framebuffer, one probe each, so that probes never overlap.
Point cell_origin(int cell, int cell_size) {
  const int per_row = kFramebuffer / cell_size;
  return {double(cell % per_row * cell_size), double(cell / per_row * cell_size)};
}

// --- GL and reference frames ---------------------------------------------------------------

struct Probe {
  Case c;
  Frame gl;
};

Frame render_gl(gl::Renderer& r, const Case& c) {
  try {
    return r.render(c);
  } catch (const gl::RenderError& e) {
    throw InputError(std::string("identify: GL could not render a probe: ") + e.what());
  }
}

std::string bits_name(int bits) {
  return bits == 0 ? "none" : std::to_string(bits);
}

const char* planes_name(Planes p) {
  return p == Planes::snapped ? "snapped" : "unsnapped";
}

const char* provoking_name(ProvokingVertex p) {
  return p == ProvokingVertex::first ? "first" : "last";
}

// One row of a table: the candidate, its columns, and whether it is the one identified.
void print_row(bool best, const std::string& candidate, const std::vector<std::string>& cells,
               const std::vector<int>& widths) {
  std::string line = fmt::format("  {} {:<18}", best ? "*" : " ", candidate);
  for (size_t k = 0; k < cells.size(); ++k)
    line += fmt::format(" {:>{}}", cells[k], widths[k]);
  fmt::print("{}\n", line);
}

void print_header(const std::string& first, const std::vector<std::string>& columns,
                  const std::vector<int>& widths) {
  print_row(false, first, columns, widths);
}

// --- 1. subpixel bits ----------------------------------------------------------------------

// Thin triangles with vertices at random float positions, one per 8x8 cell: their long edges
// pass close to many pixel centres, which different grids put on different sides.
Case thin_triangles(Random& rnd, int index) {
  Case c = probe_case("identify_thin_" + std::to_string(index),
                      "thin triangles at random float positions");
  for (int cell = 0; cell < 64; ++cell) {
    const Point o = cell_origin(cell, 8);
    // Positions held as float32 from the start. (Rounding doubles through double(float(v))
    // afterwards was dropped by GCC 12.2 at -O2 in this function: its dead store elimination
    // removed the rounded stores.)
    auto random_point = [&] {
      return FPoint{float(o.x + rnd.uniform(0.75, 7.25)), float(o.y + rnd.uniform(0.75, 7.25))};
    };
    FPoint a = random_point(), b = random_point();
    while (std::hypot(b.x - a.x, b.y - a.y) < 4)
      a = random_point(), b = random_point();
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const double t = rnd.uniform(0.25, 0.75), h = rnd.uniform(0.05, 0.6) * (rnd.coin() ? 1 : -1);
    const FPoint p{
        float(std::clamp(a.x + t * (b.x - a.x) - h * (b.y - a.y) / len, o.x + 0.6, o.x + 7.4)),
        float(std::clamp(a.y + t * (b.y - a.y) + h * (b.x - a.x) / len, o.y + 0.6, o.y + 7.4))};
    add_triangle(c, {window_vertex(a), window_vertex(b), window_vertex(p)});
  }
  return c;
}

// Targeted probes for a grid of q = 2^-bits pixel: an edge from A = (cx + α·q, cy - 1) to
// B = (cx + β·q, cy + 3) crosses the row of the pixel centre (cx, cy) at cx + (3α + β)/4·q;
// α and β (eighths, no halves) are drawn so that this lies on one side of the centre exactly
// and on the other side once A and B are rounded to the grid. Mirrored and transposed at
// random, so that x and y, and both sides, are probed. Positions need a resolution of
// 2^-(bits+3): below 32 for 16 bits (float32 spacing 2^-19), anywhere in the frame for fewer.
void add_grid_probe(Case& c, Random& rnd, int bits, Point o) {
  const double q = std::ldexp(1.0, -bits);
  double alpha = 0, beta = 0;
  for (;;) {
    const int ka = rnd.integer(-24, 24), kb = rnd.integer(-24, 24);
    if ((ka & 7) == 4 || (kb & 7) == 4) continue;  // no halves: rounding ties are no evidence
    alpha = ka / 8.0, beta = kb / 8.0;
    const double exact = 3 * alpha + beta;
    const double snapped = 3 * std::nearbyint(alpha) + std::nearbyint(beta);
    if (exact != 0 && snapped != 0 && (exact > 0) != (snapped > 0)) break;
  }
  const double side = rnd.coin() ? 1 : -1, up = rnd.coin() ? 1 : -1;
  const bool transpose = rnd.coin();
  auto at = [&](double u, double v) {  // (u, v) relative to the centre (3.5, 3.5) of the cell
    if (transpose) std::swap(u, v);
    return Point{o.x + 3.5 + u, o.y + 3.5 + v};
  };
  const Point a = at(alpha * q, -1 * up), b = at(beta * q, 3 * up), d = at(3 * side, 1.25 * up);
  add_triangle(c, {window_vertex(a), window_vertex(b), window_vertex(d)});
}

// The cells of 8x8 in an order that starts with the 16 below x, y = 32.
Point grid_cell(int cell) {
  if (cell < 16) return {double(cell % 4 * 8), double(cell / 4 * 8)};
  const int k = cell - 16, row = k / 4;  // 48 cells: 4 per row in the low rows, 8 above
  if (row < 4) return {double(32 + k % 4 * 8), double(row * 8)};
  return cell_origin(32 + (k - 16), 8);
}

std::vector<Case> subpixel_probes(Random& rnd) {
  std::vector<Case> cases;
  for (int k = 0; k < 3; ++k)
    cases.push_back(thin_triangles(rnd, k));
  constexpr int kPerGrid = 9;
  int cell = 64;
  for (int bits = 16; bits >= 4; --bits) {  // 16 first: the low cells
    for (int k = 0; k < kPerGrid; ++k, ++cell) {
      if (cell == 64) {
        cases.push_back(probe_case("identify_grid_" + std::to_string(cases.size()),
                                   "edges that rounding to one grid moves across a centre"));
        cell = 0;
      }
      add_grid_probe(cases.back(), rnd, bits, grid_cell(cell));
    }
  }
  return cases;
}

struct BitsCandidate {
  int bits = 0;
  uint64_t mismatches = 0, ties_skipped = 0;
};

struct BitsFinding {
  int identified = 0, reported = 0;
  std::vector<BitsCandidate> candidates;
  size_t triangles = 0;
  bool distinct = true;  // no other candidate has as few mismatches
};

BitsFinding identify_bits(const std::vector<Probe>& probes, int reported) {
  BitsFinding f;
  f.reported = reported;
  for (const Probe& p : probes)
    f.triangles += p.c.triangles.size();
  std::vector<int> candidates{0};
  for (int bits = 4; bits <= 16; ++bits)
    candidates.push_back(bits);
  for (int bits : candidates) {
    Model m;
    m.subpixel_bits = bits;
    BitsCandidate row;
    row.bits = bits;
    for (const Probe& p : probes) {
      const ref::Reference r = ref::render(p.c, m);
      for (size_t i = 0; i < p.gl.pixel_count(); ++i) {
        if (r.frame.primitive[i] == p.gl.primitive[i]) continue;
        // A centre exactly on an edge of this candidate is the tie rule's business.
        if (r.edges[i] & edge::tie)
          ++row.ties_skipped;
        else
          ++row.mismatches;
      }
    }
    f.candidates.push_back(row);
  }
  // Fewest mismatches; among equals, no snapping first, then the coarser grid.
  const auto best = std::min_element(
      f.candidates.begin(), f.candidates.end(),
      [](const BitsCandidate& a, const BitsCandidate& b) { return a.mismatches < b.mismatches; });
  f.identified = best->bits;
  f.distinct = std::count_if(f.candidates.begin(), f.candidates.end(), [&](const BitsCandidate& c) {
                 return c.mismatches == best->mismatches;
               }) == 1;
  return f;
}

void print_bits(const BitsFinding& f, size_t frames) {
  fmt::print(
      "1. subpixel bits: coverage of {} probe frames ({} triangles: thin ones at random float\n"
      "   positions, and edges that one grid's rounding moves across a pixel centre); pixel\n"
      "   centres exactly on an edge of the candidate are left to the tie rule\n",
      frames, f.triangles);
  const std::vector<int> w{20, 14};
  print_header("candidate", {"coverage mismatches", "ties skipped"}, w);
  for (const BitsCandidate& c : f.candidates)
    print_row(c.bits == f.identified, bits_name(c.bits),
              {std::to_string(c.mismatches), std::to_string(c.ties_skipped)}, w);
  const BitsCandidate& best =
      *std::find_if(f.candidates.begin(), f.candidates.end(),
                    [&](const BitsCandidate& c) { return c.bits == f.identified; });
  std::string verdict =
      f.identified == 0 ? "no snapping" : fmt::format("{} subpixel bits", f.identified);
  if (best.mismatches == 0)
    verdict += ", which explains every probe pixel";
  else
    verdict += fmt::format(", the closest: {} {}", best.mismatches,
                           best.mismatches == 1 ? "mismatch remains" : "mismatches remain");
  if (!f.distinct) verdict += " (other candidates explain the probes as well)";
  fmt::print("   identified: {}\n", verdict);
  if (f.identified == f.reported)
    fmt::print("   GL_SUBPIXEL_BITS reports {}: agrees\n\n", f.reported);
  else if (f.identified == 0)
    fmt::print(
        "   GL_SUBPIXEL_BITS reports {}: the report and the behaviour disagree (the driver does "
        "not snap)\n\n",
        f.reported);
  else
    fmt::print("   GL_SUBPIXEL_BITS reports {}: the report and the behaviour disagree\n\n",
               f.reported);
}

// --- 2. attribute planes -------------------------------------------------------------------

// Perspective triangles (w_c 0.5 to 3) at random float positions, with smooth and
// noperspective attributes: planes from snapped positions move every value by about the
// gradient times the snapping, far more than the float arithmetic does.
Case plane_triangles(Random& rnd, int index) {
  Case c = probe_case("identify_planes_" + std::to_string(index),
                      "perspective triangles with smooth and noperspective attributes");
  c.varyings = {Varying{"s", 4, Interpolation::smooth},
                Varying{"n", 2, Interpolation::noperspective}};
  for (int t = 0; t < 12; ++t) {
    std::array<Vertex, 3> v;
    Point p[3];
    do {
      for (Point& q : p)
        q = {rnd.uniform(1, 63), rnd.uniform(1, 63)};
    } while (std::fabs((p[1].x - p[0].x) * (p[2].y - p[0].y) -
                       (p[2].x - p[0].x) * (p[1].y - p[0].y)) < 150);
    for (int i = 0; i < 3; ++i) {
      const double w = rnd.uniform(0.5, 3);
      v[size_t(i)].clip = {float(p[i].x / kViewportScale * w), float(p[i].y / kViewportScale * w),
                           float(rnd.uniform(-0.8, 0.8) * w), float(w)};
      for (int k = 0; k < 6; ++k)
        v[size_t(i)].values.push_back(float(rnd.uniform(-8, 8)));
    }
    add_triangle(c, v);
  }
  return c;
}

struct PlanesCandidate {
  Planes planes = Planes::unsnapped;
  double max_ulps = 0, mean_ulps = 0;
  uint64_t compared = 0, non_finite = 0;
};

struct PlanesFinding {
  Planes identified = Planes::unsnapped;
  bool distinguishable = true;  // false without snapping: both candidates are one model
  std::vector<PlanesCandidate> candidates;
};

PlanesFinding identify_planes(const std::vector<Probe>& probes, int bits) {
  PlanesFinding f;
  f.distinguishable = bits != 0;
  for (Planes planes : {Planes::unsnapped, Planes::snapped}) {
    Model m;
    m.subpixel_bits = bits;
    m.planes = planes;
    PlanesCandidate row;
    row.planes = planes;
    double sum = 0;
    for (const Probe& p : probes) {
      const ref::Reference r = ref::render(p.c, m);
      const compare::UlpTable ulps(p.c);
      for (size_t i = 0; i < p.gl.pixel_count(); ++i) {
        const int32_t prim = p.gl.primitive[i];
        if (!compare::same_primitive(p.c, r.frame.primitive[i], prim)) continue;
        for (size_t k = 0; k < r.frame.components.size(); ++k) {
          const compare::PixelError e = compare::pixel_error(
              r.frame.components[k][i], p.gl.components[k][i], ulps.ulp(prim, int(k)));
          ++row.compared;
          if (e.non_finite) {
            ++row.non_finite;
            continue;
          }
          row.max_ulps = std::max(row.max_ulps, e.ulps);
          sum += e.ulps;
        }
      }
    }
    row.mean_ulps = row.compared ? sum / double(row.compared) : 0;
    f.candidates.push_back(row);
  }
  const PlanesCandidate &u = f.candidates[0], &s = f.candidates[1];
  f.identified = f.distinguishable && s.max_ulps < u.max_ulps ? Planes::snapped : Planes::unsnapped;
  return f;
}

void print_planes(const PlanesFinding& f, int bits, size_t triangles) {
  fmt::print(
      "2. attribute planes: largest varying error in ULPs of the attribute's scale, on {}\n"
      "   perspective triangles at random float positions, with subpixel bits {}\n",
      triangles, bits_name(bits));
  const std::vector<int> w{12, 10, 14, 10};
  print_header("candidate", {"max ulps", "mean ulps", "values compared", "NaN/Inf"}, w);
  for (const PlanesCandidate& c : f.candidates)
    print_row(c.planes == f.identified, planes_name(c.planes),
              {fmt::format("{:.1f}", c.max_ulps), fmt::format("{:.2f}", c.mean_ulps),
               std::to_string(c.compared), std::to_string(c.non_finite)},
              w);
  if (!f.distinguishable)
    fmt::print(
        "   identified: unsnapped (no snapping: snapped and unsnapped planes are the same "
        "model)\n\n");
  else
    fmt::print("   identified: planes from {} positions\n\n", planes_name(f.identified));
}

// --- 3. tie-break rule ---------------------------------------------------------------------

// Positions here are on the quarter-pixel grid, held as integers in quarters: every grid of 2
// bits or more (and no snapping) leaves them where they are.
struct Q {
  long x = 0, y = 0;
};

long cross(Q o, Q a, Q b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

bool centre(Q p) {
  return (p.x & 3) == 2 && (p.y & 3) == 2;
}

// Whether the segment from a to b (ends excluded) passes through a pixel centre.
bool passes_centre(Q a, Q b) {
  for (long x = std::min(a.x, b.x); x <= std::max(a.x, b.x); ++x)
    for (long y = std::min(a.y, b.y); y <= std::max(a.y, b.y); ++y) {
      const Q p{x, y};
      if (centre(p) && cross(a, b, p) == 0 && !(p.x == a.x && p.y == a.y) &&
          !(p.x == b.x && p.y == b.y))
        return true;
    }
  return false;
}

enum EdgeKind { left_vertical, left_slanted, right_vertical, right_slanted, bottom, top, kKinds };
const char* const kKindNames[kKinds] = {"left, vertical", "left, slanted", "right, vertical",
                                        "right, slanted", "bottom",        "top"};

// Whether a rule takes centres on an edge of this kind.
bool takes(TieBreak rule, int kind) {
  const bool left = rule == TieBreak::bottom_left || rule == TieBreak::top_left;
  const bool bottom_rule = rule == TieBreak::bottom_left || rule == TieBreak::bottom_right;
  switch (kind) {
    case left_vertical:
    case left_slanted:
      return left;
    case right_vertical:
    case right_slanted:
      return !left;
    case bottom:
      return bottom_rule;
    default:
      return !bottom_rule;
  }
}

struct TieCentre {
  size_t probe = 0, pixel = 0;
  int32_t primitive = 0;
  int kind = 0;
};

// One triangle per 8x8 cell with exactly one edge through pixel centres (edge kinds in turn),
// vertices off the centres, and no other edge through one.
Case tie_triangles(Random& rnd, int index, size_t probe, std::vector<TieCentre>& centres) {
  Case c = probe_case("identify_ties_" + std::to_string(index),
                      "triangles with one edge exactly through pixel centres");
  static const Q kSlanted[] = {{1, 1}, {1, -1}, {1, 2}, {2, 1}, {1, -2}, {2, -1}, {1, 3}, {3, -1}};
  for (int cell = 0; cell < 64; ++cell) {
    const Point o = cell_origin(cell, 8);
    const int kind = (cell + index) % kKinds;
    // Draw the edge, then a third vertex on the side the kind asks for; a placement that
    // leaves no room for one is drawn again.
    Q d, c0, a, b, r;
    long steps = 0;
    for (bool found = false; !found;) {
      d = kind == left_vertical || kind == right_vertical ? Q{0, 1}
          : kind == bottom || kind == top                 ? Q{1, 0}
                                                          : kSlanted[rnd.integer(0, 7)];
      if (rnd.coin()) d = {-d.x, -d.y};  // either winding
      steps = std::min(3L, 5 / std::max(std::abs(d.x), std::abs(d.y)));
      // The centres on the edge, c0 + m·d for m = 0..steps, at least a pixel inside the cell.
      auto first_centre = [&](long origin, long step) {
        const long span = steps * step;
        return 4 * (origin +
                    rnd.integer(int(1 - std::min(0L, span)), int(6 - std::max(0L, span)))) +
               2;
      };
      c0 = {first_centre(long(o.x), d.x), first_centre(long(o.y), d.y)};
      // The ends: a quarter of d beyond the first and the last centre (in quarters).
      a = {c0.x - d.x, c0.y - d.y};
      b = {c0.x + 4 * steps * d.x + d.x, c0.y + 4 * steps * d.y + d.y};
      for (int attempt = 0; attempt < 200 && !found; ++attempt) {
        r = {long(o.x) * 4 + rnd.integer(2, 30), long(o.y) * 4 + rnd.integer(2, 30)};
        const long area = cross(a, b, r);  // 32 per square pixel
        if (std::abs(area) < 64 || centre(r) || passes_centre(a, r) || passes_centre(b, r))
          continue;
        // The inward normal of edge a-b points towards r.
        long nx = -(b.y - a.y), ny = b.x - a.x;
        if (area < 0) nx = -nx, ny = -ny;
        const int got = nx > 0   ? (ny == 0 ? left_vertical : left_slanted)
                        : nx < 0 ? (ny == 0 ? right_vertical : right_slanted)
                        : ny > 0 ? bottom
                                 : top;
        found = got == kind;
      }
    }
    const auto primitive = int32_t(c.triangles.size());
    auto point = [](Q p) { return Point{p.x / 4.0, p.y / 4.0}; };
    if (rnd.coin())
      add_triangle(c, {window_vertex(point(a)), window_vertex(point(b)), window_vertex(point(r))});
    else
      add_triangle(c, {window_vertex(point(b)), window_vertex(point(a)), window_vertex(point(r))});
    for (long m = 0; m <= steps; ++m) {
      const long px = (c0.x + 4 * m * d.x - 2) / 4, py = (c0.y + 4 * m * d.y - 2) / 4;
      centres.push_back({probe, size_t(py) * kFramebuffer + size_t(px), primitive, kind});
    }
  }
  return c;
}

struct TieCandidate {
  TieBreak rule = TieBreak::bottom_left;
  uint64_t wrong_centres = 0;  // tie centres where the rule and GL disagree
  uint64_t mismatches = 0;     // coverage mismatches in the whole probe frames
};

struct TieFinding {
  TieBreak identified = TieBreak::bottom_left;
  bool explains_all = false;
  uint64_t centres = 0;
  std::array<uint64_t, kKinds> per_kind{}, taken{};
  std::vector<TieCandidate> candidates;
};

TieFinding identify_ties(const std::vector<Probe>& probes, const std::vector<TieCentre>& centres,
                         int bits) {
  TieFinding f;
  f.centres = centres.size();
  for (const TieCentre& t : centres) {
    ++f.per_kind[size_t(t.kind)];
    if (probes[t.probe].gl.primitive[t.pixel] == t.primitive) ++f.taken[size_t(t.kind)];
  }
  for (TieBreak rule :
       {TieBreak::bottom_left, TieBreak::top_left, TieBreak::bottom_right, TieBreak::top_right}) {
    TieCandidate row;
    row.rule = rule;
    for (int k = 0; k < kKinds; ++k)
      row.wrong_centres +=
          takes(rule, k) ? f.per_kind[size_t(k)] - f.taken[size_t(k)] : f.taken[size_t(k)];
    Model m;
    m.subpixel_bits = bits;
    m.tie_break = rule;
    for (const Probe& p : probes) {
      const ref::Reference r = ref::render(p.c, m);
      for (size_t i = 0; i < p.gl.pixel_count(); ++i)
        row.mismatches += r.frame.primitive[i] != p.gl.primitive[i];
    }
    f.candidates.push_back(row);
  }
  const auto best = std::min_element(
      f.candidates.begin(), f.candidates.end(), [](const TieCandidate& a, const TieCandidate& b) {
        return std::pair(a.wrong_centres, a.mismatches) < std::pair(b.wrong_centres, b.mismatches);
      });
  f.identified = best->rule;
  f.explains_all = best->wrong_centres == 0 && best->mismatches == 0;
  return f;
}

void print_ties(const TieFinding& f, int bits, size_t triangles) {
  fmt::print(
      "3. tie-break rule: {} pixel centres exactly on one edge of {} triangles (quarter-pixel\n"
      "   vertices, subpixel bits {}); what GL took, by the edge's kind (inward normal)\n",
      f.centres, triangles, bits_name(bits));
  const std::vector<int> kw{8, 8};
  print_header("edge", {"centres", "GL took"}, kw);
  for (int k = 0; k < kKinds; ++k)
    print_row(false, kKindNames[k],
              {std::to_string(f.per_kind[size_t(k)]), std::to_string(f.taken[size_t(k)])}, kw);
  const std::vector<int> w{14, 22};
  print_header("candidate", {"centres wrong", "coverage mismatches"}, w);
  for (const TieCandidate& c : f.candidates)
    print_row(c.rule == f.identified, to_string(c.rule),
              {std::to_string(c.wrong_centres), std::to_string(c.mismatches)}, w);
  const TieCandidate& best =
      *std::find_if(f.candidates.begin(), f.candidates.end(),
                    [&](const TieCandidate& c) { return c.rule == f.identified; });
  if (f.explains_all)
    fmt::print("   identified: {}, which explains every tie\n\n", to_string(f.identified));
  else
    fmt::print(
        "   identified: {} fits best, but no rule explains every tie: {} of {} centres and {} "
        "pixels in all disagree with it\n\n",
        to_string(f.identified), best.wrong_centres, f.centres, best.mismatches);
}

// --- 4. default provoking vertex -----------------------------------------------------------

// Triangles of both windings with a flat varying that differs at each vertex.
Case provoking_triangles(Random& rnd) {
  Case c = probe_case("identify_provoking",
                      "flat varying, a different value at each vertex; glProvokingVertex never "
                      "called");
  c.varyings = {Varying{"f", 1, Interpolation::flat}};
  for (int cell = 0; cell < 16; ++cell) {
    const Point o = cell_origin(cell, 16);
    std::array<Vertex, 3> v;
    for (int i = 0; i < 3; ++i) {
      const FPoint p{float(o.x + rnd.uniform(1, 15)), float(o.y + rnd.uniform(1, 15))};
      v[size_t(i)] = window_vertex(p, 0.5, {float(3 * cell + i + 1)});
    }
    add_triangle(c, v);
  }
  return c;
}

struct ProvokingFinding {
  ProvokingVertex identified = ProvokingVertex::last, reported = ProvokingVertex::last;
  uint64_t pixels = 0, first = 0, last = 0, neither = 0;
};

ProvokingFinding identify_provoking(const Probe& p, ProvokingVertex reported) {
  ProvokingFinding f;
  f.reported = reported;
  for (size_t i = 0; i < p.gl.pixel_count(); ++i) {
    const int32_t prim = p.gl.primitive[i];
    if (prim < 0 || size_t(prim) >= p.c.triangles.size()) continue;
    const auto& t = p.c.triangles[size_t(prim)];
    const float v = p.gl.components[0][i];
    ++f.pixels;
    if (v == p.c.vertices[t[0]].values[0])
      ++f.first;
    else if (v == p.c.vertices[t[2]].values[0])
      ++f.last;
    else
      ++f.neither;
  }
  f.identified = f.first > f.last ? ProvokingVertex::first : ProvokingVertex::last;
  return f;
}

void print_provoking(const ProvokingFinding& f) {
  fmt::print(
      "4. default provoking vertex: a flat varying on {} pixels of 16 triangles, on a context "
      "where\n   glProvokingVertex was never called\n",
      f.pixels);
  const std::vector<int> w{18};
  print_header("candidate", {"pixels matching"}, w);
  print_row(f.identified == ProvokingVertex::last, "last", {std::to_string(f.last)}, w);
  print_row(f.identified == ProvokingVertex::first, "first", {std::to_string(f.first)}, w);
  print_row(false, "(neither)", {std::to_string(f.neither)}, w);
  fmt::print("   identified: {} vertex{}; GL_PROVOKING_VERTEX reports {}{}\n\n",
             provoking_name(f.identified),
             f.identified == ProvokingVertex::last ? " (GL's default)" : " (GL's default is last)",
             provoking_name(f.reported), f.reported == f.identified ? ": agrees" : ": disagrees");
}

// --- 5. 24-bit depth rounding --------------------------------------------------------------

// Window positions on a 1/64 grid and window depths multiples of 2^-23, w_c = 1: every GL
// stage before the depth plane is exact, and the ideal z·(2^24 - 1) at a pixel centre is a
// ratio of integers.
struct DepthTriangle {
  std::array<long, 3> x{}, y{};  // window position · 64
  std::array<long, 3> z{};       // window depth · 2^23
};

struct DepthCategory {
  std::string name;
  uint64_t pixels = 0, informative = 0, round = 0, truncate = 0, neither = 0;
};

Case depth_triangles(Random& rnd, int category, std::vector<DepthTriangle>& exact) {
  static const char* const kNames[] = {"constant z < 0.5", "sloped z < 1/16", "sloped z < 1"};
  Case c = probe_case("identify_depth_" + std::to_string(category),
                      std::string("24-bit depth: ") + kNames[category]);
  for (int cell = 0; cell < 16; ++cell) {
    const Point o = cell_origin(cell, 16);
    DepthTriangle t;
    do {
      for (int i = 0; i < 3; ++i) {
        t.x[size_t(i)] = long(o.x) * 64 + rnd.integer(64, 15 * 64);
        t.y[size_t(i)] = long(o.y) * 64 + rnd.integer(64, 15 * 64);
      }
    } while (std::labs((t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) -
                       (t.x[2] - t.x[0]) * (t.y[1] - t.y[0])) < 40L * 64 * 64);
    const long top = category == 0 ? (1L << 22) : category == 1 ? (1L << 19) : (1L << 23) - 1;
    const long z0 = rnd.integer(1, int(top - 1));
    for (int i = 0; i < 3; ++i)
      t.z[size_t(i)] = category == 0 ? z0 : rnd.integer(1, int(top - 1));
    std::array<Vertex, 3> v;
    for (int i = 0; i < 3; ++i)
      v[size_t(i)] = window_vertex({t.x[size_t(i)] / 64.0, t.y[size_t(i)] / 64.0},
                                   std::ldexp(double(t.z[size_t(i)]), -23));
    add_triangle(c, v);
    exact.push_back(t);
  }
  return c;
}

struct DepthFinding {
  std::string identified = "round";
  std::vector<DepthCategory> categories;
  DepthCategory total;
  std::vector<DepthCategory> rows() const {  // the categories, then the total
    std::vector<DepthCategory> r = categories;
    r.push_back(total);
    return r;
  }
};

// Counts, per category, the covered pixels whose stored integer is round(z·(2^24 - 1)) or
// floor(z·(2^24 - 1)) of the exact depth at the pixel centre; informative pixels are those
// where the two differ (the fraction is above one half).
DepthFinding identify_depth(const std::vector<Probe>& probes,
                            const std::vector<std::vector<DepthTriangle>>& exact) {
  static const char* const kNames[] = {"constant z < 0.5", "sloped z < 1/16", "sloped z < 1"};
  __extension__ typedef __int128 i128;
  DepthFinding f;
  f.total.name = "all";
  for (size_t k = 0; k < probes.size(); ++k) {
    DepthCategory cat;
    cat.name = kNames[k];
    const Frame& gl = probes[k].gl;
    for (int py = 0; py < gl.height; ++py)
      for (int px = 0; px < gl.width; ++px) {
        const size_t i = gl.index(px, py);
        const int32_t prim = gl.primitive[i];
        if (prim < 0 || size_t(prim) >= exact[k].size()) continue;
        const DepthTriangle& t = exact[k][size_t(prim)];
        const long cx = 64L * px + 32, cy = 64L * py + 32;
        auto e = [&](int a, int b) {  // edge function of vertices a -> b at the centre
          return i128((t.x[size_t(a)] - cx) * (t.y[size_t(b)] - cy) -
                      (t.y[size_t(a)] - cy) * (t.x[size_t(b)] - cx));
        };
        i128 l0 = e(1, 2), l1 = e(2, 0), l2 = e(0, 1);
        const i128 area = l0 + l1 + l2;
        if (area < 0) l0 = -l0, l1 = -l1, l2 = -l2;
        if (l0 < 0 || l1 < 0 || l2 < 0) continue;  // GL covered a centre just outside
        const i128 num = (l0 * t.z[0] + l1 * t.z[1] + l2 * t.z[2]) * ((i128(1) << 24) - 1);
        const i128 den = (area < 0 ? -area : area) << 23;
        const i128 floor = num / den, rem = num % den;
        const i128 round = 2 * rem >= den ? floor + 1 : floor;
        const auto stored = i128(gl.depth[i]);
        ++cat.pixels;
        const bool informative = 2 * rem > den;
        cat.informative += informative;
        if (stored == round && informative) ++cat.round;
        if (stored == floor && informative) ++cat.truncate;
        if (stored != round && stored != floor) ++cat.neither;
      }
    f.total.pixels += cat.pixels, f.total.informative += cat.informative;
    f.total.round += cat.round, f.total.truncate += cat.truncate, f.total.neither += cat.neither;
    f.categories.push_back(cat);
  }
  f.identified = f.total.truncate > f.total.round ? "truncate" : "round";
  return f;
}

void print_depth(const DepthFinding& f) {
  fmt::print(
      "5. 24-bit depth: GL_DEPTH_COMPONENT24 read back as integers, against round and floor of\n"
      "   the exact z·(2^24 - 1) at each pixel centre; informative: the two differ there\n");
  const std::vector<int> w{8, 12, 7, 9, 8};
  print_header("probe", {"pixels", "informative", "round", "truncate", "neither"}, w);
  for (const DepthCategory& c : f.rows())
    print_row(false, c.name,
              {std::to_string(c.pixels), std::to_string(c.informative), std::to_string(c.round),
               std::to_string(c.truncate), std::to_string(c.neither)},
              w);
  const uint64_t chosen = f.identified == "round" ? f.total.round : f.total.truncate;
  fmt::print("   identified: {} ({} of {} informative pixels)\n\n",
             f.identified == "round" ? "round to nearest" : "truncate", chosen,
             f.total.informative);
}

// --- the command ---------------------------------------------------------------------------

std::unique_ptr<gl::Renderer> open_raw_renderer(const Options& o) {
  gl::Target t;
  t.backend = *gl::backend_from_string(o.backend);
  t.driver = o.driver;
  t.device_index = o.device;
  t.set_provoking_vertex = false;
  t.depth_format = gl::DepthFormat::unorm24;
  try {
    return gl::create_renderer(t);
  } catch (const gl::Unavailable& e) {
    throw InputError(e.what());
  }
}

std::vector<Probe> render_all(gl::Renderer& r, std::vector<Case> cases) {
  std::vector<Probe> probes;
  for (Case& c : cases) {
    Frame f = render_gl(r, c);
    probes.push_back({std::move(c), std::move(f)});
  }
  return probes;
}

size_t triangle_count(const std::vector<Probe>& probes) {
  size_t n = 0;
  for (const Probe& p : probes)
    n += p.c.triangles.size();
  return n;
}

// Sections 1 to 3: the choices the reference takes as a Model. `rnd` draws the probes; the
// later sections draw theirs after these, so the probes are the same in every use.
struct ModelFindings {
  BitsFinding bits;
  PlanesFinding planes;
  TieFinding ties;
  size_t coverage_frames = 0, plane_triangles = 0, tie_triangles = 0;
  Model model() const {
    Model m;
    m.subpixel_bits = bits.identified;
    m.planes = planes.identified;
    m.tie_break = ties.identified;
    return m;
  }
};

ModelFindings find_model(gl::Renderer& renderer, Random& rnd) {
  ModelFindings f;
  const std::vector<Probe> coverage = render_all(renderer, subpixel_probes(rnd));
  f.bits = identify_bits(coverage, renderer.info().subpixel_bits);
  f.coverage_frames = coverage.size();

  const std::vector<Probe> planes_probes =
      render_all(renderer, {plane_triangles(rnd, 0), plane_triangles(rnd, 1)});
  f.planes = identify_planes(planes_probes, f.bits.identified);
  f.plane_triangles = triangle_count(planes_probes);

  std::vector<TieCentre> centres;
  std::vector<Case> tie_cases;
  for (int k = 0; k < 2; ++k)
    tie_cases.push_back(tie_triangles(rnd, k, size_t(k), centres));
  const std::vector<Probe> tie_probes = render_all(renderer, std::move(tie_cases));
  f.ties = identify_ties(tie_probes, centres, f.bits.identified);
  f.tie_triangles = triangle_count(tie_probes);
  return f;
}

constexpr uint64_t kSeed = 0x5eed1de47;

}  // namespace

Model identify_model(gl::Renderer& renderer) {
  Random rnd(kSeed);
  return find_model(renderer, rnd).model();
}

ModelChoice choose_model(const Options& o, gl::Renderer& renderer) {
  if (auto chosen = model_from_command_line(o)) return *chosen;
  const gl::GlInfo& info = renderer.info();
  const ModelCacheSlot cache = model_cache_slot(info.renderer, info.version, driver_files(info));
  if (const auto cached = cache.load()) return {*cached, "identify (cached)"};
  Model m;
  try {
    m = identify_model(renderer);
  } catch (const std::exception& e) {
    return fallback_model(o, e.what());
  }
  cache.save(m);
  return {m, "identify"};
}

int cmd_identify(const Options& o) {
  const auto start = Clock::now();
  const std::filesystem::path out = output_folder(o.out);
  auto renderer = open_renderer(o);
  auto raw = open_raw_renderer(o);
  const gl::GlInfo& info = renderer->info();
  fmt::print("glrefcheck identify: {} ({}), GL {}\n\n", info.renderer, o.backend, info.version);
  std::fflush(stdout);

  Random rnd(kSeed);
  const ModelFindings found = find_model(*renderer, rnd);
  print_bits(found.bits, found.coverage_frames);
  print_planes(found.planes, found.bits.identified, found.plane_triangles);
  print_ties(found.ties, found.bits.identified, found.tie_triangles);
  const BitsFinding& bits = found.bits;
  const PlanesFinding& planes = found.planes;
  const TieFinding& ties = found.ties;
  // What identify found is what run, diff and selftest would identify: keep it for them.
  model_cache_slot(info.renderer, info.version, driver_files(info)).save(found.model());

  const Case provoking_case = provoking_triangles(rnd);
  const Probe provoking_probe{provoking_case, render_gl(*raw, provoking_case)};
  const ProvokingFinding provoking =
      identify_provoking(provoking_probe, raw->info().initial_provoking_vertex);
  print_provoking(provoking);

  std::vector<std::vector<DepthTriangle>> exact(3);
  std::vector<Case> depth_cases;
  for (int k = 0; k < 3; ++k)
    depth_cases.push_back(depth_triangles(rnd, k, exact[size_t(k)]));
  const std::vector<Probe> depth_probes = render_all(*raw, std::move(depth_cases));
  const DepthFinding depth = identify_depth(depth_probes, exact);
  print_depth(depth);

  const std::string summary =
      fmt::format("identify: subpixel_bits={} planes={} tie={} provoking_default={} depth24={}",
                  bits.identified, planes_name(planes.identified), to_string(ties.identified),
                  provoking_name(provoking.identified), depth.identified);
  fmt::print("{}\n", summary);

  json j;
  j["backend"] = o.backend;
  j["driver"] = o.driver;
  j["gl"] = {{"vendor", info.vendor},
             {"renderer", info.renderer},
             {"version", info.version},
             {"platform", info.platform},
             {"subpixel_bits", info.subpixel_bits},
             {"initial_provoking_vertex", provoking_name(raw->info().initial_provoking_vertex)}};
  json bit_rows = json::array();
  for (const BitsCandidate& c : bits.candidates)
    bit_rows.push_back(
        {{"bits", c.bits}, {"mismatches", c.mismatches}, {"ties_skipped", c.ties_skipped}});
  j["subpixel_bits"] = {
      {"identified", bits.identified}, {"snapping", bits.identified != 0},
      {"reported", bits.reported},     {"agrees_with_reported", bits.identified == bits.reported},
      {"distinct", bits.distinct},     {"triangles", bits.triangles},
      {"candidates", bit_rows}};
  json plane_rows = json::array();
  for (const PlanesCandidate& c : planes.candidates)
    plane_rows.push_back({{"planes", planes_name(c.planes)},
                          {"max_ulps", c.max_ulps},
                          {"mean_ulps", c.mean_ulps},
                          {"compared", c.compared},
                          {"non_finite", c.non_finite}});
  j["planes"] = {{"identified", planes_name(planes.identified)},
                 {"distinguishable", planes.distinguishable},
                 {"candidates", plane_rows}};
  json tie_rows = json::array(), kinds = json::array();
  for (const TieCandidate& c : ties.candidates)
    tie_rows.push_back({{"rule", to_string(c.rule)},
                        {"centres_wrong", c.wrong_centres},
                        {"coverage_mismatches", c.mismatches}});
  for (int k = 0; k < kKinds; ++k)
    kinds.push_back({{"edge", kKindNames[k]},
                     {"centres", ties.per_kind[size_t(k)]},
                     {"taken", ties.taken[size_t(k)]}});
  j["tie_break"] = {{"identified", to_string(ties.identified)},
                    {"explains_all", ties.explains_all},
                    {"centres", ties.centres},
                    {"edges", kinds},
                    {"candidates", tie_rows}};
  j["provoking_default"] = {{"identified", provoking_name(provoking.identified)},
                            {"reported", provoking_name(provoking.reported)},
                            {"pixels", provoking.pixels},
                            {"first", provoking.first},
                            {"last", provoking.last},
                            {"neither", provoking.neither}};
  json depth_rows = json::array();
  for (const DepthCategory& c : depth.rows())
    depth_rows.push_back({{"probe", c.name},
                          {"pixels", c.pixels},
                          {"informative", c.informative},
                          {"round", c.round},
                          {"truncate", c.truncate},
                          {"neither", c.neither}});
  j["depth24"] = {{"identified", depth.identified}, {"probes", depth_rows}};
  j["summary"] = summary;
  j["seconds"] = seconds_since(start);
  const std::filesystem::path file = out / "identify.json";
  std::ofstream stream(file);
  stream << j.dump(2) << "\n";
  if (!stream) throw InputError("could not write " + file.string());
  fmt::print("wrote {}/identify.json in {:.2f} s\n", o.out, seconds_since(start));
  return 0;
}

}  // namespace glrc::cli
