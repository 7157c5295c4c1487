// A case as one piglit shader_test (shader_test.hpp): the case's draw with a fragment shader
// that judges and counts, a resolve draw, and probes of the verdict. What is judged where is the
// plan's (shader_test_plan.hpp); the GLSL is export/glsl/'s, filled here; the probes are
// coverage_probes.hpp's.
#include "export/shader_test.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <vector>

#include "compare/compare.hpp"
#include "core/primitive_assembly.hpp"
#include "core/text.hpp"
#include "export/coverage_probes.hpp"
#include "export/expectation_shape.hpp"
#include "export/shader_test_glsl.hpp"
#include "export/shader_test_plan.hpp"
#include "export/shader_test_text.hpp"
#include "export/text_template.hpp"

namespace glrc::reproducer {
namespace {

// ---- The case's states as shader_runner commands ----

// Which triangles the case culls, by their winding in window coordinates (GL_CCW front faces
// are the counter-clockwise ones, GL_CW front faces the clockwise ones).
enum class Culled { none, clockwise, counter_clockwise, all };
Culled culled(const Case& c) {
  switch (c.cull) {
    case CullFace::none:
      return Culled::none;
    case CullFace::front_and_back:
      return Culled::all;
    case CullFace::back:
      return c.front_face == FrontFace::ccw ? Culled::clockwise : Culled::counter_clockwise;
    case CullFace::front:
      return c.front_face == FrontFace::ccw ? Culled::counter_clockwise : Culled::clockwise;
  }
  return Culled::none;
}

// The GLSL condition under which a fragment belongs to a culled triangle: gl_FrontFacing is
// true for counter-clockwise triangles under GL's default GL_CCW, which shader_runner keeps.
const char* culled_condition(Culled culls) {
  switch (culls) {
    case Culled::none:
      return "false";
    case Culled::clockwise:
      return "!gl_FrontFacing";
    case Culled::counter_clockwise:
      return "gl_FrontFacing";
    case Culled::all:
      return "true";
  }
  return "false";
}

void check_shape(const Case& c, const Expectation& e, const Tolerance& t) {
  auto fail = [&](const std::string& why) {
    std::string message = "shader_test: case '";
    message += c.name;
    message += "': ";
    message += why;
    throw std::invalid_argument(message);
  };
  if (const std::string why = expectation_shape_error(c, e, t); !why.empty()) fail(why);
  for (const Varying& v : c.varyings)
    if (v.size < 1 || v.size > 4) fail("a varying has not 1 to 4 components");
}

// ---- The file's parts ----

// The header's notes: which pairs' values are checked, and what the file does otherwise than
// the harness (culling, the depth buffer), or a case outside GL's specified range.
std::string notes(const Case& c, const ShaderTestPlan& plan) {
  const size_t checks = plan.checks.size(), pairs = plan.pairs.size();
  std::string scope =
      cat("Values are checked against their ranges at ", with_commas(checks), " of the ",
          with_commas(pairs), " (pixel, triangle) pairs `glrefcheck run` judges");
  scope += checks < pairs ? " (first where coverage is free, then on clipped triangles, then at "
                            "edges, then spread; the C reproducer, --format c, judges them all), "
                            "and for NaN and Inf everywhere."
                          : " (all of them), and for NaN and Inf everywhere.";
  std::string out = cat("#\n", comment_lines(scope));
  if (const std::optional<std::string> outside = outside_specified_range(c)) {
    out += "#\n";
    out += comment_lines(cat("Note: outside GL's specified range (", *outside,
                             "): glrefcheck run reports a failure of this case as a skip."));
  }
  if (culled(c) != Culled::none) {
    out += "#\n";
    out += comment_lines(
        "Culling: shader_runner has no glCullFace or glFrontFace command, so the fragment shader "
        "discards the fragments of the triangles the case culls, by gl_FrontFacing. That draws "
        "what culling draws, but does not exercise the driver's culling itself.");
  }
  if (c.depth_clamp) {
    out += "#\n";
    out += comment_lines(
        "GL_DEPTH_CLAMP is enabled (`enable GL_DEPTH_CLAMP`): the near and far planes clip "
        "nothing, and the depth judged is gl_FragCoord.z clamped to the depth range [0, 1], as "
        "the depth buffer the harness reads takes it.");
  }
  if (c.depth_func != DepthFunc::always) {
    out += "#\n";
    out += comment_lines(
        "The depth test runs on shader_runner's 24-bit depth buffer (the harness's is 32-bit "
        "float); every covered pixel's depth allowance is at least its step, 2^-24.");
  }
  return out;
}

// The header comment: what the file is, how to run it, what it checks and what it cannot.
std::string header(const Case& c, const Tolerance& tolerance, const ShaderTestSetup& setup,
                   const ShaderTestPlan& plan) {
  std::string out = cat(kShaderTestSignature, " of case ", one_line(c.name), "\n#\n");
  if (!c.description.empty()) {
    out += comment_lines(c.description);
    out += "#\n";
  }
  out += cat("# Written by: ", one_line(setup.exported_by), "\n#\n");
  std::string what =
      "It draws this one case on GL as glrefcheck's GL harness draws it and checks it "
      "against glrefcheck's exact reference of model ";
  what += setup.model;
  what += ", under ";
  if (tolerance.mode == ToleranceMode::spec) {
    what += "the specification's allowance for an implementation that reports GL_SUBPIXEL_BITS = ";
    what += std::to_string(tolerance.subpixel_bits);
    what += " (it must be what the driver reports: llvmpipe 8, softpipe 4).";
  } else {
    char number[128];
    std::snprintf(number, sizeof number, "%.9g ULPs of each attribute's scale, depth %.9g",
                  tolerance.varying_ulps, tolerance.depth_ulps);
    what += "fixed thresholds (";
    what += number;
    what += " ULPs of 1.0, flat values 0).";
  }
  out += comment_lines(what);
  out += "#\n";
  const std::string file = setup.file_name.empty() ? cat(c.name, ".shader_test") : setup.file_name;
  out += cat("#   Run: ", shader_runner_command(file), "\n");
  out +=
      "#        (GALLIUM_DRIVER=softpipe picks Mesa's driver; a pass prints PIGLIT: {\"result\": "
      "\"pass\" })\n";
  out += "#\n";
  out += comment_lines(
      "How: the case is drawn (de-indexed, each triangle's index as a flat int), and its "
      "fragment shader counts each pixel's fragments and keeps the last one's triangle and "
      "verdict (atomics on a storage buffer); with a depth test it is drawn twice, first "
      "without the depth test only to count every fragment (a count through the depth test "
      "would depend on which of two fragments of close depths passes it, which is free), then "
      "with it only to keep the winners. The verdict is 1 for NaN or Inf in depth "
      "(gl_FragCoord.z) or any component, 2 for a value outside the range [lo, hi] stated for "
      "that pixel and triangle (the float32 values within the allowance of the exact value). A "
      "resolve draw then writes, per pixel, (fragments, kept triangle or -1, verdict, 1) into "
      "an RGBA32F texture, and the probes read it: the verdict must be 0 everywhere, and the "
      "fragments and the triangle must be the reference's wherever the specification decides "
      "them (away from the edge bits' freedom; a gap or double hit on a shared edge fails). "
      "Pixels are in window coordinates, (x, y) from the bottom left.");
  return out + notes(c, plan);
}

bool viewport_set(const Case& c) {
  return c.viewport.x != 0 || c.viewport.y != 0 || c.viewport.width != c.fb_width ||
         c.viewport.height != c.fb_height;
}

std::string require_section(const Case& c) {
  const bool depth_test = c.depth_func != DepthFunc::always;
  std::string out = "\n[require]\nGL CORE >= 3.3\nGLSL >= 3.30\n";
  out += "GL_ARB_shader_storage_buffer_object\nGL_ARB_texture_storage\n";
  if (depth_test) out += "GL_ARB_shader_image_load_store\n";
  if (viewport_set(c)) out += "GL_ARB_viewport_array\n";
  if (c.distances.cull) out += "GL_ARB_cull_distance\n";
  if (depth_test) out += "depthbuffer\n";
  return out + cat("SIZE ", std::to_string(c.fb_width), " ", std::to_string(c.fb_height), "\n");
}

// export/glsl/vertex.glsl for the case's varyings.
std::string vertex_shader(const Case& c) {
  std::string attributes, copies;
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    const Varying& v = c.varyings[k];
    if (v.is_builtin()) continue;  // the fragment shader's own input
    const std::string n = std::to_string(k);
    attributes += cat("layout(location = ", std::to_string(k + 1), ") in ", glsl_type(v.size), " a",
                      n, ";\n");
    attributes += cat(glsl_qualifier(v.interpolation), " out ", glsl_type(v.size), " v", n, ";\n");
    copies += cat("  v", n, " = a", n, ";\n");
  }
  // The distances four to a vec4 attribute (a_distances<j>, component i % 4 of j = i / 4):
  // with 7 varyings and 8 distances, one float attribute each would pass the 16 locations GL
  // guarantees.
  const Distances& d = c.distances;
  for (int j = 0; j < (d.clip + d.cull + 3) / 4; ++j)
    attributes += cat("in vec4 a_distances", std::to_string(j), ";\n");
  if (d.clip) attributes += cat("out float gl_ClipDistance[", std::to_string(d.clip), "];\n");
  if (d.cull) attributes += cat("out float gl_CullDistance[", std::to_string(d.cull), "];\n");
  static constexpr const char* kComponent[] = {"x", "y", "z", "w"};
  for (int i = 0; i < d.clip + d.cull; ++i)
    copies += cat("  ", i < d.clip ? "gl_ClipDistance[" : "gl_CullDistance[",
                  std::to_string(i < d.clip ? i : i - d.clip), "] = a_distances",
                  std::to_string(i / 4), ".", kComponent[i % 4], ";\n");
  return fill_template(
      kShaderTestVertex,
      {{"ATTRIBUTES", attributes},
       {"TRIANGLE_LOCATION", std::to_string(c.varyings.size() + 1)},
       {"COPIES", copies},
       {"EXTENSIONS", d.cull ? "#extension GL_ARB_cull_distance : require\n" : ""}},
      {});
}

// FREE's items: the free spans' starts and ends, lines of at most 96 characters after the
// first ("\n    " before each line).
std::string free_list(const std::vector<std::pair<size_t, size_t>>& spans) {
  std::string out, line;
  for (size_t s = 0; s < spans.size(); ++s) {
    const std::string item =
        cat(std::to_string(spans[s].first), ", ", std::to_string(spans[s].second),
            s + 1 < spans.size() ? "," : ");");
    if (!line.empty() && line.size() + 1 + item.size() > 96) {
      out += cat("\n    ", line);
      line.clear();
    }
    if (!line.empty()) line += ' ';
    line += item;
  }
  return out + cat("\n    ", line);
}

// CHECK_AT's items (six a line) and RANGE's (one pair a line, with its exact values for people).
std::pair<std::string, std::string> check_lists(const ShaderTestPlan& plan, int width) {
  std::string at, ranges;
  const size_t checks = plan.checks.size();
  for (size_t n = 0; n < checks; ++n) {
    const ValuePair& r = plan.pairs[plan.checks[n]];
    const std::string x = std::to_string(r.pixel % size_t(width)),
                      y = std::to_string(r.pixel / size_t(width)), t = std::to_string(r.primitive);
    at += cat(n % 6 == 0 ? "\n    " : " ", "ivec3(", x, ", ", y, ", ", t, ")",
              n + 1 < checks ? "," : "");
    ranges += "\n    ";
    for (size_t k = 0; k < r.expected.size(); ++k) {
      float lo = 1, hi = 0;
      if (std::isfinite(r.expected[k]) && std::isfinite(r.allowed[k]) && r.allowed[k] >= 0)
        std::tie(lo, hi) = accepted_range(r.expected[k], r.allowed[k]);
      ranges += cat(k > 0 ? ", " : "", "vec2(", glsl_float(lo), ", ", glsl_float(hi), ")");
    }
    ranges += cat(n + 1 < checks ? ",  // (" : ");  // (", x, ", ", y, ") t ", t, ": ",
                  decimal(r.expected[0]));
    for (size_t k = 1; k < r.expected.size(); ++k)
      ranges += cat(", ", decimal(r.expected[k]));
  }
  return {at, ranges};
}

// export/glsl/fragment.glsl for the case and its plan.
std::string fragment_shader(const Case& c, const ShaderTestPlan& plan) {
  std::string varyings, names, values;
  // The pixel, from gl_FragCoord: under its layout qualifiers (a built-in written out) the
  // pixel centre (px + 1/2 or px; y from the top under origin_upper_left) truncated back to
  // the pixel's numbers.
  std::string pixel = "ivec2(gl_FragCoord.xy)";
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    const Varying& v = c.varyings[k];
    if (v.builtin == Builtin::front_facing) {
      values += ", (gl_FrontFacing ? 1.0 : 0.0)";
      continue;
    }
    if (v.builtin == Builtin::frag_coord) {
      varyings += frag_coord_redeclaration(v.layout);
      for (int j = 0; j < 4; ++j)
        values += cat(", gl_FragCoord.", std::string(1, "xyzw"[j]));
      if (v.layout.origin_upper_left)
        pixel = cat("ivec2(int(gl_FragCoord.x), ", std::to_string(c.fb_height - 1),
                    " - int(gl_FragCoord.y))");
      continue;
    }
    varyings += cat(glsl_qualifier(v.interpolation), " in ", glsl_type(v.size), " v",
                    std::to_string(k), ";  // ", glsl_comment(v.name), "\n");
    for (int j = 0; j < v.size; ++j)
      values += v.size == 1 ? cat(", v", std::to_string(k))
                            : cat(", v", std::to_string(k), ".", std::string(1, "xyzw"[j]));
  }
  for (const std::string& n : component_names(c))
    names += cat(", ", glsl_comment(n));
  const Culled culls = culled(c);
  const char* kind = culls == Culled::clockwise           ? "clockwise triangle"
                     : culls == Culled::counter_clockwise ? "counter-clockwise triangle"
                                                          : "triangle";
  const auto [check_at, ranges] = check_lists(plan, c.fb_width);
  const std::string pixels = std::to_string(size_t(c.fb_width) * size_t(c.fb_height));
  return fill_template(kShaderTestFragment,
                       {{"VARYINGS", varyings},
                        {"PIXELS", pixels},
                        {"WIDTH", std::to_string(c.fb_width)},
                        {"CHANNELS", std::to_string(c.component_count() + 1)},
                        {"CHANNEL_NAMES", names},
                        {"FREE_SPANS", std::to_string(plan.free_spans.size())},
                        {"FREE_COUNT", std::to_string(2 * plan.free_spans.size())},
                        {"FREE", plan.free_spans.empty() ? "" : free_list(plan.free_spans)},
                        {"CHECKS", std::to_string(plan.checks.size())},
                        {"CHECK_AT", check_at},
                        {"RANGES", ranges},
                        {"CHANNEL_VALUES", values},
                        {"PIXEL", pixel},
                        {"CULL", std::string(name_of(c.cull))},
                        {"FRONT_FACE", std::string(name_of(c.front_face))},
                        {"CULLED_KIND", kind},
                        {"CULLED_CONDITION", culled_condition(culls)}},
                       {{"depth_test", c.depth_func != DepthFunc::always},
                        {"culled", culls != Culled::none},
                        {"free_spans", !plan.free_spans.empty()},
                        {"checks", !plan.checks.empty()},
                        {"depth_clamp", c.depth_clamp}});
}

