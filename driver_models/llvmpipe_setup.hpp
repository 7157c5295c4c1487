// llvmpipe's triangle setup: fixed-point snapping, facing and culling, vertex reordering
// (lp_setup_tri.c), and the attribute planes its JIT setup function computes (lp_state_setup.c).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/case.hpp"
#include "driver_models/draw_vertex.hpp"

namespace glrc::driver_models {

// FIXED_ORDER: 8 subpixel bits.
constexpr int kLlvmpipeFixedOrder = 8;

// A triangle that survived calc_fixed_position and the cull choice, in the vertex order
// do_triangle_ccw receives (counter-clockwise in llvmpipe's sense, after any swap).
struct LlvmpipeTriangle {
  std::array<const DrawVertex*, 3> v{};
  std::array<int32_t, 3> x{}, y{};  // snapped: round_half_even((x_w - 0.5) * 256)
  bool front_facing = true;         // as GL sees it: the fragment shader's gl_FrontFacing
};

// triangle_both / triangle_ccw / triangle_cw for the case's cull state. False: dropped (zero
// fixed-point area, or culled).
bool llvmpipe_setup_triangle(const Case& c, const DrawVertex& v0, const DrawVertex& v1,
                             const DrawVertex& v2, LlvmpipeTriangle& out);

// a(px, py) = a0 + dadx * px + dady * py at pixel (px, py)'s centre; a0 is the value at the
// framebuffer origin's pixel centre.
struct Plane {
  float a0 = 0, dadx = 0, dady = 0;
};

struct LlvmpipeCoefficients {
  Plane z, w;        // window z and 1/w_c (slot 0, the position)
  float offset = 0;  // the polygon offset, kept in the position's a0.x

  std::vector<Plane> values;  // per component; flat: a0 only; smooth: planes of v/w
};

// The JIT setup function (init_args + calc_coef4): planes from the UNSNAPPED float window
// positions, anchored at vertex 0, plain float ops (no fusing in that JIT code). With a polygon
// offset (`offset` not null), lp_do_offset_tri's value for a 32F depth buffer: cross(e, f).xy
// of dxyz01 = v0 − v1 and dxyz20 = v2 − v0 times ooa, the larger magnitude (an unordered
// compare takes dzdx) times the factor, plus units·2^(exponent of the largest |z| − 23), then
// glPolygonOffsetClamp's clamp.
LlvmpipeCoefficients llvmpipe_coefficients(const LlvmpipeTriangle& t,
                                           const std::vector<Interpolation>& interpolation,
                                           bool flatshade_first,
                                           const PolygonOffset* offset = nullptr);

}  // namespace glrc::driver_models
