// The shader_test's GLSL, embedded at build time by cmake/embed_text.cmake from export/glsl/:
// the vertex and fragment shaders with holes (export/text_template.hpp) that shader_test.cpp
// fills for a case.
#pragma once

#include <string_view>

namespace glrc::reproducer {

extern const std::string_view kShaderTestVertex;
extern const std::string_view kShaderTestFragment;

}  // namespace glrc::reproducer
