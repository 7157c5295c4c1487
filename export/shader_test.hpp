// piglit shader_test reproducers: one case as a file that piglit's shader_runner runs
// (`glrefcheck export CASE --format shader_test`), which fails on a driver that draws the case
// wrong and passes on a correct one, for a Mesa developer to run beside piglit's own tests.
//
// What shader_runner can do decides the design (piglit 0~git20220119, Debian 12's; its [test]
// commands were read in tests/shaders/shader_runner.c):
//   - It has no glBlendFunc, so fragments cannot be counted by additive blending as the GL
//     harness does; no glCullFace or glFrontFace, and its `enable` takes no GL_CULL_FACE (only
//     clip planes, GL_DEPTH_TEST, GL_DEPTH_CLAMP and two others); no glDepthRange; and
//     glViewport only as `viewport indexed 0 x y w h` (ARB_viewport_array). So culling is done
//     in the fragment shader (discard by gl_FrontFacing, which is what culling draws, though not
//     the driver's culling itself), and a case whose states need more is refused
//     (shader_test_refusal): a depth range other than [0, 1], culling of every triangle (the
//     shader would use no varying), culling with a depth test (a discard cannot undo the
//     depth write of the early depth test below), a depth test against a clear value other
//     than 0 or 1 (its 24-bit depth buffer holds no other exactly), or a polygon offset (it has
//     no glPolygonOffset or glPolygonOffsetClamp, and its `enable` takes no
//     GL_POLYGON_OFFSET_FILL). GL_DEPTH_CLAMP is its `enable GL_DEPTH_CLAMP`; the depth judged is
//     then gl_FragCoord.z clamped to [0, 1], as the depth buffer the harness reads takes it.
//   - Its probes compare colours read back with glReadPixels, within a `tolerance`, one pixel
//     or one rectangle per line; NaN passes them (|NaN - e| > tolerance is false), and the only
//     way to hand a shader per-pixel data is text: constant arrays in the GLSL, one uniform per
//     line, one storage-buffer word per line. Its framebuffer (-fbo) is RGBA8 with a 24-bit
//     depth buffer (with `depthbuffer` in [require]); `fb tex 2d N` renders into a texture
//     without a depth buffer.
// So the judging happens on the GPU and the probes read its verdict:
//   1. The case is drawn once, as the harness draws it: clip coordinates to gl_Position
//      untouched, every varying with its qualifier and type, the case's viewport, provoking
//      vertex, culling and depth test (`depthfunc GL_LESS` on the 24-bit depth buffer, with
//      early fragment tests so that only fragments that pass it run the shader; GL_ALWAYS is
//      no depth test at all). The triangles are de-indexed (draw arrays, three rows of vertex
//      data per triangle) and carry their index as a flat int attribute, instead of
//      gl_PrimitiveID, which softpipe does not give without a geometry shader.
//   2. Its fragment shader judges each fragment's values, as compare/ does: depth
//      (gl_FragCoord.z) and every component, NaN or Inf never passing; at a bounded list of
//      (pixel, triangle) pairs also the stated range [lo, hi], the float32 values v with
//      |v - reference| <= the allowance (exactly the values `run` accepts there). It adds 1 to
//      the pixel's fragment count and keeps max((triangle + 1) * 4 + verdict) with atomics on
//      a storage buffer (ARB_shader_storage_buffer_object): the last fragment drawn, or with
//      GL_LESS the last that passed, is the one with the highest triangle index, so the pixel's
//      kept triangle and its verdict come out of the max whatever order the shader
//      invocations ran in.
//   3. A resolve draw (two triangles over the framebuffer, the same program with `uniform int
//      resolve 1`) writes per pixel (fragments, kept triangle or -1, verdict, 1) into an
//      RGBA32F texture, which the probes read: the verdict must be 0 everywhere (`probe all`),
//      and fragments and triangle must be the reference's wherever the reference decides them
//      (`probe rect`, rectangles of equal expectation): where the verdict table
//      (coverage_verdict_table.hpp, compare/'s rules) fails every other count, or every other
//      triangle, there.
// Where the reference does not decide which triangle is kept (a centre on an edge, within the
// snapping band of an edge, near a triangle the freedom may turn over, where another fragment
// may win the depth test; the edge bits), the kept fragment's values are judged only at the
// (pixel, triangle) pairs listed, since another triangle's fragment is not judged there; the
// shader has those pixels as index spans. Values are checked against their ranges at the
// pairs listed only: every pair of a case with at most shader_test_value_checks of them, else
// that many, chosen first where the coverage is free, then on triangles the clipper cuts, then
// on edge pixels, then spread evenly over the rest; NaN and Inf are checked everywhere. So a
// large case's finite wrong value at a pixel not listed passes here while `run` fails it; its
// C reproducer (--format c) judges every pixel. Fragment traces (core/fragment_trace.hpp) are
// not checked here: where the edge bits leave a pixel's count free (an outer edge's or clip
// plane's band, a triangle that may turn over), any count passes, as it did in `run` before
// traces, so a double hit on a shared edge inside another triangle's band passes here while
// `run` and the C reproducer fail it (probes of a value cannot say whose fragments a count came
// from).
//
// Every float is written so that it reads back as the same float32: vertex data and probes as
// decimals that C's strtod and a cast to float give back exactly (shader_runner's strtof_hex
// takes "0x..." as a bit pattern, so no hexadecimal floats), and GLSL literals as the shortest
// decimal that strtof gives back (Mesa's GLSL lexer uses strtof).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "core/case.hpp"
#include "core/expectation.hpp"

