// Clipping against the view volume and the user clip planes, without new vertices. x and y:
// -w_c <= x_c, y_c <= w_c is the viewport rectangle, whose edges never pass through a pixel
// centre, so it is the pixel range itself. w_c > 0: part of the homogeneous edge test
// (setup.hpp). What remains is the near and far planes, -w_c <= z_c <= w_c (0 <= z_c under
// glClipControl's GL_ZERO_TO_ONE, TriangleSetup::clip_depth; neither under GL_DEPTH_CLAMP), and
// the enabled clip distances
// (OpenGL 4.6 section 13.7): each a quantity linear in clip space, so its zero is a line in
// window space and its sign at a pixel centre is exact.
#pragma once

#include <vector>

#include "ref/exact.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

// One plane that cuts the triangle (some vertex is outside it).
struct ClipPlane {
  // >= 0 where the point of the triangle under the pixel centre is inside (closed: a centre
  // exactly on the plane is inside).
  SignEvaluator sign;
  // Pixels per unit of d/w_c (d the plane's distance: 1 + z_n, 1 − z_n, z_n under
  // GL_ZERO_TO_ONE, or gl_ClipDistance/w_c) across the plane's line: how far the line moves
  // when d/w_c at it is off by one. d/w_c is form / Σ E'_i·w_c,i, and that denominator is
  // constant over the window (homogeneous rasterization: w/w = 1), so an error ε moves the
  // line by ε·scale pixels.
  double scale = 0;
};

// The planes that cut a triangle: near and far first, then the enabled clip distances, only
// those some vertex is outside of (most triangles: none, and no exact work).
struct ClipPlanes {
  std::vector<ClipPlane> planes;
  bool any() const { return !planes.empty(); }
};

ClipPlanes clip_planes(const TriangleSetup& t);

}  // namespace glrc::ref
