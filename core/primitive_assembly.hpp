// Primitive assembly: a case's draws as the independent triangles GL rasterizes, in the order
// GL draws them, numbered as gl_PrimitiveID counts them (OpenGL 4.6 sections 10.1.8-10.1.10,
// 10.3.6 and table 13.2 for the provoking vertex; GLSL 4.60 section 7.1 for gl_PrimitiveID).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/case.hpp"
#include "core/draw.hpp"

namespace glrc {

// One assembled triangle: its vertex indices in an order with the primitive's winding (facing)
// whose provoking vertex is the first (ProvokingVertex::first) or the last (::last), so that
// everything after assembly reads the triangle as it reads a GL_TRIANGLES one. For strips and
// fans these are the orders Mesa's draw module and llvmpipe's setup emit
// (draw_decompose_tmp.h, lp_setup_vbuf.c), which the bit-exact driver models need:
//   strip triangle i (vertices v_i, v_i+1, v_i+2), table 13.2's provoking vertex v_i+2 (last)
//   or v_i (first); odd i has the opposite winding of (v_i, v_i+1, v_i+2):
//     last:  even (v_i, v_i+1, v_i+2), odd (v_i+1, v_i, v_i+2)
//     first: even (v_i, v_i+1, v_i+2), odd (v_i, v_i+2, v_i+1)
//   fan triangle i (v_0, v_i+1, v_i+2), provoking v_i+2 (last) or v_i+1 (first; never v_0):
//     last:  (v_0, v_i+1, v_i+2)      first: (v_i+1, v_i+2, v_0)
// Each is a rotation or the odd reversal of GL's vertex order, so the winding is GL's.
struct AssembledTriangles {
  std::vector<std::array<uint32_t, 3>> triangles;
  // The triangle each draw's first primitive is (gl_PrimitiveID 0 of draw d is triangle
  // first_triangle[d]); one more entry, the total, at the end.
  std::vector<uint32_t> first_triangle;
  // Which kind of primitive each triangle is, for GL's invariance rule (identical_triangles):
  // 0 a GL_TRIANGLES triangle, 1 and 2 an even and odd strip triangle, 3 a fan triangle.
  std::vector<uint8_t> kind;
};

// The triangles of `draws` under the provoking-vertex convention `pv`. Every primitive counts,
// a degenerate one too; an incomplete one (fewer than 3 vertices since the start or the last
// restart, the 1 or 2 left over of a GL_TRIANGLES list) is dropped and not numbered.
// Primitive restart ends the primitive and starts a new one of the same mode; gl_PrimitiveID
// keeps counting across it ("Restarting a primitive topology using the primitive restart index
// has no effect on the primitive ID counter") and starts again at 0 with every draw, which is
// what first_triangle records. Indices are not checked against any vertex count here.
AssembledTriangles assemble(const std::vector<Draw>& draws, ProvokingVertex pv);

// The case's draws: Case::draws, or, for a case with none, the one glDrawElements(GL_TRIANGLES,
// GL_UNSIGNED_INT) of Case::triangles that every case drew before draws existed.
std::vector<Draw> draws_of(const Case& c);

// Sets c.triangles to the assembly of c.draws under c.provoking (nothing when c.draws is
// empty: c.triangles is then the case's own list). Whoever changes a case's draws or its
// provoking vertex calls it again.
void assemble_triangles(Case& c);

// Whether the case has more than one draw: gl_PrimitiveID then starts again at 0 with each, and
// the harness adds the draw's first triangle (a uniform) to make the frame's primitive the
// case's triangle number.
bool several_draws(const Case& c);

}  // namespace glrc
