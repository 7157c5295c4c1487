// The C reproducer's runtime: export/c_runtime/declarations.c (GL, EGL and OSMesa declared by
// hand, and the scene a draw takes) and export/c_runtime/runtime.c (GL's context, the draw, the
// readback and the verdict), embedded at build time by cmake/embed_c_runtime.cmake. Every
// reproducer holds kCDeclarations, then the case's data (reproducer.cpp), then kCRuntime.
#pragma once

#include <string_view>

namespace glrc::reproducer {

extern const std::string_view kCDeclarations;
extern const std::string_view kCRuntime;

}  // namespace glrc::reproducer