// The rows of [vertex data] for the case's draws, and the `draw arrays` command of each. A
// GL_TRIANGLES draw gives every triangle's three vertices (an indexed draw expanded, as
// shader_runner has no index buffer), a_triangle its number. A strip or fan gives its vertex
// stream as GL takes it (its indices expanded in order), so that GL assembles it; a_triangle,
// flat, is read from each triangle's provoking vertex (table 13.2: strip triangle i's is v_i+2
// under the last-vertex convention and v_i under the first, a fan's v_i+2 and v_i+1), so each
// row holds the number of the triangle it provokes (-1 where none: the stream's first vertices).
// A driver that takes another provoking vertex then judges pixels against another triangle,
// which fails there as its flat values would.
struct DrawRows {
  std::vector<std::pair<uint32_t, int64_t>> rows;  // (vertex, a_triangle)
  std::vector<std::string> commands;
};

DrawRows draw_rows(const Case& c) {
  static constexpr const char* kModes[] = {"GL_TRIANGLES", "GL_TRIANGLE_STRIP", "GL_TRIANGLE_FAN"};
  const std::vector<Draw> draws = draws_of(c);
  const std::vector<uint32_t> first = assemble(draws, c.provoking).first_triangle;
  const bool pv_first = c.provoking == ProvokingVertex::first;
  DrawRows out;
  for (size_t d = 0; d < draws.size(); ++d) {
    const size_t start = out.rows.size();
    if (draws[d].mode == PrimitiveMode::triangles) {
      for (uint32_t t = first[d]; t < first[d + 1]; ++t)
        for (uint32_t vi : c.triangles[t])
          out.rows.emplace_back(vi, t);
    } else {
      const std::vector<uint32_t> e = draws[d].elements();
      // The stream position whose vertex provokes triangle i is i + lag.
      const int64_t lag = pv_first ? (draws[d].mode == PrimitiveMode::triangle_fan ? 1 : 0) : 2;
      const int64_t triangles = int64_t(first[d + 1] - first[d]);
      for (size_t j = 0; j < e.size(); ++j) {
        const int64_t i = int64_t(j) - lag;
        out.rows.emplace_back(e[j], i >= 0 && i < triangles ? int64_t(first[d]) + i : -1);
      }
    }
    if (out.rows.size() > start)
      out.commands.push_back(cat("draw arrays ", kModes[int(draws[d].mode)], " ",
                                 std::to_string(start), " ",
                                 std::to_string(out.rows.size() - start), "\n"));
  }
  return out;
}

