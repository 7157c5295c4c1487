// Port of the fragment-side evaluation of Mesa 22.3.6 llvmpipe: lp_bld_interp.c
// (attribs_update_simple: a = fmuladd(dady, y, fmuladd(dadx, x, a0)), then a * (1 / w) for
// perspective inputs) and lp_state_fs.c (z plus the polygon offset slot, clamped to [0, 1]
// because restrict_depth_values is set for GL). Fragment shaders run with FTZ/DAZ.
#include "driver_models/float_ops.hpp"
#include "driver_models/llvmpipe_raster.hpp"

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
  const float z_plane = evaluate(k.z, x, y, fma);
  if (position) position[0] = z_plane, position[1] = evaluate(k.w, x, y, fma);
  // z + polygon offset (0 here), then lp_build_clamp(z, 0, 1) (gallivm/lp_bld_arit.c): min
  // with 1 first, then max with 0. minps/maxps return the second operand for NaN, so a NaN
  // depth (a triangle set up from a NaN window position) becomes 1.
  float z = ftz(z_plane + 0.0f);
  z = z < 1.0f ? z : 1.0f;
  z = z > 0.0f ? z : 0.0f;
  return z;
}

}  // namespace glrc::driver_models
