// Internal to gl_harness: the GLSL text of the programs the renderer draws a Case with. Pure
// string functions of a Case's varyings, with no GL call, so the text is tested without a
// context (tests/gl_shaders).
//
// The interface between the shaders, the vertex data and the framebuffer, which the renderer
// relies on:
//   vertex inputs:    location 0 `a_clip` (vec4, the case's clip coordinates, passed to
//                     gl_Position untouched); location k + 1 `a<k>`, varying k's components;
//                     location kDistanceLocation + i `a_distance<i>` (float), the vertex's
//                     distance i (Vertex::distances: the clip distances, then the cull
//                     distances), copied to gl_ClipDistance / gl_CullDistance;
//   varyings:         `v<k>` (vertex shader out), `g<k>` (geometry shader out), with varying
//                     k's qualifier (smooth, flat, noperspective) and type (float .. vec4);
//   fragment outputs: location k `o<k>` (vec4: varying k padded with zeros) for k < n, and
//                     location n `o_primitive` (int: gl_PrimitiveID), n = varyings.size().
// Names are generated rather than the case's: those are arbitrary strings and may collide
// with GLSL keywords. Every shader is `#version 330 core` (with GL_ARB_cull_distance where the
// case has cull distances).
#pragma once

#include <string>

#include "core/case.hpp"
#include "core/primitive_assembly.hpp"

namespace glrc::gl {

// The first vertex input location of the distances: after the 7 varyings' (1..7).
inline constexpr int kDistanceLocation = 8;

// The GLSL type of a varying of `size` components: "float", "vec2", "vec3", "vec4". Throws
// std::invalid_argument for a size outside 1..4 (the renderer rejects such a case first).
const char* glsl_type(int size);

// The GLSL interpolation qualifier: "smooth", "flat" or "noperspective".
const char* glsl_qualifier(Interpolation i);

// A built-in's redeclaration in the fragment shader (gl_FragCoord with its layout qualifiers,
// where it has any; else nothing), and the vec4 it writes to its attachment (gl_FragCoord;
// gl_FrontFacing as 1.0 or 0.0 in x).
std::string builtin_declaration(const Varying& v);
std::string builtin_value(const Varying& v);

// The key of the program cache: programs depend only on the varyings' sizes and qualifiers,
// never on names or values, so a run of many cases compiles few programs. E.g. "4smooth,1flat,"
// (every varying followed by a comma; "" for a case without varyings). Throws nothing.
std::string program_key(const Case& c);
// The part of a program key the distances make: "" without any, else e.g. "clip2cull1,".
std::string distances_key(const Distances& d);

// The vertex shader: a_clip to gl_Position, a<k> to v<k>. Throws std::invalid_argument for a
// varying size outside 1..4.
std::string vertex_shader_source(const Case& c);

// The pass-through geometry shader, only for a driver that needs one to supply gl_PrimitiveID
// (GlInfo::primitive_id_from_geometry_shader): each triangle's three vertices out unchanged, in
// order (v<k>[i] to g<k>, so the provoking vertex is the same one), gl_PrimitiveIDIn forwarded.
// Throws std::invalid_argument for a varying size outside 1..4.
std::string geometry_shader_source(const Case& c);

// The name of the uniform that holds the draw's first triangle (several_draws), declared.
extern const char* const kPrimitiveBase;

// The fragment shader: varying k to o<k>, gl_PrimitiveID to o_primitive (plus the uniform
// `primitive_base` for a case of several draws, core/primitive_assembly.hpp). It reads g<k> when
// `after_geometry_shader`, else v<k>. Throws std::invalid_argument for a varying size outside
// 1..4.
std::string fragment_shader_source(const Case& c, bool after_geometry_shader);

// The fragment-count pass's program, the same for every case with the same distances:
// positions (location 0 `a_clip`) and the distances (as vertex_shader_source has them), and
// every fragment writes 1.0 to location 0 `o_count`, which additive blending sums per pixel.
std::string count_vertex_shader_source(const Distances& d);
std::string count_fragment_shader_source();
// The fragment-trace pass's (drawn only where traces are asked, Renderer::fragment_traces, on a
// driver that needs the geometry shader for gl_PrimitiveID): the
// count pass's vertex shader, then every fragment writes its trace's terms, p + 1 and
// fragment_hash(p) for p = gl_PrimitiveID (core/fragment_trace.hpp), to location 0 `o_trace`,
// which additive blending sums per pixel; through count_geometry_shader_source's pass-through
// geometry shader where a driver needs one for gl_PrimitiveID
// (GlInfo::primitive_id_from_geometry_shader).
std::string count_geometry_shader_source(const Distances& d);
// With `primitive_base` (a case of several draws), p is gl_PrimitiveID + the uniform
// `primitive_base`, the draw's first triangle, as in fragment_shader_source.
std::string trace_fragment_shader_source(bool primitive_base = false);
// Both at once: 1.0 to location 0 `o_count`, the trace's terms to location 1 `o_trace` (where a
// driver needs no geometry shader for gl_PrimitiveID, the count pass sums both).
std::string count_and_trace_fragment_shader_source(bool primitive_base = false);

}  // namespace glrc::gl
