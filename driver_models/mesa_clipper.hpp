// The draw module's pipeline stages that our state enables: draw_pipe_clip.c (the clipper)
// and draw_pipe_cull.c (face culling on float window positions). Both drivers share them.
#pragma once

#include <array>
#include <deque>
#include <vector>

#include "core/case.hpp"
#include "driver_models/draw_vertex.hpp"
#include "driver_models/viewport.hpp"

namespace glrc::driver_models {

struct ClipContext {
  ViewportXform viewport;
  bool flatshade_first = false;  // glProvokingVertex(GL_FIRST_VERTEX_CONVENTION)
  ClipDepth clip_depth = ClipDepth::negative_one_to_one;  // glClipControl: the near plane
  std::vector<Interpolation> interpolation;               // per component
};

using TriangleRefs = std::array<const DrawVertex*, 3>;

// do_clip_tri: clips the triangle against the planes in `clipmask` (lowest bit first) and
// emits the polygon as a fan in emit_poly's vertex order into `out`. New vertices live in
// `storage`. Nothing is emitted when the polygon vanishes or a plane distance is Inf/NaN.
void clip_triangle(const ClipContext& ctx, const TriangleRefs& tri, uint32_t clipmask,
                   std::deque<DrawVertex>& storage, std::vector<TriangleRefs>& out);

// cull_tri (draw_pipe_cull.c), its cull distances: whether no cull distance is out (below 0,
// or Inf or NaN: cull_distance_is_out) at all three vertices. Judged on the primitive before
// it is clipped: llvmpipe and softpipe draw a triangle whose clipped polygon has every
// distance negative while one of its own vertices' is not (cases/cull_distance_clipped_triangle
// .json, bit for bit), so the cull stage runs ahead of the clipper.
bool cull_distances_pass(const Case& c, const TriangleRefs& tri);

// cull_tri's face culling: whether draw's cull stage passes the triangle. det = cross(v0 - v2,
// v1 - v2) from float window positions; det == 0 counts as back facing.
bool cull_stage_passes(const Case& c, const TriangleRefs& tri);

}  // namespace glrc::driver_models
