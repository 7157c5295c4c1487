// Reproducers: one case, its GL draw and its expectation, written out as a single C file that a
// driver developer builds with a C compiler alone (`glrefcheck export CASE --format c`), runs
// on Mesa without glrefcheck, and attaches to a bug report.
//
// The C file draws the case exactly as gl_harness/ does (the harness's own GLSL, clip
// coordinates to gl_Position untouched, one RGBA32F attachment per varying, an R32I
// gl_PrimitiveID attachment, 32-bit float depth, the case's states, then the fragment-count pass
// with additive blending into R32F without the depth test, and the fragment-trace pass beside
// it), reads the frame back with glReadPixels, and judges every pixel as compare/ does. It
// restates none of compare/'s rules: coverage is the label the embedded verdict table
// (coverage_verdict_table.hpp, computed with compare::coverage_verdict) gives for the pixel's
// edge bits and what GL kept, counted and traced there; depth and every component are judged
// where GL's primitive is the reference's (or a depth-test candidate's), within the embedded
// allowance. It does not compute
// statistics (ULPs, percentiles), does not mark a case outside GL's specified range as a skip
// (it says so in a note and still fails), and draws the whole frame at once.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"
#include "core/fragment_trace.hpp"
#include "export/coverage_verdict_table.hpp"

namespace glrc::reproducer {

// The first characters of every C reproducer (its first line): `export --out` replaces only a
// file that holds them.
inline constexpr const char* kCReproducerSignature = "/* glrefcheck reproducer";

// A reproducer embeds every pixel of the frame: at most this many pixel values.
inline constexpr size_t kMaxReproducerValues = 400000;
// The pixel values a reproducer of `c` embeds: per pixel its primitive, fragment count, depth
// and each varying component (the frame's channels, check::frame_bytes / 4).
size_t reproducer_values(const Case& c);

// The GLSL the harness draws one case with (gl_harness/shaders.hpp): without and with the
// pass-through geometry shader that supplies gl_PrimitiveID where a driver needs one.
struct ReproducerShaders {
  std::string vertex, geometry, fragment, fragment_after_geometry;
  // The fragment-count pass's vertex and pass-through geometry shaders: the scene's own, as
  // they write its distances (gl::count_vertex_shader_source).
  std::string count_vertex, count_geometry;
};

// What the C file needs besides the case and its expectation. The caller (cli/export.cpp) takes
// the shaders and the first draw from gl_harness/, so that the reproducer draws what the harness
// draws; this module knows no GL.
struct CReproducerSetup {
  ReproducerShaders shaders;  // the case's
  // The harness's first draw (gl_harness/first_draw.hpp: one triangle over a 4x4 framebuffer,
  // one flat float of 1, primitive 0 and value 1 expected everywhere) and its shaders: drawn
  // first, plain and, when that is wrong, with the geometry shader, to choose as the harness
  // chooses.
  Case first_draw;
  ReproducerShaders first_draw_shaders;
  std::string count_fragment;  // the fragment-count pass's
  std::string trace_fragment;  // the fragment-trace pass's
  // Where the edge bits may excuse coverage, the traces a conforming implementation may give
  // (admitted() of ref::fragment_choices there), sorted by pixel: the C file judges GL's trace
  // against them as compare/ does (compare::TraceSource). A pixel not listed is not judged.
  std::vector<AdmittedTraces> admitted;
  std::string file_name;    // the .c file's name, for its compile line
  std::string exported_by;  // the command that wrote it, for the header
  std::string model;        // words for the model the expectation is of
};

// `cc -std=c99 -O2 -o NAME NAME.c -ldl -lm` for a C file `file` ending in ".c" (quoted for a
// POSIX shell where needed): how the header, and `export`, say to build it.
std::string c_compile_command(const std::string& file);
// The program c_compile_command builds, as a shell runs it ("./NAME" for a name without a
// folder; quoted where needed).
std::string c_run_command(const std::string& file);

// A case's coverage verdict as C data, as every reproducer embeds it after kCVerdict
// (export/c_runtime/verdict.c): COVERAGE_VERDICT (a verdict_row per value of the edge bits, the
// labels numbered as label_code numbers them) and LABEL_FAILS (per label code, 1 where it fails
// the case).
std::string c_verdict_table(const CoverageVerdictTable& table);

// The C99 text of a reproducer of case `c`.
//   c:         a valid case (casefile::load's), at most kMaxReproducerValues pixel values;
//   expected:  check::expectation_for(c, ...) without a driver model: the exact frame (window
//              coordinates, row 0 at the bottom), edge bits, the allowance per pixel and channel
//              (value units, absolute; needed for ToleranceMode::spec) and the depth-test
//              candidates, sorted by pixel;
//   tolerance: check::tolerance_for(c, ...): spec (the per-pixel allowance) or ulps (fixed
//              thresholds in ULPs of each attribute's scale, depth in ULPs of 1.0, flat 0), and
//              whether coverage differences the freedom explains pass (allow_boundary);
//   setup:     as above.
// Every float (vertex data, reference values, allowances) is written as a C99 hexadecimal
// literal, exactly; a NaN or infinite reference value (where the specification determines no
// value) as NAN or INFINITY, and not judged. Throws std::invalid_argument for a case beyond
// kMaxReproducerValues, an expectation not of that case's shape (frame size, components, edge
// bits, or no allowance under spec), or ToleranceMode::exact (bit-for-bit judging of a driver
// model, which a reproducer does not do).
std::string c_reproducer(const Case& c, const Expectation& expected, const Tolerance& tolerance,
                         const CReproducerSetup& setup);

}  // namespace glrc::reproducer
