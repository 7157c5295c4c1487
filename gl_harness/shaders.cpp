// The GLSL text the renderer draws with (shaders.hpp). Only rasterization and interpolation
// are under test, so the shaders do nothing else: clip coordinates in, varyings and
// gl_PrimitiveID out.
#include "gl_harness/shaders.hpp"

#include <stdexcept>

namespace glrc::gl {

const char* const kPrimitiveBase = "uniform int primitive_base;\n";

const char* glsl_type(int size) {
  static const char* const kTypes[] = {"float", "vec2", "vec3", "vec4"};
  // The index below would read past the table; the renderer validates sizes first, but these
  // functions are called on their own too.
  if (size < 1 || size > 4)
    throw std::invalid_argument("varying size " + std::to_string(size) + " outside 1..4");
  return kTypes[size - 1];
}

const char* glsl_qualifier(Interpolation i) {
  switch (i) {
    case Interpolation::smooth:
      return "smooth";
    case Interpolation::flat:
      return "flat";
    case Interpolation::noperspective:
      return "noperspective";
  }
  return "smooth";
}

std::string program_key(const Case& c) {
  std::string key = several_draws(c) ? "base," : "";
  for (const Varying& v : c.varyings)
    key += v.is_builtin() ? std::string(name_of(v.builtin)) + builtin_declaration(v) + ","
                          : std::to_string(v.size) + glsl_qualifier(v.interpolation) + ",";
  return key + distances_key(c.distances);
}

std::string builtin_declaration(const Varying& v) {
  return v.builtin == Builtin::frag_coord ? frag_coord_redeclaration(v.layout) : "";
}

std::string builtin_value(const Varying& v) {
  return v.builtin == Builtin::frag_coord ? "gl_FragCoord"
                                          : "vec4(gl_FrontFacing ? 1.0 : 0.0, 0.0, 0.0, 0.0)";
}

std::string distances_key(const Distances& d) {
  return d.any() ? "clip" + std::to_string(d.clip) + "cull" + std::to_string(d.cull) + "," : "";
}

namespace {

// The version line, and the cull distance extension where the shader writes or reads
// gl_CullDistance (a built-in of GLSL 4.50 only).
std::string version_line(const Distances& d) {
  return d.cull > 0 ? "#version 330 core\n#extension GL_ARB_cull_distance : require\n"
                    : "#version 330 core\n";
}

// The redeclared gl_ClipDistance / gl_CullDistance outputs, sized as the case writes them.
std::string distance_outputs(const Distances& d) {
  std::string s;
  if (d.clip) s += "out float gl_ClipDistance[" + std::to_string(d.clip) + "];\n";
  if (d.cull) s += "out float gl_CullDistance[" + std::to_string(d.cull) + "];\n";
  return s;
}
// The vertex shader's distance inputs and the outputs, and the statements that copy one to the
// other.
std::string distance_declarations(const Distances& d) {
  std::string s;
  for (int i = 0; i < d.clip + d.cull; ++i)
    s += "layout(location = " + std::to_string(kDistanceLocation + i) + ") in float a_distance" +
         std::to_string(i) + ";\n";
  return s + distance_outputs(d);
}
std::string distance_statements(const Distances& d) {
  std::string s;
  for (int i = 0; i < d.clip; ++i)
    s += "  gl_ClipDistance[" + std::to_string(i) + "] = a_distance" + std::to_string(i) + ";\n";
  for (int i = 0; i < d.cull; ++i)
    s += "  gl_CullDistance[" + std::to_string(i) + "] = a_distance" + std::to_string(d.clip + i) +
         ";\n";
  return s;
}
// A geometry shader's: each vertex's distances copied from gl_in[i] to the outputs.
std::string geometry_distance_statements(const Distances& d) {
  std::string s;
  for (int i = 0; i < d.clip; ++i)
    s += "    gl_ClipDistance[" + std::to_string(i) + "] = gl_in[i].gl_ClipDistance[" +
         std::to_string(i) + "];\n";
  for (int i = 0; i < d.cull; ++i)
    s += "    gl_CullDistance[" + std::to_string(i) + "] = gl_in[i].gl_CullDistance[" +
         std::to_string(i) + "];\n";
  return s;
}

}  // namespace

std::string vertex_shader_source(const Case& c) {
  std::string s = version_line(c.distances) + "layout(location = 0) in vec4 a_clip;\n" +
                  distance_declarations(c.distances);
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    const Varying& v = c.varyings[k];
    if (v.is_builtin()) continue;  // the fragment shader's own input
    std::string n = std::to_string(k);
    s += "layout(location = " + std::to_string(k + 1) + ") in " + glsl_type(v.size) + " a" + n +
         ";\n";
    s += std::string(glsl_qualifier(v.interpolation)) + " out " + glsl_type(v.size) + " v" + n +
         ";\n";
  }
  // Clip coordinates pass through untouched: the reference sees the very same bits.
  s += "void main() {\n  gl_Position = a_clip;\n" + distance_statements(c.distances);
  for (size_t k = 0; k < c.varyings.size(); ++k)
    if (!c.varyings[k].is_builtin())
      s += "  v" + std::to_string(k) + " = a" + std::to_string(k) + ";\n";
  return s + "}\n";
}

