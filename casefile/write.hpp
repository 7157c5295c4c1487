// Writing a Case as a case file (cases/README.md): the inverse of load() (casefile.hpp), for
// tools that make or reduce cases (a shrunk failure, a generated stress case) and want a file a
// person can read, diff and commit.
//
// Guarantee: for a Case that load() accepts, load() of the text, saved as <name>.json, gives a
// Case equal to it in every field the format has, every float bit for bit (-0.0, subnormals,
// FLT_MAX, 0.1f, ... included). The fields written: description, framebuffer and viewport
// (always, explicitly), depth_range, state, varyings and tolerance (only when they differ from
// the defaults), the vertices (always as `clip`: a loaded Case holds clip coordinates only; a
// size-1 varying as a bare number) and the triangles (always, explicitly). Not written: the name
// (a case's name is its file's stem) and source_path.
//
// Numbers. A float is a plain JSON number when its shortest decimal (std::to_chars) is exactly
// the float as a double (0.5, 3, -0.734375, 1024), so that the loader's double-then-float32
// reading is exact; otherwise (0.1f, 1e-30f, FLT_MAX, subnormals, -0.0) a JSON string holding
// that shortest decimal ("0.1", "-0.0"), which the loader reads with strtof in one rounding and
// which gives back the float by the shortest round-trip property; should a decimal ever not read
// back (it cannot with a correctly rounded strtof), a C99 hex string ("0x1.8p-3"), which is
// exact. Tolerance values (doubles, which the loader takes as JSON numbers only) are their
// shortest round-trip decimal ("-0.0" for a negative zero, which keeps its sign as a JSON float).
//
// Errors: none; the output is deterministic (same Case, same bytes). A Case the loader would
// refuse (more than 7 varyings, a bad name, a viewport outside the framebuffer, a non-finite
// float, vertex values not matching the varyings' sizes, ...) is written as it is, and loading
// the file says why.
#pragma once

#include <string>

#include "core/case.hpp"

namespace glrc::casefile {

// The text of a case file for `c`: a JSON object, one vertex per line, ending in a newline.
std::string to_case_file(const Case& c);

}  // namespace glrc::casefile