// [vertex data]: the draws' rows (draw_rows), then the resolve draw's two triangles.
std::string vertex_data(const Case& c, const DrawRows& draws) {
  std::string out = "\n[vertex data]\na_clip/float/vec4";
  for (size_t k = 0; k < c.varyings.size(); ++k)
    if (!c.varyings[k].is_builtin())
      out += cat(" a", std::to_string(k), "/float/", glsl_type(c.varyings[k].size));
  out += " a_triangle/int/int";
  const int distances = c.distances.clip + c.distances.cull, vec4s = (distances + 3) / 4;
  for (int j = 0; j < vec4s; ++j)
    out += cat(" a_distances", std::to_string(j), "/float/vec4");
  out += "\n";
  for (const auto& [vi, t] : draws.rows) {
    const Vertex& v = c.vertices[vi];
    std::string row;
    for (float x : v.clip)
      row += cat(decimal(x), " ");
    size_t at = 0;
    for (const Varying& var : c.varyings)  // a built-in's zeros are not vertex data
      for (int j = 0; j < var.size; ++j, ++at)
        if (!var.is_builtin()) row += cat(" ", decimal(v.values[at]));
    row += cat("  ", std::to_string(t));
    for (int i = 0; i < 4 * vec4s; ++i)
      row += cat(i % 4 == 0 ? "  " : " ", i < distances ? decimal(v.distances[size_t(i)]) : "0");
    out += cat(row, "\n");
  }
  std::string zeros;
  for (const Varying& var : c.varyings)
    for (int j = 0; j < var.size && !var.is_builtin(); ++j)
      zeros += " 0";
  // The resolve draw's distances 0: inside every clip plane, and not culled (0 is not negative).
  std::string distance_zeros;
  for (int i = 0; i < 4 * vec4s; ++i)
    distance_zeros += i % 4 == 0 ? "  0" : " 0";
  for (const char* corner : {"-1 -1", "1 -1", "1 1", "-1 -1", "1 1", "-1 1"})
    out += cat(corner, " 0 1 ", zeros, "  -1", distance_zeros, "\n");
  return out;
}

