// Allowance: how far a conforming implementation's value may be from the exact one at a pixel,
// derived from what the GL specification leaves free. Three freedoms add up:
//
// Position. Each vertex of the polygon an implementation rasterizes may lie up to δ_j pixels
// from the exact one, in x and in y (freedom.hpp: snapping, float32 window positions, clipping
// arithmetic), and the freedom at a pixel is δ = Σ λ_j δ_j over the polygon's vertices (the
// largest over every triangulation). Moving vertex j by d_j changes the screen barycentrics at
// a fixed pixel by dλ_i = -λ_j ∇λ_i·d_j, and so the value v (smooth, noperspective or depth
// alike) by dv = -λ_j ∇v·d_j; with the λ_j >= 0 summing to 1, to first order:
//     |dv| <= δ·(|∂v/∂x| + |∂v/∂y|)
// Exactly: the moved vertices q_j + d_j draw at the pixel centre p the exact value at the point
// q = p - Σ λ'_j d_j, where λ' are p's barycentrics in the moved triangle, which are q's in the
// exact one (the vertices' values are the same). So |q - p| <= Σ λ'_j δ_j = δ(q) in x and in y,
// and with L the slope of δ (PositionFreedom::slope), |q - p| <= h = min(δ(p)/(1 - L), the
// largest δ) (PositionReach). N and D are linear in the window position, so
// v(q) - v(p) = (A·(q_x - p_x) + B·(q_y - p_y)) / D(q), with A = N_x - v·D_x, B = N_y - v·D_y
// and |D(q)| >= |D(p)| - h·(|D_x| + |D_y|):
//     |dv| <= h·(|A| + |B|) / (|D| - h·(|D_x| + |D_y|))   where that denominator is > 0
// and any value the vertices span where it is not. Near a vertex whose w_c is close to 0, D
// changes fast and this is many times the first order (found by fuzz on a GPU: a smooth value
// 0.0037 that snapping one vertex by 0.0017 px moves to 0.0185, five times the first order).
// The allowance takes the larger of 1.5 times the first order (its bound before the exact one:
// kept where it is larger, so that no allowance shrinks) and the exact bound, and never more
// than the spread of the triangle's vertex values, since every legal value is a convex
// combination of them (inside the polygon; outside it, below). In doubles, with the reference's
// value v rounded to float: |A| + |B| gets (2^-23·|v| + 2^-149)·(|D_x| + |D_y|) more; D at p,
// computed from its terms, 2^-50 of their magnitudes less; a denominator below 2^-20·|D| counts as
// 0; and 2^-30 of the bound more covers the roundings of its own arithmetic (δ and h are bounds
// with margins of their own, freedom.hpp and PositionReach). Depth adds the z_w freedom of clipped
// vertices (freedom.hpp).
//
// Outside the polygon. Snapping covers centres beyond the exact edges, where the plane is
// extrapolated and two implementations differ. One whose planes come from the vertices it
// snaps covers p inside its own triangle: the bound above holds (q is inside the exact one),
// but v(p) lies beyond the vertices' values, so the spread no longer caps it. One whose planes
// come from its unsnapped float positions f_j (within ε of q_j: the freedom less the
// snapping; llvmpipe) draws the value at q = Σ λ'_j q_j with λ' the barycentrics of p in (f_j),
// which are not all >= 0 there: |q - p| <= ε·Σ|λ'_j|, and Σ|λ'_j| = Σ|2A'_j(p)|/|2A'| is
// bounded exactly from the exact areas and ε (FanTriangles::outside_reach: the largest over the
// fan triangles that may hold p), the exact bound above taken with that h and no cap. Where
// the rounding may make 2A' zero (a sliver it may turn over) the value is not determined: a
// `sizes` campaign found llvmpipe drawing 10.4 where the exact plane gives -1.1 at a centre
// beside a sliver 3.5e-5 px high (cases/sliver_extrapolated_outside.json). A constant plane
// stays constant. Not covered: a centre inside the polygon that a fan triangle not holding it
// covers (its extrapolation is within the plane-setup term for every triangle that is not a
// sliver piece the rounding may turn over).
//
// Arithmetic. The planes N = Σ λ_i a_i and D = Σ λ_i b_i (a = v/w, b = 1/w for smooth;
// a = v, b = 1 for noperspective and depth) evaluated in float32 from an anchor point, and the
// divide N/D:
//     c_e·u·(|N_a| + |N_x·(x - x_a)| + |N_y·(y - y_a)| + |v|·(|D_a| + ...)) / |D|
// with u = 2^-24 and N_a the plane's value at the anchor, which is the implementation's choice:
// the window origin, or a vertex of the polygon it rasterizes (llvmpipe anchors at the
// triangle's vertex 0, where a vertex with a tiny w_c makes N_a huge); the largest is taken.
//
// Setup. The plane's gradient is computed in float32 from one triangle of the implementation's
// fan, anchored at one of its vertices q_i, with edges e1 = q_j - q_i, e2 = q_k - q_i and value
// differences da1 = ∇N·e1, da2 = ∇N·e2 (llvmpipe's calc_coef4, softpipe's setup_tri_coefficients):
//     ∂N/∂x = (da1·e2.y - da2·e1.y) / 2A,   ∂N/∂y = (da2·e1.x - da1·e2.x) / 2A
// The differences' own roundings are consistent moves of a vertex or of a value (covered
// above); what is not: each product's rounding, u·(|da1·e2.y| + |da2·e1.y|)/|2A| in ∂N/∂x (and
// likewise in y), which no longer cancels where the fan triangle is a sliver; and 2A computed
// from two rounded products, a relative error κ·u common to both components, κ = (|e1.x·e2.y|
// + |e2.x·e1.y|)/|2A|, which scales the plane about q_i: κ·u·|N(p) - N(q_i)|. With |da| <=
// |N_x·e.x| + |N_y·e.y| and |N(p) - N(q_i)| <= |N_x|·|x - x_i| + |N_y|·|y - y_i|, all of it is at
// most G·u·(|N_x| + |N_y|)·max(|x - x_i|, |y - y_i|), with G = 2κ + 2·max(|e1.x·e2.x|,
// |e1.y·e2.y|)/|2A| a number of the triangle's shape alone (about 5 for a well-shaped one,
// hundreds for a sliver). So, with c_s roundings:
//     c_s·u·G(p)·max_i ((|N_x| + |N_y|)·d_i + |v|·(|D_x| + |D_y|)·d_i) / |D|,  d_i = max(|x-x_i|,
//     |y-y_i|)
// The fan is the implementation's: G(p) is the largest G of any triangle of the polygon's
// vertices that holds the pixel (within the vertices' position freedom; FanTriangles), and q_i
// ranges over the polygon's vertices. Large only inside slivers: a clipped vertex close to
// another one makes them, and llvmpipe's fan uses them (measured: 2.3e-4 relative error in N
// on one). This is the setup of an implementation that clips (Mesa's draw module, then float
// planes from unsnapped positions). Not covered: a guard-band rasterizer that sets up float
// gradients the same way on a triangle reaching far outside the viewport; one that snaps first
// has 2A exact and interpolates from its vertices (evaluation above), and that is assumed.
//
// Values. The float rounding of the vertex values themselves and of 1/w, c_v·u·s with s the
// largest |v_i|; a vertex made by clipping carries values rounded once per clip plane that made
// it (2u·|v_B - v_A| + u·|v_C| <= 5u·s each), and for smooth values its 1/w_c a relative error
// ρ (freedom.hpp), which moves the value by at most ρ·spread. Denormals: GLSL lets every input
// and intermediate result that is a denormal be flushed to zero, an absolute error below
// 2^-126 in each, which the planes carry to the value multiplied by at most the largest pixel
// coordinate M and the largest |w_c|: c_d·2^-126·(1 + M)·max(1, |w|).
// c_p = c_e = c_v = c_d = 8 roundings, c_s = 4 (two per product term derived: the product and
// the multiplication by 1/2A). Flat values are copied: allowance 0.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/case.hpp"
#include "ref/blocks.hpp"
#include "ref/exact.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

