// The C reproducer's runtime, embedded at build time by cmake/embed_text.cmake:
// export/c_runtime/declarations.c (GL, EGL and OSMesa declared by hand, and the scene a draw
// takes), export/c_runtime/verdict.c (a pixel's coverage label looked up in the verdict table a
// reproducer embeds: export/coverage_verdict_table.hpp) and export/c_runtime/runtime.c (GL's
// context, the draw, the readback and the judging). Every reproducer holds kCDeclarations, the
// case's size, kCVerdict, the case's data (reproducer.cpp), then kCRuntime.
#pragma once

#include <string_view>

namespace glrc::reproducer {

extern const std::string_view kCDeclarations;
extern const std::string_view kCVerdict;
extern const std::string_view kCRuntime;

}  // namespace glrc::reproducer
