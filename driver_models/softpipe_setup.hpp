// softpipe's triangle setup (sp_setup.c): vertices sorted by y, facing and culling from the
// float determinant, attribute coefficients from the sorted vertices, and the scanline spans
// that decide coverage. No snapping anywhere.
#pragma once

#include <vector>

#include "core/case.hpp"
#include "driver_models/draw_vertex.hpp"
#include "driver_models/llvmpipe_setup.hpp"  // Plane

namespace glrc::driver_models {

// One row of pixels [left, right) of the triangle, already clipped to the framebuffer.
struct Span {
  int y = 0, left = 0, right = 0;
};

struct SoftpipeTriangle {
  Plane z, w;                 // posCoef[2], posCoef[3]: window z and 1/w_c, linear
  std::vector<Plane> values;  // per component; flat: a0 only; smooth: planes of v/w
  std::vector<Span> spans;
  bool front_facing = true;  // the fragment shader's gl_FrontFacing
};

// sp_setup_tri up to the spans. False: dropped (1/area not finite, or culled).
bool softpipe_setup_triangle(const Case& c, const std::vector<Interpolation>& interpolation,
                             const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2,
                             SoftpipeTriangle& out);

}  // namespace glrc::driver_models
