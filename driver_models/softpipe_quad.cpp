// Port of the fragment side of Mesa 22.3.6 softpipe: quads from sp_setup.c flush_spans (x0,
// y0 even), inputs from tgsi_exec.c (eval_linear_coef, eval_perspective_coef,
// eval_constant_coef) with W from sp_fs_exec.c setup_pos_vector, and depth from
// sp_quad_depth_test.c interpolate_quad_depth (not clamped: depth clip is on).
#include "driver_models/softpipe_quad.hpp"

#include "driver_models/viewport.hpp"

#include <algorithm>

namespace glrc::driver_models {
namespace {

// Quad pixel order f[0..3] = (x, y), (x+1, y), (x, y+1), (x+1, y+1):
// a0 + dadx*x + dady*y, then + dadx and/or + dady, left to right.
float quad_value(const Plane& p, float qx, float qy, bool right, bool top) {
  const float a = p.a0 + p.dadx * qx + p.dady * qy;
  if (right && top) return a + p.dadx + p.dady;
  if (right) return a + p.dadx;
  if (top) return a + p.dady;
  return a;
}

}  // namespace

float softpipe_fragment(const SoftpipeTriangle& t, const std::vector<Interpolation>& interp, int px,
                        int py, float* values, float* position) {
  const float qx = float(px & ~1), qy = float(py & ~1);
  const bool right = px & 1, top = py & 1;
  const float w = quad_value(t.w, qx, qy, right, top);
  for (size_t i = 0; i < interp.size(); ++i) {
    switch (interp[i]) {
      case Interpolation::flat:
        values[i] = t.values[i].a0;
        break;
      case Interpolation::noperspective:
        values[i] = quad_value(t.values[i], qx, qy, right, top);
        break;
      case Interpolation::smooth:
        values[i] = quad_value(t.values[i], qx, qy, right, top) / w;
        break;
    }
  }
  const float z = quad_value(t.z, qx, qy, right, top);
  if (position) position[0] = z, position[1] = w;  // setup_fragcoord_coeff: posCoef's z and w
  return z;
}

SoftpipeRasterizer::SoftpipeRasterizer(const Case& c, FrameWriter& writer)
    : case_(c),
      writer_(writer),
      interpolation_(component_interpolation(c)),
      values_(interpolation_.size()),
      builtins_(writes_builtins(c)) {
  // depth_test_quads_fallback: near_val = translate[2] − scale[2], far_val = near_val +
  // scale[2]·2.0 (in double, stored to a float), whichever way round; clip_halfz is not
  // looked at, so under GL_ZERO_TO_ONE the lower bound is 2n − f, not n.
  const ViewportXform vp = viewport_xform(c);
  const float near_val = vp.translate[2] - vp.scale[2];
  const float far_val = float(double(near_val) + double(vp.scale[2]) * 2.0);
  depth_bounds_ = {near_val < far_val ? near_val : far_val,
                   near_val < far_val ? far_val : near_val};
}

void SoftpipeRasterizer::triangle(const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2,
                                  int32_t primitive) {
  SoftpipeTriangle t;
  if (!softpipe_setup_triangle(case_, interpolation_, v0, v1, v2, t)) return;
  for (const Span& s : t.spans)
    for (int x = s.left; x < s.right; ++x) {
      float position[2];
      float depth = softpipe_fragment(t, interpolation_, x, s.y, values_.data(),
                                      builtins_ ? position : nullptr);
      // CLAMP(X, MIN, MAX): X > MIN ? (X > MAX ? MAX : X) : MIN (NaN gives the lower bound).
      if (case_.depth_clamp)
        depth = depth > depth_bounds_[0] ? (depth > depth_bounds_[1] ? depth_bounds_[1] : depth)
                                         : depth_bounds_[0];
      if (builtins_)
        write_builtins(case_, x, s.y, position[0], position[1], t.front_facing, values_.data());
      writer_.fragment(x, s.y, primitive, depth, values_.data());
    }
}

}  // namespace glrc::driver_models
