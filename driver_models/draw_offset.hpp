// Polygon offset as Mesa's draw module computes it: the pipeline's offset stage
// (draw_pipe_offset.c), which softpipe uses, and the 32F minimum resolvable difference that
// stage and llvmpipe's setup (lp_state_setup.c lp_do_offset_tri) share.
#pragma once

#include <array>

#include "core/case.hpp"
#include "driver_models/draw_vertex.hpp"

namespace glrc::driver_models {

// do_offset_tri (draw_pipe_offset.c), a 32F depth buffer (floating_point_depth): from the
// piece's float window positions, dzdx and dzdy over the cull stage's det, MAX2 of them times
// the factor, plus units·2^(exponent of the largest |z| − 23) (0 below 2^-103), clamped by
// glPolygonOffsetClamp's clamp; then added to each vertex's z and saturated to [0, 1], per
// vertex ("Ideally, the offset is applied per-fragment", says Mesa): a vertex pushed past 0
// or 1 tilts the piece's depth plane.
void offset_stage(const PolygonOffset& o, std::array<DrawVertex, 3>& v);

// The 32F minimum resolvable difference both drivers compute from the largest |z| of a
// triangle's vertices: its exponent's bits less 23 << 23, taken as a float (0 when that is
// not positive).
float float_depth_mrd(float z0, float z1, float z2);

}  // namespace glrc::driver_models
