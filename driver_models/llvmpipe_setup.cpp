// Port of Mesa 22.3.6 src/gallium/drivers/llvmpipe/lp_setup_tri.c (calc_fixed_position,
// rotate_fixed_position_*, triangle_*) and lp_state_setup.c (init_args, calc_coef4,
// apply_perspective_corr, emit_constant_coef4).
#include "driver_models/llvmpipe_setup.hpp"

#include <algorithm>
#include <cmath>

#include "driver_models/draw_offset.hpp"
#include "driver_models/float_ops.hpp"

namespace glrc::driver_models {
namespace {

// calc_fixed_position (SSE path): subtract the half-pixel offset in float, scale by
// FIXED_ONE, cvtps2dq. Returns the sign of the int64 area dx01*dy20 - dx20*dy01.
int fixed_position(const DrawVertex* const* v, std::array<int32_t, 3>& x,
                   std::array<int32_t, 3>& y) {
  const float fixed_one = float(1 << kLlvmpipeFixedOrder);
  for (int i = 0; i < 3; ++i) {
    x[i] = cvt_rne_i32((v[i]->window[0] - 0.5f) * fixed_one);
    y[i] = cvt_rne_i32((v[i]->window[1] - 0.5f) * fixed_one);
  }
  // _mm_sub_epi32: wrapping int32 differences, then 64-bit products.
  auto sub = [](int32_t a, int32_t b) { return int32_t(uint32_t(a) - uint32_t(b)); };
  const int64_t dx01 = sub(x[0], x[1]), dy01 = sub(y[0], y[1]);
  const int64_t dx20 = sub(x[2], x[0]), dy20 = sub(y[2], y[0]);
  const uint64_t area = uint64_t(dx01 * dy20) - uint64_t(dx20 * dy01);
  return area == 0 ? 0 : (area >> 63) ? -1 : 1;
}

}  // namespace

bool llvmpipe_setup_triangle(const Case& c, const DrawVertex& v0, const DrawVertex& v1,
                             const DrawVertex& v2, LlvmpipeTriangle& out) {
  out.v = {&v0, &v1, &v2};
  const int sign = fixed_position(out.v.data(), out.x, out.y);
  if (sign == 0) return false;

  // The state tracker renders a user FBO y-up and flips front_ccw for it, so llvmpipe's
  // "ccw" (area > 0) is clockwise as GL sees it and ccw_is_frontface = (front face is CW);
  // it flips front_ccw once more under GL_UPPER_LEFT (st_atom_rasterizer.c).
  const bool ccw_is_frontface = (c.front_face == FrontFace::cw) != facing_reversed(c);
  bool draw_positive = true, draw_negative = true;  // triangle_both
  switch (c.cull) {
    case CullFace::none:
      break;
    case CullFace::back:  // ccw_is_frontface ? triangle_ccw : triangle_cw
      draw_positive = ccw_is_frontface;
      draw_negative = !ccw_is_frontface;
      break;
    case CullFace::front:  // ccw_is_frontface ? triangle_cw : triangle_ccw
      draw_positive = !ccw_is_frontface;
      draw_negative = ccw_is_frontface;
      break;
    case CullFace::front_and_back:  // triangle_noop
      return false;
  }
  out.front_facing = (sign > 0) == ccw_is_frontface;
  if (sign > 0) return draw_positive;
  if (!draw_negative) return false;
  // Make it counter-clockwise (llvmpipe's sense) keeping the provoking vertex in place:
  // (v0, v2, v1) with first-vertex provoking, (v1, v0, v2) otherwise.
  if (c.provoking == ProvokingVertex::first) {
    std::swap(out.v[1], out.v[2]);
    std::swap(out.x[1], out.x[2]);
    std::swap(out.y[1], out.y[2]);
  } else {
    std::swap(out.v[0], out.v[1]);
    std::swap(out.x[0], out.x[1]);
    std::swap(out.y[0], out.y[1]);
  }
  return true;
}

LlvmpipeCoefficients llvmpipe_coefficients(const LlvmpipeTriangle& t,
                                           const std::vector<Interpolation>& interpolation,
                                           bool flatshade_first, const PolygonOffset* offset) {
  const auto& p0 = t.v[0]->window;
  const auto& p1 = t.v[1]->window;
  const auto& p2 = t.v[2]->window;
  // init_args
  const float x0_center = p0[0] - 0.5f, y0_center = p0[1] - 0.5f;
  const float dx01 = p0[0] - p1[0], dy01 = p0[1] - p1[1];
  const float dx20 = p2[0] - p0[0], dy20 = p2[1] - p0[1];
  const float e = dx01 * dy20, f = dy01 * dx20;
  const float ooa = 1.0f / (e - f);
  const float dx20_ooa = dx20 * ooa, dy20_ooa = dy20 * ooa;
  const float dx01_ooa = dx01 * ooa, dy01_ooa = dy01 * ooa;

  auto calc_coef4 = [&](float a0, float a1, float a2) {
    const float da01 = a0 - a1, da20 = a2 - a0;
    Plane p;
    p.dadx = da01 * dy20_ooa - da20 * dy01_ooa;
    p.dady = da20 * dx01_ooa - da01 * dx20_ooa;
    p.a0 = a0 - (p.dadx * x0_center + p.dady * y0_center);
    return p;
  };

  LlvmpipeCoefficients out;
  // The key's pgon_offset_units and scale: a setup without either computes no offset.
  if (offset && (offset->factor != 0.0f || offset->units != 0.0f)) {
    const float dz01 = p0[2] - p1[2], dz20 = p2[2] - p0[2];
    const float res_x = dz20 * dy01 - dy20 * dz01, res_y = dx20 * dz01 - dz20 * dx01;
    const float dzdx = std::fabs(res_x * ooa), dzdy = std::fabs(res_y * ooa);
    const float max = dzdx > dzdy || std::isnan(dzdx) || std::isnan(dzdy) ? dzdx : dzdy;
    const float mult = max * offset->factor;
    const float bias = float_depth_mrd(p0[2], p1[2], p2[2]) * offset->units;
    float zoffset = bias + mult;
    const float clamp = offset->clamp.value_or(0.0f);
    if (clamp > 0) zoffset = std::min(clamp, zoffset);
    if (clamp < 0) zoffset = std::max(clamp, zoffset);
    out.offset = zoffset;
  }
  out.z = calc_coef4(p0[2], p1[2], p2[2]);
  out.w = calc_coef4(p0[3], p1[3], p2[3]);
  const DrawVertex& provoking = flatshade_first ? *t.v[0] : *t.v[2];
  out.values.resize(interpolation.size());
  for (size_t k = 0; k < interpolation.size(); ++k) {
    const float a0 = t.v[0]->values[k], a1 = t.v[1]->values[k], a2 = t.v[2]->values[k];
    switch (interpolation[k]) {
      case Interpolation::flat:
        out.values[k] = Plane{provoking.values[k], 0, 0};
        break;
      case Interpolation::noperspective:
        out.values[k] = calc_coef4(a0, a1, a2);
        break;
      case Interpolation::smooth:
        // apply_perspective_corr: premultiply by each vertex's 1/w.
        out.values[k] = calc_coef4(a0 * p0[3], a1 * p1[3], a2 * p2[3]);
        break;
    }
  }
  return out;
}

}  // namespace glrc::driver_models