// [test]'s draws: the case's (with a depth test, after a count without it), then the resolve.
std::string draws(const Case& c, const DrawRows& rows) {
  std::string out = "\n[test]\n";
  out += "# The case's states (the harness's depth test with GL_ALWAYS is no depth test here).\n";
  out += cat("ssbo 0 ", std::to_string(size_t(c.fb_width) * size_t(c.fb_height) * 8), "\n");
  if (viewport_set(c))
    out += cat("viewport indexed 0 ", decimal(c.viewport.x), " ", decimal(c.viewport.y), " ",
               decimal(c.viewport.width), " ", decimal(c.viewport.height), "\n");
  if (c.provoking == ProvokingVertex::first) out += "provoking vertex first\n";
  if (c.depth_clamp) out += "enable GL_DEPTH_CLAMP\n";
  for (int i = 0; i < c.distances.clip; ++i)
    if (c.distances.plane_enabled(i)) out += cat("enable GL_CLIP_PLANE", std::to_string(i), "\n");
  std::string draw_case;
  for (const std::string& command : rows.commands)
    draw_case += command;
  const bool depth_test = c.depth_func != DepthFunc::always;
  if (depth_test) {
    out +=
        "# Every fragment counted first, without the depth test; then the case's draw with it.\n";
    out += cat("uniform int resolve 2\n", draw_case, "uniform int resolve 0\n");
    out +=
        cat("clear depth ", c.depth_clear == 0.0f ? "0" : "1", "\nclear\nenable GL_DEPTH_TEST\n");
    std::string func(name_of(c.depth_func));  // GL's name is the case file's, upper case
    std::transform(func.begin(), func.end(), func.begin(),
                   [](char ch) { return char(ch - 'a' + 'A'); });
    out += cat("depthfunc GL_", func, "\n");
  }
  out += cat(draw_case, "memory barrier GL_SHADER_STORAGE_BARRIER_BIT\n");
  out +=
      "\n# Resolve: per pixel (fragments, kept triangle or -1, verdict, 1) into an RGBA32F "
      "texture.\n";
  if (depth_test) out += "disable GL_DEPTH_TEST\n";
  const std::string width = std::to_string(c.fb_width), height = std::to_string(c.fb_height);
  if (viewport_set(c)) out += cat("viewport indexed 0 0 0 ", width, " ", height, "\n");
  out += cat("texture storage 0 2D GL_RGBA32F (1 ", width, " ", height, ")\n");
  out += "fb tex 2d 0\nuniform int resolve 1\n";
  out += cat("draw arrays GL_TRIANGLES ", std::to_string(rows.rows.size()), " 6\n");
  out +=
      "\n# Values: the verdict (third) is 0 at every pixel: no NaN or Inf (1), nothing outside "
      "its range (2).\n";
  return out + "tolerance 1e9 1e9 0.25 1e9\nprobe all rgba 0 0 0 1\n";
}

}  // namespace

