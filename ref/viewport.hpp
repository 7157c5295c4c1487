// Perspective divide and viewport transform, kept homogeneous: a vertex's window position is
// (x_h / w_c, y_h / w_c), which needs no divide until w_c > 0 is known, and stays linear in clip
// space so that clipping needs no new vertices.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/case.hpp"

namespace glrc::ref {

struct WindowVertex {
  mpq_class x_h, y_h;  // x_c·(w_v/2) + w_c·(x_v + w_v/2), likewise y: x_w = x_h / w_c
  mpq_class z_c, w_c;
  // w_c·z_w = z_c·(f−n)/2 + w_c·(n+f)/2: glDepthRange applied to z_n = z_c/w_c, times w_c
  // (z_c·(f−n) + w_c·n under GL_ZERO_TO_ONE). y_h reads y_c negated under GL_UPPER_LEFT.
  mpq_class wz_w;
  // The enabled user clip planes' gl_ClipDistance (Distances::plane_enabled), in plane order;
  // empty for a case without. Linear in clip space as x_h, y_h and w_c are.
  std::vector<mpq_class> clip_distances;
};

WindowVertex to_window(const Vertex& v, const Case& c);

// z_w of a vertex with w_c > 0: the depth-range mapping of its z_n.
inline mpq_class z_w(const WindowVertex& v) {
  return v.wz_w / v.w_c;
}

// A vertex's window position (x_w, y_w) in double, for w_c > 0 (GL_UPPER_LEFT's y_c negated):
// it places bounds, bands and freedoms, never a bit of a value (exactly, x_w = x_h / w_c).
inline std::array<double, 2> approximate_window(const Case& c, const std::array<float, 4>& clip) {
  const Viewport& vp = c.viewport;
  return {vp.x + vp.width / 2.0 * (1 + double(clip[0]) / clip[3]),
          vp.y + vp.height / 2.0 * (1 + window_y_c(c, clip[1]) / clip[3])};
}

// z_w for a normalized depth z_n = z_c / w_c in double (glDepthRange's mapping, glClipControl's
// GL_ZERO_TO_ONE included), unclamped: like approximate_window, never a bit of a value.
inline double approximate_depth(const Case& c, double z_n) {
  const double n = c.depth_near, f = c.depth_far;
  return c.clip_depth == ClipDepth::zero_to_one ? n + z_n * (f - n)
                                                : (n + f) / 2 + z_n * (f - n) / 2;
}

// GL interprets a viewport's bounds to GL_VIEWPORT_SUBPIXEL_BITS of precision (OpenGL 4.6
// section 13.6.1: glViewportIndexedf's floats), rounded any way. Taken at GL's least, 0, which
// is what llvmpipe, softpipe and zink report (Mesa 22.3.6 and 25.0.7): a fractional viewport
// may be drawn as a whole-pixel one. Not covered: a driver reporting more is held to no more
// than that.
inline constexpr int kViewportSubpixelBits = 0;

// How far each bound of the viewport may be from what an implementation takes, pixels (less
// than that): 0 for a viewport whose bounds lie on the 2^-kViewportSubpixelBits grid
// (glViewport's whole numbers), else one step of that grid.
double viewport_step(const Viewport& vp);

// How far the viewport's precision may move the window point (x_w, y_w), pixels in x and in y:
// each bound by less than a step, x' = x + Δx, w' = w + Δw, so x_w by Δx + Δw·(x_w - x)/w,
// below step·(1 + |x_w - x|/w) (likewise y; the larger). One transform for every vertex: it
// moves edges and values, never turns a triangle over.
double viewport_shift(const Viewport& vp, double x_w, double y_w);

// How far the centre of pixel (px, py) is from the nearest side of the viewport, pixels.
// Always inlined: once per pixel of a clipped triangle, into FragmentBlocks' AVX2 copy too
// (GCC does not inline a function of the default target into a target_clones copy unasked).
[[gnu::always_inline]] inline double viewport_side_distance(const Viewport& vp, int px, int py) {
  const double x = px + 0.5, y = py + 0.5;
  return std::min({x - vp.x, double(vp.x) + vp.width - x, y - vp.y, double(vp.y) + vp.height - y});
}

}  // namespace glrc::ref
