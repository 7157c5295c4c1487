// Coverage: is a pixel centre inside the (clipped) triangle, with a tie-break rule for centres
// exactly on an edge so that triangles sharing an edge cover each of its pixels exactly once.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

#include "core/expectation.hpp"
#include "core/model.hpp"
#include "ref/clipping.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

class CoverageTest {
 public:
  // `classifies`: classify, classifies_nothing and row_span(s) may be called. Without it, on
  // the snapped path, the exact edges' double copies (SignEvaluator) are not made: coverage
  // there needs only the integer edges, and render_frame, which draws no edge bits, would make
  // three exact forms' copies per triangle for nothing. row_spans then gives every pixel of
  // each row (a span may hold more; the walk or the coverage test decides).
  CoverageTest(const TriangleSetup& t, const Model& m, bool classifies = true);
  bool covers(int px, int py) const;
  // f(px) for every px in [x0, x1] whose pixel of row py covers() holds, in order. The snapped
  // edge functions are stepped by their integer a from pixel to pixel: exact, the same values
  // as evaluating each pixel, for a fraction of the 128-bit products; on a wide row, the run of
  // covered pixels is found by dividing instead (exact too).
  template <class F>
  void for_each_covered(int py, int x0, int x1, F&& f) const;
  // The covered pixels of rows y0, y0 + 1, ..., y1 in turn, each row's as the one run
  // for_each_covered visits, found without a test per pixel. Edge i covers px when
  // a_i·px + M_i(py) >= 0, M_i = b_i·py + c_i - need_i (integers: need 0 on a tie-inside edge,
  // else 1): px >= -floor(M_i/a_i) for a_i > 0, px <= floor(M_i/-a_i) for a_i < 0, every px
  // or none for a_i = 0. Each quotient is divided out once, then stepped from row to row by
  // the integer quotient and remainder of b_i (as a scan converter walks an edge), exact. A
  // thin triangle's rows cover a pixel or none: their cost is this step, not a span of tests.
  class CoveredRows {
   public:
    // The covered pixels [lo, hi] within [x0, x1] of the next row (y0 first); lo > hi for none.
    std::pair<int, int> next() {
      int64_t lo = x0_, hi = x1_, none = 0;
      for (int i = 0; i < count_; ++i)
        step(edges_[size_t(i)], lo, hi, none);
      return run(lo, hi, none);
    }
    // How many edges the walk steps: those that bind within its rows and columns.
    int edges() const { return count_; }
    // f(lo, hi) for the next `rows` rows in turn, as next() gives them: the walk's state in
    // locals, which the compiler keeps in registers for the whole loop, not stored and loaded
    // again from row to row; a loop for each count of edges that bind.
    template <class F>
    void for_each_row(int rows, F&& f) {
      Edge e0 = edges_[0], e1 = edges_[1], e2 = edges_[2];
      switch (count_) {
        case 3:
          walk(rows, f, e0, e1, e2);
          break;
        case 2:
          walk(rows, f, e0, e1);
          break;
        case 1:
          walk(rows, f, e0);
          break;
        default:
          walk(rows, f);
      }
      edges_ = {e0, e1, e2};
    }