size_t shader_test_value_checks(int components) {
  const size_t channels = size_t(std::max(components, 0)) + 1;
  return std::max<size_t>(1, std::min(kMaxShaderTestValueChecks, kMaxShaderTestRanges / channels));
}

std::string shader_runner_command(const std::string& file) {
  std::string command = "PIGLIT_PLATFORM=surfaceless_egl shader_runner ";
  command += shell_word(file);
  command += " -auto -fbo";
  return command;
}

std::optional<std::string> shader_test_state_refusal(const Case& c) {
  if (c.front_face == FrontFace::cw &&
      std::any_of(c.varyings.begin(), c.varyings.end(),
                  [](const Varying& v) { return v.builtin == Builtin::front_facing; }))
    return std::string(
        "gl_FrontFacing under glFrontFace(GL_CW) cannot be expressed in a shader_test: "
        "shader_runner has no glFrontFace command (culling is emulated in its shader, the facing "
        "GL reports is not)");
  if (c.scissor)
    return std::string(
        "the scissor test cannot be expressed in a shader_test: shader_runner has no glScissor "
        "command (its `enable GL_SCISSOR_TEST` would keep the whole window's box)");
  if (c.clip_origin != ClipOrigin::lower_left || c.clip_depth != ClipDepth::negative_one_to_one)
    return cat(
        "glClipControl(",
        c.clip_origin == ClipOrigin::upper_left ? "GL_UPPER_LEFT" : "GL_LOWER_LEFT", ", ",
        c.clip_depth == ClipDepth::zero_to_one ? "GL_ZERO_TO_ONE" : "GL_NEGATIVE_ONE_TO_ONE",
        ") cannot be expressed in a shader_test: shader_runner has no glClipControl command");
  if (const std::optional<PolygonOffset>& o = c.polygon_offset) {
    std::string why =
        cat("polygon_offset (factor ", decimal(o->factor), ", units ", decimal(o->units));
    if (o->clamp) why += cat(", clamp ", decimal(*o->clamp));
    why += cat(") cannot be expressed in a shader_test: shader_runner has no ",
               o->clamp ? "glPolygonOffsetClamp" : "glPolygonOffset",
               " command (and its `enable` takes no GL_POLYGON_OFFSET_FILL)");
    return why;
  }
  // A restart that no index meets changes nothing: such a draw is expanded as any other.
  for (size_t d = 0; d < c.draws.size(); ++d)
    if (std::any_of(c.draws[d].indices.begin(), c.draws[d].indices.end(),
                    [&](uint32_t i) { return c.draws[d].restarts_at(i); }))
      return cat("draw ", std::to_string(d),
                 "'s primitive restart cannot be expressed in a shader_test: shader_runner draws "
                 "only arrays (`draw arrays`), with no index buffer to hold a restart index");
  if (c.depth_near != 0.0f || c.depth_far != 1.0f) {
    std::string why = "depth_range (near ";
    why += decimal(c.depth_near);
    why += ", far ";
    why += decimal(c.depth_far);
    why +=
        ") cannot be expressed in a shader_test: shader_runner has no glDepthRange command (only "
        "[0, 1])";
    return why;
  }
  if (culled(c) == Culled::all) {
    std::string why =
        "cull front_and_back cannot be expressed in a shader_test: shader_runner "
        "has no glCullFace command (its `enable` takes no GL_CULL_FACE), and a "
        "fragment shader that discards every fragment leaves the varyings unused, "
        "which the linker removes with their attributes (and shader_runner then "
        "refuses their vertex data)";
    return why;
  }
  if (c.cull != CullFace::none && c.depth_func != DepthFunc::always) {
    std::string why = "cull ";
    why += name_of(c.cull);
    why += " with depth_func ";
    why += name_of(c.depth_func);
    why +=
        " cannot be expressed in a shader_test: shader_runner has no "
        "glCullFace command (its `enable` takes no GL_CULL_FACE), and culling in the fragment "
        "shader cannot undo the depth writes of the early depth test that keeping only the "
        "depth test's winners needs";
    return why;
  }
  const size_t pixels = size_t(std::max(c.fb_width, 0)) * size_t(std::max(c.fb_height, 0));
  if (pixels > kMaxShaderTestPixels)
    return cat("a ", std::to_string(c.fb_width), "x", std::to_string(c.fb_height),
               " framebuffer; a shader_test takes at most ", with_commas(kMaxShaderTestPixels),
               " pixels: shrink the case first (glrefcheck fuzz --replay ...)");
  if (c.triangles.size() > kMaxShaderTestTriangles)
    return cat(with_commas(c.triangles.size()), " triangles; a shader_test takes at most ",
               with_commas(kMaxShaderTestTriangles),
               ": shrink the case first (glrefcheck fuzz --replay ...)");
  return std::nullopt;
}

