#include "identify/tie_rule.hpp"

#include <algorithm>
#include <cstdlib>
#include <utility>

#include "ref/reference.hpp"

namespace glrc::identify {
namespace {

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

}  // namespace

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
      const Expectation r = ref::render(p.c, m);
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

}  // namespace glrc::identify
