// Port of the edge setup of Mesa 22.3.6 lp_setup_tri.c (do_triangle_ccw: bounding box, plane
// c/dcdx/dcdy with the fill-convention bias) and the pixel test of lp_rast_tri_tmp.h.
#include "driver_models/llvmpipe_raster.hpp"

#include <algorithm>

namespace glrc::driver_models {

LlvmpipeEdges llvmpipe_edges(const LlvmpipeTriangle& t, int fb_width, int fb_height) {
  LlvmpipeEdges e;
  // Edge i runs from vertex i to vertex i+1: dcdx = y_i - y_j, dcdy = x_i - x_j,
  // c = dcdx * x_i - dcdy * y_i.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const int64_t dcdx = int64_t(t.y[i]) - t.y[j];
    const int64_t dcdy = int64_t(t.x[i]) - t.x[j];
    int64_t c = dcdx * t.x[i] - dcdy * t.y[i];
    // Fill convention for a y-up FBO (bottom_edge_rule 0): left edges (dcdx < 0) and
    // horizontal edges with dcdy >= 0 include their pixel centres (the SSE path's c_dec).
    if (dcdx < 0 || (dcdx == 0 && dcdy >= 0)) ++c;
    e.c[i] = c;
    e.dcdx[i] = dcdx * (1 << kLlvmpipeFixedOrder);
    e.dcdy[i] = dcdy * (1 << kLlvmpipeFixedOrder);
  }
  // The bounding box only picks the 64x64 tiles the triangle is binned to; inside them the
  // edge functions alone decide (plus the framebuffer edges as scissor planes). A box one
  // pixel wider than the snapped vertices holds every pixel the edges can accept.
  const int32_t min_x = std::min({t.x[0], t.x[1], t.x[2]});
  const int32_t max_x = std::max({t.x[0], t.x[1], t.x[2]});
  const int32_t min_y = std::min({t.y[0], t.y[1], t.y[2]});
  const int32_t max_y = std::max({t.y[0], t.y[1], t.y[2]});
  e.x0 = std::max((min_x >> kLlvmpipeFixedOrder) - 1, 0);
  e.x1 = std::min((max_x >> kLlvmpipeFixedOrder) + 1, fb_width - 1);
  e.y0 = std::max((min_y >> kLlvmpipeFixedOrder) - 1, 0);
  e.y1 = std::min((max_y >> kLlvmpipeFixedOrder) + 1, fb_height - 1);
  return e;
}

LlvmpipeRasterizer::LlvmpipeRasterizer(const Case& c, bool fma, FrameWriter& writer)
    : case_(c),
      fma_(fma),
      writer_(writer),
      interpolation_(component_interpolation(c)),
      values_(interpolation_.size()) {}

void LlvmpipeRasterizer::triangle(const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2,
                                  int32_t primitive) {
  LlvmpipeTriangle t;
  if (!llvmpipe_setup_triangle(case_, v0, v1, v2, t)) return;
  const LlvmpipeEdges e = llvmpipe_edges(t, case_.fb_width, case_.fb_height);
  if (e.x0 > e.x1 || e.y0 > e.y1) return;
  const LlvmpipeCoefficients k =
      llvmpipe_coefficients(t, interpolation_, case_.provoking == ProvokingVertex::first);
  for (int py = e.y0; py <= e.y1; ++py)
    for (int px = e.x0; px <= e.x1; ++px) {
      if (!llvmpipe_covers(e, px, py)) continue;
      const float depth = llvmpipe_fragment(k, interpolation_, px, py, fma_, values_.data());
      writer_.fragment(px, py, primitive, depth, values_.data());
    }
}

}  // namespace glrc::driver_models
