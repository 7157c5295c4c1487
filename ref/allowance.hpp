// Allowance: how far a conforming implementation's value may be from the exact one at a pixel,
// derived from what the GL specification leaves free. Three freedoms add up:
//
// Position. Each vertex of the polygon an implementation rasterizes may lie up to δ_j pixels
// from the exact one, in x and in y (freedom.hpp: snapping, float32 window positions, clipping
// arithmetic), and the freedom at a pixel is δ = Σ λ_j δ_j over the polygon's vertices (the
// largest over every triangulation). Moving vertex j by d_j changes the screen barycentrics at
// a fixed pixel by dλ_i = -λ_j ∇λ_i·d_j, and so the value v (smooth, noperspective or depth
// alike) by dv = -λ_j ∇v·d_j; with the λ_j >= 0 summing to 1:
//     |dv| <= δ·(|∂v/∂x| + |∂v/∂y|)        (first order; times 1.5 for the second)
// and never more than the spread of the triangle's vertex values, since every legal value is a
// convex combination of them. Depth adds the z_w freedom of clipped vertices (freedom.hpp).
//
// Arithmetic. The planes N = Σ λ_i a_i and D = Σ λ_i b_i (a = v/w, b = 1/w for smooth;
// a = v, b = 1 for noperspective and depth) evaluated in float32 from an anchor point, and the
// divide N/D:
//     c_e·u·(|N_a| + |N_x·(x - x_a)| + |N_y·(y - y_a)| + |v|·(|D_a| + ...)) / |D|
// with u = 2^-24 and N_a the plane's value at the anchor, which is the implementation's choice:
// the window origin, or a vertex of the polygon it rasterizes (llvmpipe anchors at the
// triangle's vertex 0, where a vertex with a tiny w_c makes N_a huge); the largest is taken.
//
// Values. The float rounding of the vertex values themselves and of 1/w, c_v·u·s with s the
// largest |v_i|; a vertex made by clipping carries values rounded once per clip plane that made
// it (2u·|v_B - v_A| + u·|v_C| <= 5u·s each), and for smooth values its 1/w_c a relative error
// ρ (freedom.hpp), which moves the value by at most ρ·spread. Denormals: GLSL lets every input
// and intermediate result that is a denormal be flushed to zero, an absolute error below
// 2^-126 in each, which the planes carry to the value multiplied by at most the largest pixel
// coordinate M and the largest |w_c|: c_d·2^-126·(1 + M)·max(1, |w|).
// c_p = c_e = c_v = c_d = 8 roundings. Flat values are copied: allowance 0.
#pragma once

#include <array>
#include <vector>

#include "core/case.hpp"
#include "ref/exact.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

inline constexpr double kFloatUnitRoundoff = 0x1p-24;
inline constexpr double kPositionRoundings = 8, kEvaluationRoundings = 8, kValueRoundings = 8;
inline constexpr double kDenormalFlushes = 8, kClippedValueRoundings = 5;

// A double bound as a float that is not smaller: stored allowances must stay bounds.
float round_up(double bound);

// The absolute freedom of a channel's values that does not depend on the pixel: c_v·u·s, the
// values of clipped vertices (`generations` clip planes deep) and denormals flushed, for a
// channel of largest vertex magnitude `scale` on triangle t of case c.
double value_freedom(const Case& c, const TriangleSetup& t, double scale, int generations);

// The allowance of one interpolated channel (a varying component or depth) over one triangle.
class Allowance {
 public:
  Allowance() = default;
  // The exact N and D of the channel (as in interpolation.hpp), in pixel coordinates; `spread`:
  // max v_i - min v_i (infinite when unknown); `values`: value_freedom above, plus ρ·spread
  // for a smooth channel of a clipped triangle.
  // `anchors`: window positions where the implementation may anchor its planes (besides the
  // window origin): PositionFreedom::anchors.
  Allowance(const LinearForm& numerator, const LinearForm& denominator, double spread,
            double values, const std::vector<std::array<double, 2>>& anchors = {});
  // At pixel (px, py), whose value is `value`: `delta` is the position freedom there
  // (PositionFreedom::at, pixels) and `extra` any further absolute freedom there (depth:
  // PositionFreedom::depth_at).
  double at(int px, int py, float value, double delta, double extra = 0) const;

 private:
  double an_ = 0, bn_ = 0, cn_ = 0, ad_ = 0, bd_ = 0, cd_ = 0;
  double spread_ = 0, values_ = 0;
  // Per anchor (the origin first): x, y and the planes' values there, |N(a)| and |D(a)|.
  std::vector<std::array<double, 4>> anchors_;
};

}  // namespace glrc::ref
