// Allowance: how far a conforming implementation's value may be from the exact one at a pixel,
// derived from what the GL specification leaves free. Two freedoms add up:
//
// Position. An implementation may snap window positions to any grid of at least the
// GL_SUBPIXEL_BITS it reports (GL requires 4), with any rounding, and build its attribute planes
// from snapped or unsnapped positions. So each vertex may move by up to
//     delta = 2^-bits + c_p·u·M   pixels in x and in y,
// the second term being float32's rounding of window positions of magnitude up to M (the
// largest |x_w|, |y_w| of the viewport and the vertices). Moving vertex j by d_j changes the
// screen barycentrics at a fixed pixel by dλ_i = -λ_j ∇λ_i·d_j, and so the value v (smooth,
// noperspective or depth alike) by dv = -λ_j ∇v·d_j. With λ_j >= 0 summing to 1:
//     |dv| <= delta·(|∂v/∂x| + |∂v/∂y|)        (first order; times 1.5 for the second)
// and never more than the spread of the triangle's vertex values, since every legal value is a
// convex combination of them.
//
// Arithmetic. The planes N = Σ λ_i a_i and D = Σ λ_i b_i (a = v/w, b = 1/w for smooth;
// a = v, b = 1 for noperspective and depth) evaluated in float32, anchored at the window origin,
// and the divide N/D:
//     c_e·u·(|N_0| + |N_x·x| + |N_y·y| + |v|·(|D_0| + |D_x·x| + |D_y·y|)) / |D|  +  c_v·u·s
// with u = 2^-24, N_0 the plane's value at the window origin, s the largest |v_i| (float
// rounding of the vertex values themselves, of 1/w, and of clipped vertices' values).
// c_p = c_e = c_v = 8 roundings. Flat values are copied: allowance 0.
#pragma once

#include "core/case.hpp"
#include "ref/exact.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

inline constexpr double kFloatUnitRoundoff = 0x1p-24;
inline constexpr double kPositionRoundings = 8, kEvaluationRoundings = 8, kValueRoundings = 8;

// A double bound as a float that is not smaller: stored allowances must stay bounds.
float round_up(double bound);

// delta above, in pixels, for one triangle of a case, given the reported subpixel bits.
double position_freedom(const Case& c, const TriangleSetup& t, int subpixel_bits);

// The allowance of one interpolated channel (a varying component or depth) over one triangle.
class Allowance {
 public:
  Allowance() = default;
  // The exact N and D of the channel (as in interpolation.hpp), in pixel coordinates; `spread`:
  // max v_i - min v_i (infinite when unknown); `scale`: max |v_i|.
  Allowance(const LinearForm& numerator, const LinearForm& denominator, double delta, double spread,
            double scale);
  double at(int px, int py, float value) const;

 private:
  double an_ = 0, bn_ = 0, cn_ = 0, ad_ = 0, bd_ = 0, cd_ = 0;
  double delta_ = 0, spread_ = 0, scale_ = 0;
};

}  // namespace glrc::ref