// One triangle in, the same triangle out, vertex order kept: the provoking vertex of a flat
// varying stays the one the reference takes.
std::string geometry_shader_source(const Case& c) {
  std::string s = version_line(c.distances) +
                  "layout(triangles) in;\n"
                  "layout(triangle_strip, max_vertices = 3) out;\n" +
                  distance_outputs(c.distances);
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    const Varying& v = c.varyings[k];
    if (v.is_builtin()) continue;
    std::string q = std::string(glsl_qualifier(v.interpolation)) + " ";
    std::string n = std::to_string(k);
    s += q + "in " + glsl_type(v.size) + " v" + n + "[];\n";
    s += q + "out " + glsl_type(v.size) + " g" + n + ";\n";
  }
  s += "void main() {\n  for (int i = 0; i < 3; ++i) {\n";
  s += "    gl_Position = gl_in[i].gl_Position;\n    gl_PrimitiveID = gl_PrimitiveIDIn;\n" +
       geometry_distance_statements(c.distances);
  for (size_t k = 0; k < c.varyings.size(); ++k)
    if (!c.varyings[k].is_builtin())
      s += "    g" + std::to_string(k) + " = v" + std::to_string(k) + "[i];\n";
  return s + "    EmitVertex();\n  }\n  EndPrimitive();\n}\n";
}

std::string fragment_shader_source(const Case& c, bool after_geometry_shader) {
  // Every attachment is RGBA32F, whatever the varying's size: the unused components are 0.
  static const char* const kPad[] = {", 0.0, 0.0, 0.0", ", 0.0, 0.0", ", 0.0", ""};
  const char* const input = after_geometry_shader ? "g" : "v";
  std::string s = "#version 330 core\n";
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    const Varying& v = c.varyings[k];
    std::string n = std::to_string(k);
    if (v.is_builtin())
      s += builtin_declaration(v);
    else
      s += std::string(glsl_qualifier(v.interpolation)) + " in " + glsl_type(v.size) + " " + input +
           n + ";\n";
    s += "layout(location = " + n + ") out vec4 o" + n + ";\n";
  }
  s += "layout(location = " + std::to_string(c.varyings.size()) + ") out int o_primitive;\n";
  if (several_draws(c)) s += kPrimitiveBase;
  s += "void main() {\n";
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    std::string n = std::to_string(k);
    if (c.varyings[k].is_builtin())
      s += "  o" + n + " = " + builtin_value(c.varyings[k]) + ";\n";
    else
      s += "  o" + n + " = vec4(" + input + n + kPad[c.varyings[k].size - 1] + ");\n";
  }
  // Without a geometry shader gl_PrimitiveID counts the draw's triangles from 0: the
  // reference's primitive id. The pass-through one forwards that same count. With several
  // draws each starts again at 0; the draw's first triangle added makes it the case's number.
  s += several_draws(c) ? "  o_primitive = gl_PrimitiveID + primitive_base;\n}\n"
                        : "  o_primitive = gl_PrimitiveID;\n}\n";
  return s;
}

std::string count_vertex_shader_source(const Distances& d) {
  if (!d.any())
    return "#version 330 core\n"
           "layout(location = 0) in vec4 a_clip;\n"
           "void main() { gl_Position = a_clip; }\n";
  return version_line(d) + "layout(location = 0) in vec4 a_clip;\n" + distance_declarations(d) +
         "void main() {\n  gl_Position = a_clip;\n" + distance_statements(d) + "}\n";
}

std::string count_geometry_shader_source(const Distances& d) {
  return version_line(d) +
         "layout(triangles) in;\n"
         "layout(triangle_strip, max_vertices = 3) out;\n" +
         distance_outputs(d) +
         "void main() {\n"
         "  for (int i = 0; i < 3; ++i) {\n"
         "    gl_Position = gl_in[i].gl_Position;\n"
         "    gl_PrimitiveID = gl_PrimitiveIDIn;\n" +
         geometry_distance_statements(d) +
         "    EmitVertex();\n"
         "  }\n"
         "  EndPrimitive();\n"
         "}\n";
}

std::string count_fragment_shader_source() {
  return "#version 330 core\n"
         "layout(location = 0) out float o_count;\n"
         "void main() { o_count = 1.0; }\n";
}

namespace {

// fragment_hash (core/fragment_trace.hpp) in uint arithmetic, which wraps modulo 2^32, and the
// trace's terms: both integers below 2^24, exact in float32.
// p is gl_PrimitiveID, plus primitive_base where the case has several draws.
std::string trace_terms(bool primitive_base) {
  const std::string p = primitive_base ? "(gl_PrimitiveID + primitive_base)" : "gl_PrimitiveID";
  return std::string(primitive_base ? kPrimitiveBase : "") +
         "vec2 trace_terms() {\n"
         "  uint x = uint(" +
         p +
         ");\n"
         "  x ^= x >> 16u;\n"
         "  x *= 0x7feb352du;\n"
         "  x ^= x >> 15u;\n"
         "  x *= 0x846ca68bu;\n"
         "  x ^= x >> 16u;\n"
         "  return vec2(float(" +
         p +
         " + 1), float((x >> 20u) + 1u));\n"
         "}\n";
}

}  // namespace

std::string trace_fragment_shader_source(bool primitive_base) {
  return std::string(
             "#version 330 core\n"
             "layout(location = 0) out vec2 o_trace;\n") +
         trace_terms(primitive_base) + "void main() { o_trace = trace_terms(); }\n";
}

std::string count_and_trace_fragment_shader_source(bool primitive_base) {
  return std::string(
             "#version 330 core\n"
             "layout(location = 0) out float o_count;\n"
             "layout(location = 1) out vec2 o_trace;\n") +
         trace_terms(primitive_base) +
         "void main() {\n  o_count = 1.0;\n  o_trace = trace_terms();\n}\n";
}

}  // namespace glrc::gl