inline constexpr double kFloatUnitRoundoff = 0x1p-24;
inline constexpr double kPositionRoundings = 8, kEvaluationRoundings = 8, kValueRoundings = 8;
inline constexpr double kDenormalFlushes = 8, kClippedValueRoundings = 5, kSetupRoundings = 4;

// A polygon an implementation may rasterize: its vertices' window positions, pixels.
using WindowPolygon = std::vector<std::array<double, 2>>;

// A double bound as a float that is not smaller: stored allowances must stay bounds. Inline: it
// runs once per pixel and channel.
inline float round_up(double bound) {
  const float f = float(bound);
  if (!(double(f) < bound)) return f;  // exact, or rounded up already, or NaN
  // The next float up; bound > f >= 0 in practice (an allowance), the general case otherwise.
  if (f >= 0 && f < std::numeric_limits<float>::infinity())
    return std::bit_cast<float>(std::bit_cast<uint32_t>(f) + 1);
  return std::nextafter(f, std::numeric_limits<float>::infinity());
}

// round_up() of kRowBlock bounds at once, bit for bit: the common case (a finite bound not
// below 0) in a loop without branches, which is vectorized; any other lane one at a time.
inline void round_up(const double* bound, float* out) {
  // Integer flags and an added 0 or 1: no branch, no short circuit, so that it is vectorized.
  int rest = 0;
  float rounded[kRowBlock];
  for (int j = 0; j < kRowBlock; ++j) {
    const double b = bound[j];
    const float f = float(b);
    const int up = double(f) < b;
    const int plain = (f >= 0) & (f < std::numeric_limits<float>::infinity());
    rounded[j] = std::bit_cast<float>(std::bit_cast<uint32_t>(f) + uint32_t(up & plain));
    rest |= up & (plain ^ 1);
  }
  if (!rest) return (void)std::copy(rounded, rounded + kRowBlock, out);
  for (int j = 0; j < kRowBlock; ++j)
    out[j] = round_up(bound[j]);
}

