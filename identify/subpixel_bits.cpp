#include "identify/subpixel_bits.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "ref/reference.hpp"

namespace glrc::identify {
namespace {

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

}  // namespace

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
      const Expectation r = ref::render(p.c, m);
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

}  // namespace glrc::identify
