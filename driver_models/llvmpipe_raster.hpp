// llvmpipe's coverage (edge setup in lp_setup_tri.c, tests in lp_rast_tri_tmp.h) and the
// TriangleSink that puts setup, coverage and fragment evaluation together.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/case.hpp"
#include "driver_models/draw_vertex.hpp"
#include "driver_models/frame_writer.hpp"
#include "driver_models/llvmpipe_setup.hpp"

namespace glrc::driver_models {

// Three half-edge functions in fixed point and the pixel rectangle worth testing (the
// triangle's bounding box clipped to the framebuffer: draw_regions without scissor), for the
// triangles llvmpipe's 32-bit rasterizers draw (boxes up to 128 px), where nothing wraps.
struct LlvmpipeEdges {
  std::array<int64_t, 3> c{};
  std::array<int64_t, 3> dcdx{}, dcdy{};  // already scaled by FIXED_ONE
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;   // inclusive
};

// The edges, and the box of pixels they may accept within `region` (the draw region).
LlvmpipeEdges llvmpipe_edges(const LlvmpipeTriangle& t, const PixelRect& region);

// c + dcdy * py - dcdx * px - 1 >= 0 for all three edges (the "- 1" and the +1 bias on
// left/bottom edges in llvmpipe_edges make the fill convention).
inline bool llvmpipe_covers(const LlvmpipeEdges& e, int px, int py) {
  for (int i = 0; i < 3; ++i)
    if (e.c[i] + e.dcdy[i] * py - e.dcdx[i] * px - 1 < 0) return false;
  return true;
}

// Calls covered(px, py) once for each framebuffer pixel llvmpipe shades for the triangle:
// do_triangle_ccw's bounding box and planes, lp_setup_bin_triangle's tiles, and the
// hierarchical tests of the rasterizer it picks. Wherever no 32-bit value wraps this is the
// plain edge test of llvmpipe_covers; a vertex far outside (a NaN window position snaps to
// INT32_MIN) wraps the edge steps and covers what the blocks' sign tests say.
// `draw_region` is setup's draw region: the framebuffer, within the scissor box when the
// scissor test is on (scissor_region), whose sides crossing the box become planes.
void llvmpipe_coverage(const LlvmpipeTriangle& t, int fb_width, int fb_height,
                       const PixelRect& draw_region, const std::function<void(int, int)>& covered);

// The fragment shader's inputs and depth at pixel (px, py) (lp_bld_interp.c,
// attribs_update_simple; lp_state_fs.c, lp_build_depth_clamp): `values` gets one float per
// component; `position`, where not null, the position input's z and w (gl_FragCoord.zw: the
// planes of window z and 1/w_c, as evaluated); returns the depth as tested and written.
float llvmpipe_fragment(const LlvmpipeCoefficients& k, const std::vector<Interpolation>& interp,
                        int px, int py, bool fma, float* values, float* position);
// GL_DEPTH_CLAMP's bounds {min_depth, max_depth} (lp_setup.c, util_viewport_zmin_zmax) and the
// clamp lp_build_depth_clamp takes the depth to with them, after llvmpipe_fragment's [0, 1].
std::array<float, 2> llvmpipe_depth_bounds(const Case& c);
float llvmpipe_depth_clamp(float z, const std::array<float, 2>& bounds);

class LlvmpipeRasterizer final : public TriangleSink {
 public:
  LlvmpipeRasterizer(const Case& c, bool fma, FrameWriter& writer);
  void triangle(const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2,
                int32_t primitive) override;

 private:
  const Case& case_;
  bool fma_;
  FrameWriter& writer_;
  std::vector<Interpolation> interpolation_;
  std::vector<float> values_;
  bool builtins_;  // the case writes a built-in (write_builtins)
};

}  // namespace glrc::driver_models
