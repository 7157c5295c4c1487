// Port of Mesa 22.3.6 src/gallium/auxiliary/draw/draw_pipe_offset.c (do_offset_tri), the
// floating_point_depth path (the harness's depth buffer is 32F). Identical in 25.0.7.
#include "driver_models/draw_offset.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace glrc::driver_models {

float float_depth_mrd(float z0, float z1, float z2) {
  // MAX3(fabs(...)) in double, the maximum stored back to a float exactly.
  const float most =
      float(std::max({std::fabs(double(z0)), std::fabs(double(z1)), std::fabs(double(z2))}));
  int32_t bits = int32_t(std::bit_cast<uint32_t>(most) & (0xffu << 23)) - (23 << 23);
  return std::bit_cast<float>(uint32_t(std::max(bits, 0)));
}

void offset_stage(const PolygonOffset& o, std::array<DrawVertex, 3>& v) {
  auto& v0 = v[0].window;
  auto& v1 = v[1].window;
  auto& v2 = v[2].window;
  // The cull stage's det = cross(e, f).z, e = v0 − v2, f = v1 − v2.
  const float ex = v0[0] - v2[0], ey = v0[1] - v2[1], ez = v0[2] - v2[2];
  const float fx = v1[0] - v2[0], fy = v1[1] - v2[1], fz = v1[2] - v2[2];
  const float det = ex * fy - ey * fx;
  const float inv_det = 1.0f / det;
  const float a = ey * fz - ez * fy;
  const float b = ez * fx - ex * fz;
  const float dzdx = std::fabs(a * inv_det), dzdy = std::fabs(b * inv_det);
  const float mult = (dzdx > dzdy ? dzdx : dzdy) * o.factor;  // MAX2: (a > b ? a : b)
  const float bias = o.units * float_depth_mrd(v0[2], v1[2], v2[2]);
  float zoffset = bias + mult;
  const float clamp = o.clamp.value_or(0.0f);
  if (clamp != 0.0f)
    zoffset = clamp < 0.0f ? (zoffset > clamp ? zoffset : clamp)   // MAX2
                           : (zoffset < clamp ? zoffset : clamp);  // MIN2
  // SATURATE(x): ((x) < 0.0f ? 0.0f : ((x) > 1.0f ? 1.0f : (x))).
  for (auto* p : {&v0, &v1, &v2}) {
    const float z = (*p)[2] + zoffset;
    (*p)[2] = z < 0.0f ? 0.0f : z > 1.0f ? 1.0f : z;
  }
}

}  // namespace glrc::driver_models