// The absolute freedom of a channel's values that does not depend on the pixel: c_v·u·s, the
// values of clipped vertices (`generations` clip planes deep) and denormals flushed, for a
// channel of largest vertex magnitude `scale` on triangle t of case c.
double value_freedom(const Case& c, const TriangleSetup& t, double scale, int generations);

// The triangles of a polygon's vertices: every triangle an implementation's fan of it may have
// (for a convex polygon, any of them is in some triangulation), and which of them hold a pixel.
// Built once per triangle of the case and shared by every channel's Allowance.
class FanTriangles {
 public:
  FanTriangles() = default;
  // `polygon`: window positions (PositionFreedom::polygon); `margin`: how far outside a
  // triangle a pixel centre may lie and still be drawn with it (the vertices' largest position
  // freedom, pixels). Three vertices on one line make no triangle.
  // `rounding`: how far an implementation that builds its planes from unsnapped positions
  // puts each vertex, in x and in y (the position freedom less the snapping), for
  // outside_reach.
  FanTriangles(const WindowPolygon& polygon, double margin, double rounding = 0);
  size_t size() const { return triangles_.size(); }
  // G(p) above: the largest shape factor G of the triangles that hold the window point (x, y)
  // within the margin; 0 when none does.
  double condition(double x, double y) const;
  // condition() of kRowBlock points (x[j], y[j]) at once, bit for bit: the same largest G.
  void condition(const double* x, const double* y, double* out) const;
  // Bounds {lo, hi} of what condition() gives at every point (x, y), x in [x0, x1]: the
  // largest G of the triangles that hold both ends (so every point between: they are convex),
  // with the rounding of the edge tests allowed for; and of those whose box meets the segment.
  std::array<double, 2> condition_range(double x0, double x1, double y) const;

  // Outside the polygon (allowance.hpp, "Outside the polygon"): -1 at a window point (x, y)
  // inside it (or on its edges, within their rounding); elsewhere (>= 0) how far from it, in x
  // and in y, lies the point whose exact value an implementation with planes from its
  // unsnapped vertices draws there: the largest reach over the triangles that hold the point
  // within the margin (over all of them where none does), infinite where one of them may turn
  // over or vanish within the rounding (no value is determined there). -1 everywhere for a
  // polygon of zero area.
  double outside_reach(double x, double y) const;
  // outside_reach() of kRowBlock points at once, bit for bit.
  void outside_reach(const double* x, const double* y, double* out) const;
  // Whether every point (x, y), x in [x0, x1], is inside the polygon as outside_reach() judges
  // it (its reach -1): both ends inside by more than the tests' rounding (it is convex).
  bool holds_run(double x0, double x1, double y) const;

 private:
  struct Triangle {
    double box[4];      // x0, y0, x1, y1 grown by the margin
    double edge[3][3];  // a·x + b·y + c >= 0 inside: unit normals, c grown by the margin
    double condition;   // G
    double q[3][2];     // its vertices
    // |2A| less how far the rounding may change it (negative where it may turn over), and
    // the reach's constant terms.
    double area_below, rounding;
  };
  // One triangle's reach at (x, y) (outside_reach), the point outside the polygon.
  static double reach(const Triangle& t, double x, double y);
  bool inside(double x, double y) const;
  std::vector<Triangle> triangles_;
  // The polygon's edges, a·x + b·y + c >= 0 inside (unit normals); none for zero area.
  std::vector<std::array<double, 3>> hull_;
};

