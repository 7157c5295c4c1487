// Clipping against the view volume, without new vertices. x and y: -w_c <= x_c, y_c <= w_c is
// the viewport rectangle, whose edges never pass through a pixel centre, so it is the pixel
// range itself. w_c > 0: part of the homogeneous edge test (setup.hpp). What remains is the near
// and far planes, -w_c <= z_c <= w_c (0 <= z_c under glClipControl's GL_ZERO_TO_ONE,
// TriangleSetup::clip_depth), which are lines in window space: z_n is linear there.
#pragma once

#include "ref/exact.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

struct DepthClip {
  bool crosses_near = false, crosses_far = false;
  // >= 0 where the point of the triangle under the pixel centre has z_c >= -w_c (near) and
  // z_c <= w_c (far). Closed: a centre exactly on the plane is inside.
  SignEvaluator near, far;
  // Pixels per unit of z_n across each plane's line (1/|grad z_n|, in window pixels): how far
  // the line moves when z_n at it is off by one. 1 ± z_n is form / Σ E'_i·w_c,i, and that
  // denominator is constant over the window (homogeneous rasterization: w/w = 1), so a z_n
  // error ε moves the line by ε·scale pixels. 0 for a plane the triangle does not cross.
  double near_scale = 0, far_scale = 0;
};

DepthClip depth_clip(const TriangleSetup& t);

}  // namespace glrc::ref