   private:
    friend class CoverageTest;
    CoveredRows() = default;
    // M = q·d + r, 0 <= r < d = |a| (d = 1 for a = 0: q = M); from row to row M rises by b =
    // step_q·d + step_r. lower (a > 0), upper (a < 0), level (a = 0): all ones or 0.
    struct Edge {
      int64_t q = 0, r = 0, d = 1, step_q = 0, step_r = 0;
      int64_t lower = 0, upper = 0, level = 0;
    };
    // One edge on one row: its bound on the run, then the edge stepped to the next row. No
    // branch: the kinds as masks, the carry as a mask (on a thin triangle's rows carries come as
    // the slope's digits do, no pattern a predictor learns).
    [[gnu::always_inline]] static void step(Edge& w, int64_t& lo, int64_t& hi, int64_t& none) {
      constexpr int64_t kLeast = std::numeric_limits<int64_t>::min();
      constexpr int64_t kMost = std::numeric_limits<int64_t>::max();
      lo = std::max(lo, (-w.q & w.lower) | (kLeast & ~w.lower));
      hi = std::min(hi, (w.q & w.upper) | (kMost & ~w.upper));
      none |= w.level & -int64_t(w.q < 0);
      w.q += w.step_q, w.r += w.step_r;
      const int64_t carry = -int64_t(w.r >= w.d);  // all ones when r reached d
      w.r -= w.d & carry, w.q -= carry;
    }
    [[gnu::always_inline]] std::pair<int, int> run(int64_t lo, int64_t hi, int64_t none) const {
      if (none || lo > hi) return {x0_, x0_ - 1};
      return {int(lo), int(hi)};
    }
    template <class F, class... E>
    [[gnu::always_inline]] void walk(int rows, F& f, E&... e) const {
      for (int k = 0; k < rows; ++k) {
        int64_t lo = x0_, hi = x1_, none = 0;
        (step(e, lo, hi, none), ...);
        const auto [l, h] = run(lo, hi, none);
        f(l, h);
      }
    }
    // The edges that bind, first: an edge every pixel of the rows and columns walked passes
    // (a fan triangle's rim far outside the framebuffer, a large triangle's edges beyond the
    // viewport) is left out, and the walk steps count_ edges a row.
    std::array<Edge, 3> edges_{};
    int count_ = 0;
    int x0_ = 0, x1_ = -1;
  };
  // A CoveredRows for rows [y0, y1] and pixels [x0, x1] (y0 <= y1, x0 <= x1): on the snapped
  // path, where no clip plane cuts (for_each_covered tests those per pixel), and
  // where every number of the walk fits 64 bits (always, but for triangles reaching far into
  // the guard band); else nothing: for_each_covered.
  std::optional<CoveredRows> covered_rows(int y0, int y1, int x0, int x1) const;
  // The same walk down columns x0, x1, ... in turn, each column's covered pixels [lo, hi] of
  // rows [y0, y1] (y for x throughout: an edge covers py when b_i·py + a_i·px + c_i - need_i >=
  // 0). A thin triangle nearer vertical than horizontal has fewer columns than rows to walk.
  std::optional<CoveredRows> covered_columns(int x0, int x1, int y0, int y1) const;
  // Columns [first, last] of the box holding every pixel of rows [y0, y1] the triangle covers
  // (a pixel or so wider): the columns covered_columns walks for those rows; first > last for
  // none. Off the snapped path, every column of the box.
  std::pair<int, int> columns_of_rows(int y0, int y1) const;
  // What this triangle's boundary means for the centre of pixel (px, py), as edge:: bits.
  // `freedom`: how far (in pixels, along x and along y) an implementation may move each vertex;
  // an edge then moves by at most freedom·(|n_x| + |n_y|) for its unit normal n, which is the
  // band around the exact (unsnapped) edge. snapping or shared: the centre is inside the
  // triangle grown by the bands, and within the band of an edge (shared: of an edge another
  // triangle shares; snapping: of an outer edge, or of a clip plane's line, whose band is
  // `freedom`). tie: the centre is exactly on an edge of this coverage test or of the exact
  // triangle, and not outside the others. unstable: the triangle's orientation is not decided
  // by the freedom; every centre inside it grown by the bands is marked edge::unstable.
  uint8_t classify(int px, int py, double freedom, const std::array<bool, 3>& shared,
                   bool unstable = false, double z_freedom = 0) const;
  // The bands classify() tests, each apart: whether the centre of (px, py) is inside the
  // triangle grown by the bands (`reached`; outside, no conforming implementation covers it),
  // and then which edges' bands (bit i: edge i) and whether a clip plane's band holds it.
  // Inside and in no band, every conforming implementation covers it.
  struct Bands {
    bool reached = false;
    uint8_t edges = 0;
    bool plane = false;
  };
  Bands bands(int px, int py, double freedom, double z_freedom = 0) const;
  // (z_freedom: the freedom of a clip plane's d/w_c at the pixel, PositionFreedom::z_clip_at,
  // which widens each plane's band by z_freedom · ClipPlane::scale pixels.)
  // Whether classify(px, py, freedom, ...) is 0 for every freedom up to `largest` (the centre is
  // outside a band, or inside every band with nothing else to mark), so that the freedom at the
  // pixel need not be computed. False says nothing.
  // largest_z: the largest z_freedom of the triangle.
  // Inline: once per pixel within reach of every triangle.
  bool classifies_nothing(int px, int py, double largest, bool unstable,
                          double largest_z = 0) const;
  // The pixels [first, last] of row py within [x0, x1] whose centre may be within `reach`
  // pixels of the exact triangle (inside every exact edge's line grown by `reach`), as a span
  // that may hold more but never misses one (SignEvaluator::row_bound); first > last for
  // none. With reach >= sqrt(2)·max(freedom, s) for the largest freedom passed to classify and
  // s half the model's subpixel step on the snapped path (0 on the homogeneous one), no pixel
  // outside it is covered (a snapped vertex moves by at most s along x and y) or classified
  // (every bit needs the centre inside the triangle grown by its bands): walking only
  // the spans visits pixels in proportion to the triangle's area and perimeter, not to its
  // bounding box, and changes no bit.
  std::pair<int, int> row_span(int py, double reach, int x0, int x1) const;
  // row_span() for every row of [y0, y1], each edge's bound walked from row to row
  // (SignEvaluator::row_bound): at(py) holds every pixel row_span(py, ...) must.
  class RowSpans {
   public:
    std::pair<int, int> at(int py) const {  // inline: per row of every triangle
      double lo = x0_, hi = x1_;
      for (const SignEvaluator::RowBound& b : bounds_) {
        const auto [l, h] = b.at(double(py));
        lo = std::max(lo, l), hi = std::min(hi, h);
      }
      if (!(lo <= hi)) return {x0_, x0_ - 1};
      return {int(std::ceil(lo)), int(std::floor(hi))};
    }