// Where the planes of one triangle's channels may be evaluated from: the window origin, the
// polygon's vertices (where a fan triangle may be set up too) and the guard-band triangle's,
// each point once. Shared by every channel's Allowance of the triangle, so that the distances
// of a pixel to them are computed once per pixel, not once per channel.
class Anchors {
 public:
  static constexpr size_t kMost = 1 + 9 + 3;  // the origin; a triangle clipped by 6 planes; 3

  Anchors() = default;
  // `polygon`, `guard_band`: as Allowance's below.
  Anchors(const WindowPolygon& polygon, const WindowPolygon& guard_band);
  size_t size() const { return count_; }
  double x(size_t i) const { return points_[i][0]; }
  double y(size_t i) const { return points_[i][1]; }
  bool fan(size_t i) const { return fan_[i]; }

  // |x - x_a|, |y - y_a| and their maximum for the centre of pixel (px, py) and every anchor a.
  struct Distances {
    std::array<double, kMost> dx, dy, most;
  };
  void distances(int px, int py, Distances& out) const;
  // The same for the centres of kRowBlock pixels (px[j], py[j]) (integer pixel coordinates as
  // doubles), by anchor then pixel: bit for bit what distances() gives each.
  struct RowDistances {
    std::array<std::array<double, kRowBlock>, kMost> dx, dy, most;
  };
  void distances(const double* px, const double* py, RowDistances& out) const;
  // Bounds of what distances() gives over the centres of pixels px0..px1 of row py (px0 <=
  // px1), per anchor: |x - x_a| from dx_lo to dx_hi, |y - y_a| exactly dy, their maximum from
  // most_lo to most_hi. Exact bounds: x - x_a, rounded, is monotone in x.
  struct RunDistances {
    std::array<double, kMost> dx_lo, dx_hi, dy, most_lo, most_hi;
  };
  void distances(int px0, int px1, int py, RunDistances& out) const;

 private:
  std::array<std::array<double, 2>, kMost> points_{};
  std::array<bool, kMost> fan_{};
  size_t count_ = 0;
};

// How far from a pixel centre p, in x and in y, the point q lies whose exact value moved
// vertices draw at p (the position term above): h = min(max(δ·scale, floor), most) pixels for
// the freedom δ at p. of(L, largest): scale = 1/(1 - L) (and 2^-30 more) for δ's slope
// L < 1 - 2^-20 (PositionFreedom::slope), else the largest δ anywhere. The default, h = δ, is
// for a δ the same everywhere.
struct PositionReach {
  double scale = 1, floor = 0, most = std::numeric_limits<double>::infinity();
  static PositionReach of(double slope, double largest) {
    // The slope is a sum of two magnitudes, rounded (2^-53 of it): below 1 - 2^-20, 1/(1 - L)
    // computed is within 2^-31 of the exact one's, and 2^-30 more makes it not below it.
    if (slope < 1 - 0x1p-20) return {(1 + 0x1p-30) / (1 - slope), 0, largest};
    return {0, largest, largest};
  }
  double at(double delta) const {
    const double scaled = delta * scale;
    const double h = scaled < floor ? floor : scaled;  // std::max, as a selection
    return most < h ? most : h;
  }
};