std::optional<std::string> shader_test_refusal(const Case& c, const Expectation& expected,
                                               const Tolerance& tolerance) {
  if (auto why = shader_test_state_refusal(c)) return why;
  if (tolerance.mode == ToleranceMode::exact)
    return std::string(
        "exact tolerance (a driver model's bits) cannot be expressed in a shader_test, which "
        "checks ranges of values");
  if (c.depth_func != DepthFunc::always && c.depth_clear != 0.0f && c.depth_clear != 1.0f) {
    std::string why = "depth_clear ";
    why += decimal(c.depth_clear);
    why +=
        " with a depth test cannot be expressed in a shader_test: shader_runner's depth buffer has "
        "24 bits, which hold only 0 and 1 of the clear values exactly";
    return why;
  }
  if (c.depth_func != DepthFunc::always) {
    const compare::UlpTable ulps(c);
    const compare::ChannelAllowance depth(c, expected, tolerance, Channel::depth());
    const Frame& f = expected.frame;
    for (size_t i = 0; i < f.pixel_count() && i < f.primitive.size(); ++i) {
      const int32_t p = f.primitive[i];
      if (p == Frame::kNoPrimitive) continue;
      if (depth.at(i, ulps.ulp(p, Channel::depth())) < 0x1p-24) {
        std::string why = "depth_func ";
        why += name_of(c.depth_func);
        why += " with a depth allowance of ";
        char number[32];
        std::snprintf(number, sizeof number, "%.3g", depth.at(i, ulps.ulp(p, Channel::depth())));
        why += number;
        why += cat(" at pixel (", std::to_string(i % size_t(f.width)), ", ",
                   std::to_string(i / size_t(f.width)), ")");
        why +=
            " cannot be expressed in a shader_test: shader_runner's depth buffer has 24 bits, "
            "whose step 2^-24 could decide the depth test there";
        return why;
      }
    }
  }
  return std::nullopt;
}

