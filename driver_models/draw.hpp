// Mesa's draw module front end as our harness exercises it: vertex processing, the vsplit
// segments of an indexed GL_TRIANGLES draw, and the choice between emitting triangles straight
// to the driver and running them through the clip (and cull) pipeline.
#pragma once

#include "core/case.hpp"
#include "driver_models/draw_vertex.hpp"
#include "driver_models/viewport.hpp"

namespace glrc::driver_models {

enum class VertexPath {
  llvm,  // llvmpipe: draw_llvm's JIT vertex shader computes the viewport (fmuladd)
  c,     // softpipe: draw_pt_post_vs_run's C viewport after the geometry shader
};

struct DrawConfig {
  VertexPath path = VertexPath::c;
  bool fma = false;  // VertexPath::llvm only
  // The pipeline's offset stage (draw_pipe_offset.c) applies a polygon offset: softpipe's
  // (llvmpipe offsets in its own setup and keeps the stage off).
  bool offset_stage = false;
};

// Draws every triangle of the case into `sink`, in the order the driver's setup sees them.
void run_draw(const Case& c, const DrawConfig& config, TriangleSink& sink);

}  // namespace glrc::driver_models
