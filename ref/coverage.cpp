#include "ref/coverage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

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
    : t_(t), clip_(clip_planes(t)), subpixel_bits_(m.subpixel_bits) {
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
  for (const ClipPlane& p : clip_.planes)
    if (p.sign.sign(px, py) < 0) return false;
  return true;
}

namespace {

// floor(n/d) and n - floor(n/d)·d, for d > 0 (C++ division truncates toward zero).
void floor_divide(int128 n, int128 d, int128& q, int128& r) {
  // In 64 bits where both fit (nearly always): one instruction, not libgcc's 128-bit division.
  constexpr int128 kMost = std::numeric_limits<int64_t>::max();
  if (n <= kMost && n >= -kMost && d <= kMost) {
    const int64_t n64 = int64_t(n), d64 = int64_t(d);
    int64_t q64 = n64 / d64, r64 = n64 % d64;
    if (r64 < 0) r64 += d64, --q64;
    q = q64, r = r64;
    return;
  }
  q = n / d, r = n - q * d;
  if (r < 0) r += d, --q;
}

}  // namespace

std::optional<CoverageTest::CoveredRows> CoverageTest::covered_rows(int y0, int y1, int x0,
                                                                    int x1) const {
  return walk(false, y0, y1, x0, x1);
}

std::optional<CoverageTest::CoveredRows> CoverageTest::covered_columns(int x0, int x1, int y0,
                                                                       int y1) const {
  return walk(true, x0, x1, y0, y1);
}

std::optional<CoverageTest::CoveredRows> CoverageTest::walk(bool columns, int l0, int l1, int s0,
                                                            int s1) const {
  if (t_.path != CoveragePath::snapped || clip_.any()) return std::nullopt;
  // Every quotient the walk reaches is within lines·(|step_q| + 1) of its first one, and every
  // remainder below d: 64 bits hold them (negated too) when these bounds are below 2^62.
  constexpr int128 kFits = int128(1) << 62;
  const int128 lines = int128(l1) - l0 + 1;
  auto abs128 = [](int128 v) { return v < 0 ? -v : v; };
  CoveredRows walk;
  walk.x0_ = s0, walk.x1_ = s1;
  for (size_t i = 0; i < 3; ++i) {
    const TriangleSetup::IntEdge& e = t_.snapped_edges[i];
    // Along the line (a row: x; a column: y) and across it, from line to line.
    const int128 along = columns ? e.b : e.a, across = columns ? e.a : e.b;
    const int128 need = tie_inside_[i] ? 0 : 1;
    // Linear: its least value over the rectangle is at a corner. Passed there, everywhere.
    const int128 least =
        std::min(along * s0, along * s1) + std::min(across * l0, across * l1) + e.c;
    if (least >= need) continue;
    const int128 m = across * l0 + e.c - need;
    const int128 d = along > 0 ? along : along < 0 ? -along : 1;
    int128 q, r, step_q, step_r;
    floor_divide(m, d, q, r);
    floor_divide(across, d, step_q, step_r);
    if (d >= kFits || abs128(q) + lines * (abs128(step_q) + 1) >= kFits) return std::nullopt;
    CoveredRows::Edge& w = walk.edges_[size_t(walk.count_++)];
    w.q = int64_t(q), w.r = int64_t(r), w.d = int64_t(d);
    w.step_q = int64_t(step_q), w.step_r = int64_t(step_r);
    w.lower = along > 0 ? -1 : 0, w.upper = along < 0 ? -1 : 0, w.level = along == 0 ? -1 : 0;
  }
  return walk;
}

std::pair<int, int> CoverageTest::columns_of_rows(int y0, int y1) const {
  const std::pair<int, int> none{t_.box.x0, t_.box.x0 - 1};
  if (t_.path != CoveragePath::snapped) return {t_.box.x0, t_.box.x1};
  if (y1 < y0) return none;
  // The snapped triangle (every covered centre is in it, closed) cut to the rows' centres, in
  // subpixel steps: its vertices there and its edges' crossings of the two lines. Vertices are
  // exact in double (|s| < 2^40); a crossing is off by a few of its ulps, under 2^-9 step, far
  // inside the margin of a pixel each side.
  const double unit = std::ldexp(1.0, subpixel_bits_);
  const double lines[2] = {(y0 + 0.5) * unit, (y1 + 0.5) * unit};
  double lo = INFINITY, hi = -INFINITY;
  auto take = [&](double x) { lo = std::min(lo, x), hi = std::max(hi, x); };
  for (size_t i = 0; i < 3; ++i) {
    const double xa = double(t_.snapped[i][0]), ya = double(t_.snapped[i][1]);
    if (ya >= lines[0] && ya <= lines[1]) take(xa);
    const double xb = double(t_.snapped[(i + 1) % 3][0]), yb = double(t_.snapped[(i + 1) % 3][1]);
    if (ya == yb) continue;
    for (double line : lines)
      if ((line - ya) * (line - yb) <= 0) take(xa + (line - ya) * ((xb - xa) / (yb - ya)));
  }
  if (!(lo <= hi)) return none;
  const double step = 1 / unit;
  // Centre px + 1/2 within [lo, hi]·step, a pixel wider each side; inside the box.
  const double first = std::max(double(t_.box.x0), std::ceil(lo * step - 0.5) - 1);
  const double last = std::min(double(t_.box.x1), std::floor(hi * step - 0.5) + 1);
  if (!(first <= last)) return none;
  return {int(first), int(last)};
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

CoverageTest::Bands CoverageTest::bands(int px, int py, double freedom, double z_freedom) const {
  Bands out;
  // Distances first: a centre far outside any band needs no exact sign.
  std::array<double, 3> d{}, band{};
  for (int i = 0; i < 3; ++i) {
    d[i] = edges_[i].distance(px, py);
    band[i] = freedom * band_scale_[i];
    if (d[i] < -band[i]) return out;
  }
  bool in_plane_band = false;
  for (const ClipPlane& p : clip_.planes) {
    const double plane_band = freedom + z_freedom * p.scale, plane_d = p.sign.distance(px, py);
    if (plane_d < -plane_band) return out;
    in_plane_band = in_plane_band || plane_d <= plane_band;
  }
  out.reached = true;
  for (int i = 0; i < 3; ++i)
    if (d[i] <= band[i]) out.edges |= uint8_t(1u << i);
  out.plane = in_plane_band;
  return out;
}

uint8_t CoverageTest::classify(int px, int py, double freedom, const std::array<bool, 3>& shared,
                               bool unstable, double z_freedom) const {
  const Bands b = bands(px, py, freedom, z_freedom);
  if (!b.reached) return 0;
  uint8_t bits = 0;
  for (int i = 0; i < 3; ++i)
    if (b.edges & (1u << i)) bits |= shared[size_t(i)] ? edge::shared : edge::snapping;
  if (b.plane) bits |= edge::snapping;
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