ShaderTest shader_test(const Case& c, const Expectation& expected, const Tolerance& tolerance,
                       const ShaderTestSetup& setup) {
  if (auto why = shader_test_refusal(c, expected, tolerance)) {
    std::string message = "shader_test: case '";
    message += c.name;
    message += "': ";
    message += *why;
    throw std::invalid_argument(message);
  }
  check_shape(c, expected, tolerance);
  const ShaderTestPlan plan = plan_shader_test(c, expected, tolerance);
  const CoverageProbes probes = coverage_probes(expected.frame, plan.decided);
  ShaderTest result;
  result.value_pairs = plan.pairs.size();
  result.value_checks = plan.checks.size();
  result.coverage_probes = probes.probes;
  result.pixels_decided = probes.pixels_decided;
  result.text.reserve(65536 + c.triangles.size() * 3 * size_t(4 + c.component_count()) * 16);
  result.text += header(c, tolerance, setup, plan);
  result.text += require_section(c);
  result.text += cat("\n[vertex shader]\n", vertex_shader(c));
  result.text += cat("\n[fragment shader]\n", fragment_shader(c, plan));
  const DrawRows rows = draw_rows(c);
  result.text += vertex_data(c, rows);
  result.text += draws(c, rows);
  result.text += probes.text;
  return result;
}

}  // namespace glrc::reproducer