namespace glrc::reproducer {

// The first characters of every shader_test written (its first line): `export --out` replaces
// only a file that holds them.
inline constexpr const char* kShaderTestSignature = "# glrefcheck shader_test";

// Bounds that keep a shader_test a file to read: framebuffer pixels (the storage buffer, the
// spans and the probes grow with it), triangles (three rows of vertex data each), and
// (pixel, triangle) pairs whose values are checked against a stated range, at most
// kMaxShaderTestValueChecks of them with at most kMaxShaderTestRanges ranges in all (one per
// channel: depth and each component).
inline constexpr size_t kMaxShaderTestPixels = 262144;
inline constexpr size_t kMaxShaderTestTriangles = 4096;
inline constexpr size_t kMaxShaderTestValueChecks = 64;
inline constexpr size_t kMaxShaderTestRanges = 512;
// How many pairs a case with `components` varying components may list: at most
// kMaxShaderTestValueChecks, at most kMaxShaderTestRanges / (components + 1), at least 1.
size_t shader_test_value_checks(int components);

// What the file says besides the case and its expectation.
struct ShaderTestSetup {
  std::string exported_by;  // the command that wrote it, for the header
  std::string model;        // words for the model the expectation is of
  std::string file_name;    // the file's name, for the header's command line
};

// The text, and counts for the line `export` prints.
struct ShaderTest {
  std::string text;
  size_t value_checks = 0;     // (pixel, triangle) pairs checked against a stated range
  size_t value_pairs = 0;      // (pixel, triangle) pairs `run` would judge (covered + candidates)
  size_t coverage_probes = 0;  // `probe rect` lines
  size_t pixels_decided = 0;   // pixels whose fragments or triangle those probes check
};

// Why the case's states cannot be expressed with shader_runner's commands (one sentence naming
// the state and what shader_runner lacks), or the framebuffer or triangle count is past the
// bounds above; nothing when they can. Needs no expectation.
std::optional<std::string> shader_test_state_refusal(const Case& c);

// As shader_test_state_refusal, and what the expectation rules out: ToleranceMode::exact (a
// driver model's bits, which a range of values does not express), and with a depth test a
// depth allowance below the 24-bit depth buffer's step (2^-24) at a pixel the reference covers,
// where the rounding of the stored depth could decide the depth test the reference decides.
std::optional<std::string> shader_test_refusal(const Case& c, const Expectation& expected,
                                               const Tolerance& tolerance);

// The shader_test of case `c`.
//   c:         a valid case (casefile::load's);
//   expected:  check::expectation_for(c, ...) without a driver model: the exact frame (window
//              coordinates, row 0 at the bottom) with fragment counts, edge bits, the allowance
//              per pixel and channel (needed under ToleranceMode::spec) and the depth-test
//              candidates, sorted by pixel;
//   tolerance: check::tolerance_for(c, ...): spec or ulps, and allow_boundary;
//   setup:     as above.
// Throws std::invalid_argument with shader_test_refusal's reason, or when the expectation is not
// of this case's shape.
ShaderTest shader_test(const Case& c, const Expectation& expected, const Tolerance& tolerance,
                       const ShaderTestSetup& setup);

// `PIGLIT_PLATFORM=surfaceless_egl shader_runner FILE -auto -fbo`, FILE quoted for a POSIX
// shell where needed: how the header, and `export`, say to run it.
std::string shader_runner_command(const std::string& file);

}  // namespace glrc::reproducer
