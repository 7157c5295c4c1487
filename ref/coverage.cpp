#include "ref/coverage.hpp"

#include <algorithm>
#include <cmath>

namespace glrc::ref {

namespace {

// The tie-break rule, from the inward normal (a, b) of the edge in window coordinates (y up):
// a > 0 is a left edge, a < 0 a right edge, a == 0 with b > 0 a bottom edge, with b < 0 a top
// edge.
bool tie_inside(int sign_a, int sign_b, TieBreak rule) {
  const bool left = rule == TieBreak::bottom_left || rule == TieBreak::top_left;
  const bool bottom = rule == TieBreak::bottom_left || rule == TieBreak::bottom_right;
  if (sign_a != 0) return left ? sign_a > 0 : sign_a < 0;
  return bottom ? sign_b > 0 : sign_b < 0;
}

int sign128(int128 v) {
  return v > 0 ? 1 : v < 0 ? -1 : 0;
}

}  // namespace

CoverageTest::CoverageTest(const TriangleSetup& t, const Model& m, bool classifies)
    : t_(t), clip_(depth_clip(t)) {
  // The homogeneous path's coverage is the exact edges' signs: always made there.
  const bool exact_edges = classifies || t.path != CoveragePath::snapped;
  for (int i = 0; i < 3; ++i) {
    const auto& e = t.homogeneous_edges[i];
    if (exact_edges) {
      edges_[i] = SignEvaluator(e);
      const double a = std::fabs(e.a.get_d()), b = std::fabs(e.b.get_d());
      const double norm = std::hypot(a, b);
      band_scale_[i] = norm > 0 ? (a + b) / norm : 1.0;
    }
    if (t.path == CoveragePath::snapped) {
      const auto& s = t.snapped_edges[i];
      tie_inside_[i] = tie_inside(sign128(s.a), sign128(s.b), m.tie_break);
    } else {
      tie_inside_[i] = tie_inside(sgn(e.a), sgn(e.b), m.tie_break);
    }
  }
}

bool CoverageTest::covers(int px, int py) const {
  for (int i = 0; i < 3; ++i) {
    const int s = t_.path == CoveragePath::snapped ? sign128(t_.snapped_edges[i].at(px, py))
                                                   : edges_[i].sign(px, py);
    if (s < 0 || (s == 0 && !tie_inside_[i])) return false;
  }
  if (clip_.crosses_near && clip_.near.sign(px, py) < 0) return false;
  if (clip_.crosses_far && clip_.far.sign(px, py) < 0) return false;
  return true;
}

namespace {

// floor(n/d) and n - floor(n/d)·d, for d > 0 (C++ division truncates toward zero).
void floor_divide(int128 n, int128 d, int128& q, int128& r) {
  q = n / d, r = n - q * d;
  if (r < 0) r += d, --q;
}

}  // namespace

std::optional<CoverageTest::CoveredRows> CoverageTest::covered_rows(int y0, int y1, int x0,
                                                                    int x1) const {
  if (t_.path != CoveragePath::snapped || clip_.crosses_near || clip_.crosses_far)
    return std::nullopt;
  // Every quotient the walk reaches is within rows·(|step_q| + 1) of its first one, and every
  // remainder below d: 64 bits hold them (negated too) when these bounds are below 2^62.
  constexpr int128 kFits = int128(1) << 62;
  const int128 rows = int128(y1) - y0 + 1;
  auto abs128 = [](int128 v) { return v < 0 ? -v : v; };
  CoveredRows walk;
  walk.x0_ = x0, walk.x1_ = x1;
  for (size_t i = 0; i < 3; ++i) {
    const TriangleSetup::IntEdge& e = t_.snapped_edges[i];
    const int128 need = tie_inside_[i] ? 0 : 1;
    // Linear: its least value over the rectangle is at a corner. Passed there, everywhere.
    const int128 least = std::min(e.a * x0, e.a * x1) + std::min(e.b * y0, e.b * y1) + e.c;
    if (least >= need) continue;
    const int128 m = e.b * y0 + e.c - need;
    const int128 d = e.a > 0 ? e.a : e.a < 0 ? -e.a : 1;
    int128 q, r, step_q, step_r;
    floor_divide(m, d, q, r);
    floor_divide(e.b, d, step_q, step_r);
    if (d >= kFits || abs128(q) + rows * (abs128(step_q) + 1) >= kFits) return std::nullopt;
    CoveredRows::Edge& w = walk.edges_[size_t(walk.count_++)];
    w.q = int64_t(q), w.r = int64_t(r), w.d = int64_t(d);
    w.step_q = int64_t(step_q), w.step_r = int64_t(step_r);
    w.lower = e.a > 0 ? -1 : 0, w.upper = e.a < 0 ? -1 : 0, w.level = e.a == 0 ? -1 : 0;
  }
  return walk;
}

CoverageTest::RowSpans CoverageTest::row_spans(double reach, int x0, int x1, int y0, int y1) const {
  RowSpans spans;
  spans.x0_ = x0, spans.x1_ = x1;
  for (size_t i = 0; i < 3; ++i)
    spans.bounds_[i] = edges_[i].row_bound(reach, x0, x1, y0, y1);
  return spans;
}

std::pair<int, int> CoverageTest::row_span(int py, double reach, int x0, int x1) const {
  return row_spans(reach, x0, x1, py, py).at(py);
}

uint8_t CoverageTest::classify(int px, int py, double freedom, const std::array<bool, 3>& shared,
                               bool unstable, double z_freedom) const {
  uint8_t bits = 0;
  // Distances first: a centre far outside any band needs no exact sign.
  std::array<double, 3> d{}, band{};
  for (int i = 0; i < 3; ++i) {
    d[i] = edges_[i].distance(px, py);
    band[i] = freedom * band_scale_[i];
    if (d[i] < -band[i]) return 0;
  }
  double near_d = INFINITY, far_d = INFINITY;
  const double near_band = freedom + z_freedom * clip_.near_scale;
  const double far_band = freedom + z_freedom * clip_.far_scale;
  if (clip_.crosses_near && (near_d = clip_.near.distance(px, py)) < -near_band) return 0;
  if (clip_.crosses_far && (far_d = clip_.far.distance(px, py)) < -far_band) return 0;
  for (int i = 0; i < 3; ++i)
    if (d[i] <= band[i]) bits |= shared[i] ? edge::shared : edge::snapping;
  if (near_d <= near_band || far_d <= far_band) bits |= edge::snapping;
  if (unstable) bits |= edge::unstable;
  if (bits == 0) return 0;

  // Exactly on an edge of the coverage test (snapped or exact) or of the exact triangle, and
  // not outside the other edges of that same test.
  auto on_edge = [&](auto sign_of) {
    bool zero = false;
    for (int i = 0; i < 3; ++i) {
      const int s = sign_of(i);
      if (s < 0) return false;
      zero = zero || s == 0;
    }
    return zero;
  };
  const bool tie = on_edge([&](int i) { return edges_[i].sign(px, py); }) ||
                   (t_.path == CoveragePath::snapped &&
                    on_edge([&](int i) { return sign128(t_.snapped_edges[i].at(px, py)); }));
  if (tie) bits |= edge::tie;
  return bits;
}

}  // namespace glrc::ref
