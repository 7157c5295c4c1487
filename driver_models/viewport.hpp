// Viewport transform and view-volume test, as Mesa computes them for a vertex the vertex
// shader (or geometry shader) emitted.
#pragma once

#include <array>
#include <cstdint>

#include "core/case.hpp"

namespace glrc::driver_models {

// pipe_viewport_state from _mesa_get_viewport_xform (main/viewport.c): x, y, width, height
// are floats there; the depth terms are computed in double from the float near/far.
struct ViewportXform {
  std::array<float, 3> scale{}, translate{};
};
ViewportXform viewport_xform(const Case& c);

// llvmpipe's vertex shader epilogue (draw_llvm.c generate_viewport): oow = 1/w, then
// x_w = fmuladd(x * oow, scale, translate), fused on FMA CPUs.
std::array<float, 4> window_position_llvm(const std::array<float, 4>& clip, const ViewportXform& vp,
                                          bool fma);

// The C viewport of draw_cliptest_tmp.h and of the clipper's interp(): x * oow * scale +
// translate, two roundings (Mesa's C code is built for baseline x86-64: no FMA).
std::array<float, 4> window_position_c(const std::array<float, 4>& clip, const ViewportXform& vp);

// The six view-volume planes in draw_pipe_clip order (x <= w, -w <= x, y <= w, -w <= y,
// -w <= z (0 <= z under GL_ZERO_TO_ONE, clip_halfz), z <= w): bit i set when the vertex is
// outside plane i. A NaN test counts as outside, as in both the LLVM (unordered compares) and
// C (!(... >= 0)) versions.
// Under GL_DEPTH_CLAMP (`clip_z` false: draw_update_clip_flags keys it on the rasterizer's
// depth_clip_near, which the state tracker clears with GL_DEPTH_CLAMP) neither z plane is tested,
// and nothing else takes their place: the x and y planes keep w_c >= 0.
uint32_t clip_mask(const std::array<float, 4>& clip, ClipDepth depth, bool clip_z = true);

}  // namespace glrc::driver_models