// The allowance of one interpolated channel (a varying component or depth) over one triangle.
class Allowance {
 public:
  Allowance() = default;
  // The exact N and D of the channel (as in interpolation.hpp), in pixel coordinates; `spread`:
  // max v_i - min v_i (infinite when unknown); `values`: value_freedom above, plus ρ·spread
  // for a smooth channel of a clipped triangle.
  // `polygon`: the vertices of the polygon the implementation rasterizes, where its fan
  // triangles may be anchored (PositionFreedom::polygon); `guard_band`: the guard-band
  // triangle's (PositionFreedom::guard_band_triangle). Both, and the window origin, are where
  // the planes may be evaluated from.
  Allowance(const LinearForm& numerator, const LinearForm& denominator, double spread,
            double values, const WindowPolygon& polygon = {}, const WindowPolygon& guard_band = {});
  // The same, its anchors given as the triangle's shared Anchors (kept by pointer: they must
  // outlive it), and `reach` the triangle's (PositionReach::of its PositionFreedom).
  Allowance(const LinearForm& numerator, const LinearForm& denominator, double spread,
            double values, const Anchors& anchors, const PositionReach& reach = {});
  // At pixel (px, py), whose value is `value`: `delta` is the position freedom there
  // (PositionFreedom::at, pixels), `extra` any further absolute freedom there (depth:
  // PositionFreedom::depth_at), `condition` the setup's G(p) (FanTriangles::condition).
  // `outside` the reach of FanTriangles::outside_reach there (-1: inside the polygon).
  double at(int px, int py, float value, double delta, double extra = 0, double condition = 0,
            double outside = -1) const;
  // The same, with the pixel's distances to the anchors computed once for every channel
  // (Anchors::distances of the Anchors this was built with).
  double at(int px, int py, float value, double delta, double extra, double condition,
            double outside, const Anchors::Distances& distances) const;
  // at() for kRowBlock pixels (px[j], py[j]) at once (integer pixel coordinates as doubles;
  // each array kRowBlock long): out[j] is bit for bit at(px[j], py[j], value[j], delta[j],
  // extra[j], condition[j], outside[j], ...) with distances the Anchors::RowDistances of the
  // same pixels. Every lane is computed; a caller with fewer pixels pads the arrays.
  void at(const double* px, const double* py, const float* value, const double* delta,
          const double* extra, const double* condition, const double* outside,
          const Anchors::RowDistances& distances, double* out) const;
  // The block at() above with each lane's bound rounded up to a float (round_up): the
  // allowances a frame stores, bit for bit round_up() of at()'s.
  void at_rounded_up(const double* px, const double* py, const float* value, const double* delta,
                     const double* extra, const double* condition, const double* outside,
                     const Anchors::RowDistances& distances, float* out) const;
  // Bounds {lo, hi} of what at_rounded_up() gives at the pixels px0..px1 of row py (px0 <=
  // px1), each pixel's value in [value_lo, value_hi] (finite), delta, extra and condition within
  // the bounds given ({lo, hi} each), every pixel inside the polygon (outside -1:
  // FanTriangles::holds_run; lo holds outside it too) and distances those of
  // Anchors::distances of the run: lo <= each allowance <= hi. {0, +inf} when the run's D may be 0
  // (the value undefined there). The bound is taken operation by operation in at()'s order: every
  // operation but the planes' sums (whose rounding is allowed for) is monotone in its operands; a
  // relative 2^-44 more covers a compiler's other grouping of the sums of positive terms.
  std::array<double, 2> range(int px0, int px1, int py, float value_lo, float value_hi,
                              const std::array<double, 2>& delta,
                              const std::array<double, 2>& extra,
                              const std::array<double, 2>& condition,
                              const Anchors::RunDistances& distances) const;

 private:
  void set_planes(const LinearForm& numerator, const LinearForm& denominator);
  // The position term at pixel (px, py) of value v, where D computed is d and the freedom is
  // delta: position(position_parts(...)), at()'s and the block at()'s, one body. `defined`:
  // 1 where the exact bound's denominator is above 2^-20·|D| (a double: a lane of the block's
  // loops), else 0 and the bound infinite.
  // `h`: how far the point whose exact value is drawn may lie (PositionReach for a pixel
  // inside the polygon).
  struct PositionParts {
    double first, exact, defined;
  };
  PositionParts position_parts(double px, double py, double v, double d, double delta,
                               double h) const;
  double position(const PositionParts& parts) const;
  // The position term at a pixel outside the polygon whose reach (FanTriangles::outside_reach)
  // is `outside` >= 0: the larger of the snapped implementation's and the unsnapped one's,
  // neither capped by the spread.
  double outside_position(double px, double py, double v, double d, double delta,
                          double outside) const;
  void block_at(const double* px, const double* py, const float* value, const double* delta,
                const double* extra, const double* condition, const double* outside,
                const Anchors::RowDistances& distances, double* result) const;

  double an_ = 0, bn_ = 0, cn_ = 0, ad_ = 0, bd_ = 0, cd_ = 0;
  double abs_an_ = 0, abs_bn_ = 0, abs_ad_ = 0, abs_bd_ = 0;
  double spread_ = 0, values_ = 0;
  PositionReach reach_;
  const Anchors& anchors() const { return shared_ ? *shared_ : own_; }

  Anchors own_;                      // when built from the polygons
  const Anchors* shared_ = nullptr;  // the triangle's, when given
  // Per anchor: |N(a)| and |D(a)|, the planes' values there.
  std::array<double, Anchors::kMost> n_{}, d_{};
};

}  // namespace glrc::ref
