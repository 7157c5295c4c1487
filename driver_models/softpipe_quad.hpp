// softpipe's per-quad evaluation (tgsi_exec.c eval_*_coef, sp_fs_exec.c setup_pos_vector,
// sp_quad_depth_test.c) and the TriangleSink that runs setup, spans and quads.
#pragma once

#include <array>
#include <vector>

#include "core/case.hpp"
#include "driver_models/draw_vertex.hpp"
#include "driver_models/frame_writer.hpp"
#include "driver_models/softpipe_setup.hpp"

namespace glrc::driver_models {

// Values of pixel (px, py): evaluated at its 2x2 quad's top-left (even) pixel as
// a0 + dadx * x + dady * y, then dadx and dady added for the other three pixels; perspective
// inputs divided by the W plane evaluated the same way; `position`, where not null, gets the z
// and W planes' values (gl_FragCoord.zw, setup_fragcoord_coeff). Returns the (unclamped) depth.
float softpipe_fragment(const SoftpipeTriangle& t, const std::vector<Interpolation>& interp, int px,
                        int py, float* values, float* position);

class SoftpipeRasterizer final : public TriangleSink {
 public:
  SoftpipeRasterizer(const Case& c, FrameWriter& writer);
  void triangle(const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2,
                int32_t primitive) override;

 private:
  const Case& case_;
  FrameWriter& writer_;
  std::vector<Interpolation> interpolation_;
  std::vector<float> values_;
  bool builtins_;  // the case writes a built-in (write_builtins)
  // GL_DEPTH_CLAMP's {minval, maxval} (sp_quad_depth_test.c).
  std::array<float, 2> depth_bounds_{};
};

}  // namespace glrc::driver_models