   private:
    friend class CoverageTest;
    std::array<SignEvaluator::RowBound, 3> bounds_;
    int x0_ = 0, x1_ = -1;
  };
  RowSpans row_spans(double reach, int x0, int x1, int y0, int y1) const;

 private:
  // covered_rows (lines l rows, s columns) or covered_columns (lines columns, s rows).
  std::optional<CoveredRows> walk(bool columns, int l0, int l1, int s0, int s1) const;
  const TriangleSetup& t_;
  ClipPlanes clip_;
  int subpixel_bits_ = 0;               // the model's: t_.snapped's unit is 2^-subpixel_bits_ pixel
  std::array<SignEvaluator, 3> edges_;  // the exact (homogeneous) edges, on either path
  std::array<bool, 3> tie_inside_{};    // a centre exactly on edge i is covered
  std::array<double, 3> band_scale_{};  // (|n_x| + |n_y|) of each exact edge's unit normal
};

inline bool CoverageTest::classifies_nothing(int px, int py, double largest, bool unstable,
                                             double largest_z) const {
  // classify's own tests with the band of `largest`, which is the widest: a centre outside it
  // is outside every narrower one; one inside every edge's and the clip planes' bands
  // from within is inside every narrower one too.
  bool inside = !unstable;
  for (int i = 0; i < 3; ++i) {
    const double d = edges_[size_t(i)].distance(px, py), band = largest * band_scale_[size_t(i)];
    if (d < -band) return true;
    inside = inside && d > band;
  }
  for (const ClipPlane& p : clip_.planes) {
    const double d = p.sign.distance(px, py), b = largest + largest_z * p.scale;
    if (d < -b) return true;
    inside = inside && d > b;
  }
  return inside;
}

template <class F>
void CoverageTest::for_each_covered(int py, int x0, int x1, F&& f) const {
  if (t_.path != CoveragePath::snapped) {
    for (int px = x0; px <= x1; ++px)
      if (covers(px, py)) f(px);
    return;
  }
  if (x1 < x0) return;
  std::array<int128, 3> e;
  for (int i = 0; i < 3; ++i)
    e[size_t(i)] = t_.snapped_edges[size_t(i)].at(x0, py);
  // A wide row: the covered pixels are one run, found exactly by dividing. Edge i covers pixel
  // x0 + k when e_i + a_i·k >= need_i (e > 0, or e >= 0 on a tie-inside edge: integers), so k
  // >= ceil((need - e)/a) for a > 0, k <= floor((e - need)/-a) for a < 0, and every k or none
  // for a = 0. Three 128-bit divisions per row, where stepping costs a few operations per pixel
  // (a thin triangle's short rows keep stepping). The clip planes are tested per pixel.
  constexpr int kWideRow = 32;
  if (x1 - x0 >= kWideRow && !clip_.any()) {
    // floor and ceiling of n/d for d > 0 (C++ division truncates toward zero).
    auto floor_div = [](int128 n, int128 d) { return n >= 0 ? n / d : -((-n + d - 1) / d); };
    auto ceil_div = [](int128 n, int128 d) { return n >= 0 ? (n + d - 1) / d : -(-n / d); };
    int128 lo = 0, hi = x1 - x0;
    for (size_t i = 0; i < 3; ++i) {
      const int128 a = t_.snapped_edges[i].a, need = tie_inside_[i] ? 0 : 1;
      if (a > 0)
        lo = std::max(lo, ceil_div(need - e[i], a));
      else if (a < 0)
        hi = std::min(hi, floor_div(e[i] - need, -a));
      else if (e[i] < need)
        return;
    }
    for (int128 k = lo; k <= hi; ++k)
      f(x0 + int(k));
    return;
  }
  for (int px = x0; px <= x1; ++px) {
    bool inside = true;
    for (size_t i = 0; i < 3; ++i) {
      inside = inside && (e[i] > 0 || (e[i] == 0 && tie_inside_[i]));
      e[i] += t_.snapped_edges[i].a;
    }
    if (inside && std::all_of(clip_.planes.begin(), clip_.planes.end(),
                              [&](const ClipPlane& p) { return p.sign.sign(px, py) >= 0; }))
      f(px);
  }
}

}  // namespace glrc::ref
