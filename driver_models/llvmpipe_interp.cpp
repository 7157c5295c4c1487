// Port of the fragment-side evaluation of Mesa 22.3.6 llvmpipe: lp_bld_interp.c
// (attribs_update_simple: a = fmuladd(dady, y, fmuladd(dadx, x, a0)), then a * (1 / w) for
// perspective inputs) and lp_state_fs.c (z plus the polygon offset slot, clamped to [0, 1]
// because restrict_depth_values is set for GL, then under GL_DEPTH_CLAMP to the viewport's
// depth bounds: lp_build_depth_clamp). Fragment shaders run with FTZ/DAZ.
#include "driver_models/float_ops.hpp"
#include "driver_models/llvmpipe_raster.hpp"
#include "driver_models/viewport.hpp"

namespace glrc::driver_models {
namespace {

float evaluate(const Plane& p, float x, float y, bool fma) {
  // DAZ on the coefficients as loaded, FTZ on every result.
  const float a0 = ftz(p.a0), dadx = ftz(p.dadx), dady = ftz(p.dady);
  if (fma) return ftz(fma32(dady, y, ftz(fma32(dadx, x, a0))));
  const float a = ftz(ftz(dadx * x) + a0);
  return ftz(ftz(dady * y) + a);
}

}  // namespace

float llvmpipe_fragment(const LlvmpipeCoefficients& k, const std::vector<Interpolation>& interp,
                        int px, int py, bool fma, float* values, float* position) {
  // pixoffx/pixoffy: the integer pixel position (the half-pixel offset is in a0).
  const float x = float(px), y = float(py);
  bool have_oow = false;
  float oow = 0;
  for (size_t i = 0; i < interp.size(); ++i) {
    const Plane& p = k.values[i];
    switch (interp[i]) {
      case Interpolation::flat:
        values[i] = p.a0;
        break;
      case Interpolation::noperspective:
        values[i] = evaluate(p, x, y, fma);
        break;
      case Interpolation::smooth:
        if (!have_oow) {
          oow = ftz(1.0f / evaluate(k.w, x, y, fma));  // lp_build_rcp is a true division
          have_oow = true;
        }
        values[i] = ftz(evaluate(p, x, y, fma) * oow);
        break;
    }
  }
  // The fragment shader's position input, where asked: the z and 1/w planes themselves
  // (gl_FragCoord's z is not clamped; its w is the plane of 1/w_c, not its reciprocal).
  // The position's z has the polygon offset added (attribs_update: a0.x of slot 0), so
  // gl_FragCoord.z sees it too.
  float z = ftz(evaluate(k.z, x, y, fma) + k.offset);
  if (position) position[0] = z, position[1] = evaluate(k.w, x, y, fma);
  // lp_build_depth_clamp's restrict_depth_values: lp_build_clamp(z, 0, 1) (gallivm/
  // lp_bld_arit.c): min with 1 first, then max with 0. minps/maxps return the second operand
  // for NaN, so a NaN depth (a triangle set up from a NaN window position) becomes 1.
  z = z < 1.0f ? z : 1.0f;
  z = z > 0.0f ? z : 0.0f;
  return z;
}

std::array<float, 2> llvmpipe_depth_bounds(const Case& c) {
  // util_viewport_zmin_zmax of the viewport's float scale and translate: a = t − s (t under
  // clip_halfz), b = t + s, each way round.
  const ViewportXform vp = viewport_xform(c);
  const float a =
      c.clip_depth == ClipDepth::zero_to_one ? vp.translate[2] : vp.translate[2] - vp.scale[2];
  const float b = vp.translate[2] + vp.scale[2];
  return {a < b ? a : b, a < b ? b : a};
}

float llvmpipe_depth_clamp(float z, const std::array<float, 2>& bounds) {
  z = z < bounds[1] ? z : bounds[1];  // lp_build_clamp: min with the upper bound first
  return z > bounds[0] ? z : bounds[0];
}

}  // namespace glrc::driver_models
