// A case as one self-contained C file (reproducer.hpp): the case's draw, its expectation as
// hexadecimal float literals, and a C runtime that opens GL through dlopen, draws as gl_harness/
// does and judges as compare/ does.
#include "export/reproducer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "compare/compare.hpp"
#include "core/primitive_assembly.hpp"
#include "core/text.hpp"
#include "export/c_runtime.hpp"
#include "export/coverage_verdict_table.hpp"
#include "export/expectation_shape.hpp"

namespace glrc::reproducer {
namespace {

// ---- The C runtime: the same text in every reproducer (export/c_runtime/, embedded) ----

// ---- Writing C ----

// A C99 literal of v, exactly: hexadecimal floating point, or NAN / INFINITY (math.h).
std::string hex_literal(double v) {
  if (std::isnan(v)) return "NAN";
  if (std::isinf(v)) return v < 0 ? "-INFINITY" : "INFINITY";
  char digits[64];
  const auto [end, ec] =
      std::to_chars(digits, digits + sizeof digits, std::fabs(v), std::chars_format::hex);
  if (ec != std::errc()) throw std::logic_error("hex_literal: to_chars failed");
  return (std::signbit(v) ? "-0x" : "0x") + std::string(digits, end);
}

// A C string literal of `text`, one literal per line of it, the later ones on lines of their
// own after `indent`. '?' is escaped (no trigraphs), bytes outside printable ASCII are octal.
std::string c_string(std::string_view text, std::string_view indent = "    ") {
  if (text.empty()) return "\"\"";
  std::string out;
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    end = end == std::string_view::npos ? text.size() : end + 1;
    if (start > 0) out += "\n" + std::string(indent);
    out += '"';
    for (const char ch : text.substr(start, end - start)) {
      const auto u = static_cast<unsigned char>(ch);
      if (ch == '\n') {
        out += "\\n";
      } else if (ch == '"' || ch == '\\' || ch == '?') {
        out += '\\';
        out += ch;
      } else if (u < 0x20 || u >= 0x7f) {
        const char octal[] = {'\\', char('0' + (u >> 6)), char('0' + ((u >> 3) & 7)),
                              char('0' + (u & 7))};
        out.append(octal, sizeof octal);
      } else {
        out += ch;
      }
    }
    out += '"';
    start = end;
  }
  return out;
}

// Text for a /* */ comment: no "*/" to end it early, no trigraph, no control character.
std::string comment_text(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    const auto u = static_cast<unsigned char>(ch);
    if ((ch == '/' && !out.empty() && out.back() == '*') ||
        (ch == '?' && !out.empty() && out.back() == '?'))
      out += ' ';
    out += u < 0x20 || u == 0x7f ? ' ' : ch;
  }
  return out;
}

// `text` as comment lines " * ..." of at most `width` characters, broken at spaces.
std::string comment_lines(std::string_view text, size_t width = 96) {
  return wrap_words(comment_text(text), width, " * ");
}

// Items separated by ", ", lines broken before 100 columns after `indent`; a lone "0" when
// there are none (C has no empty initializer lists; a count beside the array says so).
class ListWriter {
 public:
  ListWriter(std::string& out, std::string indent) : out_(out), indent_(std::move(indent)) {}
  void item(std::string_view text) {
    separate();
    if (column_ == 0 || column_ + 1 + text.size() > 100) {
      newline();
    } else {
      out_ += ' ';
      ++column_;
    }
    out_ += text;
    column_ += text.size();
    ++items_;
    comma_ = false;
  }
  // A comment starting a line of its own; the next items follow it.
  void line_comment(std::string_view text) {
    separate();
    newline();
    out_ += "/* " + std::string(text) + " */";
    column_ += text.size() + 6;
  }
  void finish() {
    if (items_ == 0) {
      newline();
      out_ += "0";
    }
    out_ += "\n";
  }

 private:
  void separate() {
    if (items_ > 0 && !comma_) out_ += ",", comma_ = true;
  }
  void newline() {
    out_ += "\n" + indent_;
    column_ = indent_.size();
  }
  std::string& out_;
  std::string indent_;
  size_t column_ = 0, items_ = 0;
  bool comma_ = false;
};

// A float for people: the shortest "%.9g".
std::string printable_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

const char* gl_cull(CullFace f) {
  switch (f) {
    case CullFace::none:
      return "0 /* no culling */";
    case CullFace::front:
      return "GL_FRONT";
    case CullFace::back:
      return "GL_BACK";
    case CullFace::front_and_back:
      return "GL_FRONT_AND_BACK";
  }
  return "0";
}

// GL's name of the depth function, which the C text defines: the case file's, upper case.
std::string gl_depth_func(DepthFunc f) {
  std::string name(name_of(f));
  std::transform(name.begin(), name.end(), name.begin(),
                 [](char ch) { return char(ch - 'a' + 'A'); });
  return "GL_" + name;
}

// The arrays and the struct scene `name` of case `c`, drawn with `shaders`; its arrays' names
// start with `prefix`.
// The case's draws (draws_of): each indexed draw's indices as an array of its own type, then
// the struct draw of every draw, as the harness issues them (gl_harness/renderer.cpp).
std::string draws_text(const Case& c, const std::string& prefix) {
  static constexpr const char* kModes[] = {"GL_TRIANGLES", "GL_TRIANGLE_STRIP", "GL_TRIANGLE_FAN"};
  static constexpr const char* kTypes[] = {"0", "GL_UNSIGNED_BYTE", "GL_UNSIGNED_SHORT",
                                           "GL_UNSIGNED_INT"};
  static constexpr const char* kCTypes[] = {"", "GLubyte", "GLushort", "GLuint"};
  const std::vector<Draw> draws = draws_of(c);
  const std::vector<uint32_t> first = assemble(draws, c.provoking).first_triangle;
  std::string out, table;
  for (size_t d = 0; d < draws.size(); ++d) {
    const Draw& draw = draws[d];
    const std::string array = prefix + "_indices_" + std::to_string(d);
    const int type = int(draw.index_type);
    if (draw.indexed()) {
      out += "static const " + std::string(kCTypes[type]) + " " + array + "[] = {";
      std::string list;
      ListWriter w(list, "    ");
      for (uint32_t i : draw.indices)
        w.item(std::to_string(i) + (type == 3 ? "u" : ""));
      w.finish();
      out += list + "};\n";
    }
    const std::string restart = draw.restart == Restart::fixed_index
                                    ? "GL_PRIMITIVE_RESTART_FIXED_INDEX"
                                : draw.restart == Restart::index ? "GL_PRIMITIVE_RESTART"
                                                                 : "0";
    table += "    {" + std::string(kModes[int(draw.mode)]) + ", " + kTypes[type] + ", " +
             std::to_string(draw.first) + ", " +
             std::to_string(draw.indexed() ? draw.indices.size() : draw.count) + ", " +
             (draw.indexed() ? array + ", sizeof " + array : "0, 0") + ", " + restart + ", " +
             std::to_string(draw.restart_index) + "u, " + std::to_string(first[d]) + "},\n";
  }
  return out + "static const struct draw " + prefix +
         "_draws[] = {\n    /* mode, index type, first, count, indices, their bytes, restart, "
         "restart index, first triangle */\n" +
         table + "};\n";
}

void write_scene(std::string& out, const Case& c, const ReproducerShaders& shaders,
                 const std::string& prefix, const std::string& name, const std::string& case_name) {
  out += "static const int " + prefix + "_varying_sizes[] = {";
  for (size_t k = 0; k < c.varyings.size(); ++k)
    out += (k ? ", " : "") + std::to_string(c.varyings[k].size);
  if (c.varyings.empty()) out += "0 /* none */";
  out += "};\n";

  std::string components;
  for (const std::string& n : component_names(c))
    components += ", " + n;
  out += "/* Per vertex: clip coordinates (x_c, y_c, z_c, w_c), exactly what gl_Position receives" +
         comment_text(components.empty() ? std::string() : ", then " + components.substr(2)) +
         (c.distances.any() ? ", then gl_ClipDistance[" + std::to_string(c.distances.clip) +
                                  "] and gl_CullDistance[" + std::to_string(c.distances.cull) + "]"
                            : std::string()) +
         ". */\n";
  out += "static const float " + prefix + "_vertices[] = {";
  {
    std::string list;
    ListWriter w(list, "    ");
    for (size_t v = 0; v < c.vertices.size(); ++v) {
      w.line_comment("vertex " + std::to_string(v));
      for (float x : c.vertices[v].clip)
        w.item(hex_literal(x));
      for (float x : c.vertices[v].values)
        w.item(hex_literal(x));
      for (float x : c.vertices[v].distances)
        w.item(hex_literal(x));
    }
    w.finish();
    out += list;
  }
  out += "};\n";
  out += draws_text(c, prefix);
  const std::pair<const char*, const std::string*> sources[] = {
      {"vertex_shader", &shaders.vertex},
      {"geometry_shader", &shaders.geometry},
      {"fragment_shader", &shaders.fragment},
      {"fragment_after_geometry", &shaders.fragment_after_geometry},
      {"count_vertex_shader", &shaders.count_vertex},
      {"count_geometry_shader", &shaders.count_geometry}};
  for (const auto& [field, text] : sources)
    out += "static const char " + prefix + "_" + field + "[] =\n    " + c_string(*text) + ";\n";

  out += "static const struct scene " + name + " = {\n";
  out += "    .name = " + case_name + ",\n";
  out += "    .width = " + std::to_string(c.fb_width) +
         ", .height = " + std::to_string(c.fb_height) + ",\n";
  out += "    .viewport = {" + hex_literal(c.viewport.x) + ", " + hex_literal(c.viewport.y) + ", " +
         hex_literal(c.viewport.width) + ", " + hex_literal(c.viewport.height) + "}, /* " +
         comment_text(printable_number(c.viewport.x) + ", " + printable_number(c.viewport.y) +
                      ", " + printable_number(c.viewport.width) + ", " +
                      printable_number(c.viewport.height)) +
         " */\n";
  if (c.scissor)
    out += "    .scissor = {1, " + std::to_string(c.scissor->x) + ", " +
           std::to_string(c.scissor->y) + ", " + std::to_string(c.scissor->width) + ", " +
           std::to_string(c.scissor->height) + "},\n";
  if (c.clip_origin != ClipOrigin::lower_left || c.clip_depth != ClipDepth::negative_one_to_one)
    out += std::string("    .clip_control = {") +
           (c.clip_origin == ClipOrigin::upper_left ? "GL_UPPER_LEFT" : "GL_LOWER_LEFT") + ", " +
           (c.clip_depth == ClipDepth::zero_to_one ? "GL_ZERO_TO_ONE" : "GL_NEGATIVE_ONE_TO_ONE") +
           "},\n";
  out += "    .depth_near = " + hex_literal(c.depth_near) +
         ", .depth_far = " + hex_literal(c.depth_far) + ", /* " +
         comment_text(printable_number(c.depth_near) + ", " + printable_number(c.depth_far)) +
         " */\n";
  out += std::string("    .depth_clamp = ") + (c.depth_clamp ? "1" : "0") + ",\n";
  if (const std::optional<PolygonOffset>& o = c.polygon_offset) {
    std::string numbers =
        "factor " + printable_number(o->factor) + ", units " + printable_number(o->units);
    if (o->clamp) numbers += ", clamp " + printable_number(*o->clamp);
    out += "    .polygon_offset = {1, " + hex_literal(o->factor) + ", " + hex_literal(o->units) +
           ", " + (o->clamp ? "1, " + hex_literal(*o->clamp) : std::string("0, 0")) + "}, /* " +
           comment_text(numbers) + " */\n";
  }
  out += std::string("    .cull = ") + gl_cull(c.cull) + ",\n";
  out += std::string("    .front_face = ") + (c.front_face == FrontFace::ccw ? "GL_CCW" : "GL_CW") +
         ",\n";
  out += std::string("    .provoking_vertex = ") +
         (c.provoking == ProvokingVertex::last ? "GL_LAST_VERTEX_CONVENTION"
                                               : "GL_FIRST_VERTEX_CONVENTION") +
         ",\n";
  out += std::string("    .depth_func = ") + gl_depth_func(c.depth_func) +
         ", .depth_clear = " + hex_literal(c.depth_clear) + ", /* " +
         comment_text(printable_number(c.depth_clear)) + " */\n";
  out += std::string("    .work_arounds = ") + (c.work_arounds ? "1" : "0") + ",\n";
  out += "    .varying_count = " + std::to_string(c.varyings.size()) +
         ", .varying_sizes = " + prefix + "_varying_sizes,\n";
  out += "    .component_count = " + std::to_string(c.component_count()) + ",\n";
  out += "    .distance_count = " + std::to_string(c.distances.clip + c.distances.cull) +
         ", .clip_planes = " + std::to_string(c.distances.enabled) + "u,\n";
  out += "    .vertex_count = " + std::to_string(c.vertices.size()) + ", .vertices = " + prefix +
         "_vertices,\n";
  out += "    .draw_count = " + std::to_string(draws_of(c).size()) + ", .draws = " + prefix +
         "_draws,\n";
  out += "    .vertex_shader = " + prefix + "_vertex_shader, .geometry_shader = " + prefix +
         "_geometry_shader,\n";
  out += "    .fragment_shader = " + prefix + "_fragment_shader,\n";
  out += "    .fragment_after_geometry = " + prefix + "_fragment_after_geometry,\n";
  out += "    .count_vertex_shader = " + prefix + "_count_vertex_shader,\n";
  out += "    .count_geometry_shader = " + prefix + "_count_geometry_shader,\n";
  out += "    .count_fragment_shader = count_fragment_shader,\n";
  out += "    .trace_fragment_shader = trace_fragment_shader};\n\n";
}

// Throws std::invalid_argument unless `e` is an expectation of case `c` the C file can embed.
void check_inputs(const Case& c, const Expectation& e, const Tolerance& t,
                  const CReproducerSetup& setup) {
  auto fail = [&](const std::string& why) {
    throw std::invalid_argument("c_reproducer: case '" + c.name + "': " + why);
  };
  if (t.mode == ToleranceMode::exact)
    fail("exact tolerance (a driver model's bits) is not what a reproducer judges");
  if (reproducer_values(c) > kMaxReproducerValues)
    fail(std::to_string(reproducer_values(c)) + " pixel values, more than " +
         std::to_string(kMaxReproducerValues));
  if (const std::string why = expectation_shape_error(c, e, t); !why.empty()) fail(why);
  if (setup.first_draw.component_count() != 1 || setup.first_draw.triangles.empty())
    fail("the first draw is not the harness's (one flat float, one triangle)");
}

// The header comment: what the file is, how to build and run it, what it judges.
void write_header(std::string& out, const Case& c, const Tolerance& tolerance,
                  const CReproducerSetup& setup) {
  std::string file_name = setup.file_name.empty() ? c.name + ".c" : setup.file_name;
  if (const size_t slash = file_name.rfind('/'); slash != std::string::npos)
    file_name = file_name.substr(slash + 1);
  const std::string program = c_run_command(file_name);
  out += std::string(kCReproducerSignature) + " of case " + comment_text(c.name) + ", in C99\n";
  out += " *\n";
  if (!c.description.empty()) out += comment_lines(c.description) + " *\n";
  out += comment_lines(
      "Written by `" + setup.exported_by +
      "`. It draws this one case on GL as glrefcheck's GL harness draws it and checks every "
      "pixel against glrefcheck's exact reference, embedded below. Self-contained: C99 and libc "
      "only, no glrefcheck and no GL, EGL or OSMesa headers; libEGL or libOSMesa is opened at "
      "run time (dlopen).");
  out += " *\n";
  out += " *   Build:  " + comment_text(c_compile_command(file_name)) + "\n";
  out += " *   Run:    " + comment_text(program) + " [egl|osmesa]       (default: egl)\n";
  out += " *           GALLIUM_DRIVER=softpipe " + comment_text(program) + " osmesa\n";
  out += " *\n";
  out += comment_lines(
      "egl: Mesa's surfaceless EGL platform (libEGL.so.1, EGL_PLATFORM_SURFACELESS_MESA), an "
      "OpenGL 3.3 core context current without a surface. osmesa: libOSMesa.so.8, "
      "OSMesaCreateContextAttribs with an OpenGL 3.3 core profile. GALLIUM_DRIVER picks Mesa's "
      "driver as usual (llvmpipe when unset, softpipe, or zink through egl); with a CPU driver "
      "named, egl sets LIBGL_ALWAYS_SOFTWARE=1 unless it is set, as glrefcheck does, and a "
      "GALLIUM_DRIVER that GL_RENDERER does not name is refused.");
  out += " *\n";
  std::string judged =
      "Judged as `glrefcheck run` judges it, against the exact reference of model " + setup.model +
      ", under ";
  if (tolerance.mode == ToleranceMode::spec)
    judged +=
        "the specification's allowance for an implementation that reports GL_SUBPIXEL_BITS = " +
        std::to_string(tolerance.subpixel_bits) +
        " (it must be what the driver reports: llvmpipe 8, softpipe 4)";
  else
    judged += "fixed thresholds (" + printable_number(tolerance.varying_ulps) +
              " ULPs of each attribute's scale, depth " + printable_number(tolerance.depth_ulps) +
              " ULPs of 1.0, flat values 0)";
  judged += std::string(
                ". Coverage: per pixel the reference's primitive (-1: none), its fragment "
                "count and its edge bits; a different primitive passes only where the "
                "edge bits say the specification's freedom allows it (a centre exactly on "
                "an edge, within the snapping band of an edge, near a triangle that may "
                "turn over, or where another fragment may win the depth test)") +
            (tolerance.allow_boundary ? "" : " and this case allows no such difference") +
            "; away from outer edges GL must rasterize as many fragments as the reference, "
            "counted without the depth test (gaps and double hits on shared edges fail). Values: "
            "depth, then every component, where GL's "
            "primitive is the reference's (or a candidate of the depth test): |GL - reference| "
            "must be at most the allowed absolute error; NaN or Inf from GL always fails; a "
            "reference value that is NaN or Inf (the specification determines none there) is not "
            "judged. Pixels are in GL window coordinates: (x, y) from the bottom left.";
  out += comment_lines(judged);
  out += " *\n";
  out += comment_lines(
      "Prints each failing check (the first 30, then how many more) and a summary line with "
      "GL_RENDERER and GL_VERSION. Exit status: 0 when everything is within what is allowed, 1 "
      "when a check fails or GL cannot draw the case, 2 when GL cannot be had (library, display, "
      "context, OpenGL 3.3 core).");
  out += " */\n";
  out += kCDeclarations;
}

// The case and the harness's first draw, as the harness draws them.
void write_case(std::string& out, const Case& c, const CReproducerSetup& setup) {
  const int components = c.component_count();
  const std::vector<std::string> names = component_names(c);
  out += "\n/* ---- The case ---- */\n";
  out += "static const char CASE_NAME[] = " + c_string(c.name) + ";\n";
  out += "#define FB_WIDTH " + std::to_string(c.fb_width) + "\n";
  out += "#define FB_HEIGHT " + std::to_string(c.fb_height) + "\n";
  out += "#define PIXELS (FB_WIDTH * FB_HEIGHT)\n";
  out += "#define COMPONENT_COUNT " + std::to_string(components) + "\n";
  out += "#define CHANNELS (1 + COMPONENT_COUNT) /* depth, then every component */\n";
  out += "static const char *const CHANNEL_NAMES[CHANNELS] = {\"depth\"";
  for (const std::string& n : names)
    out += ", " + c_string(n);
  out += "};\n";
  out +=
      "static const char count_fragment_shader[] =\n    " + c_string(setup.count_fragment) + ";\n";
  out +=
      "static const char trace_fragment_shader[] =\n    " + c_string(setup.trace_fragment) + ";\n";
  write_scene(out, c, setup.shaders, "case", "THE_CASE", "CASE_NAME");
  out +=
      "/* The harness's first draw: one triangle over a 4x4 framebuffer, one flat float of 1; "
      "primitive 0\n   and value 1 expected at every pixel. */\n";
  write_scene(out, setup.first_draw, setup.first_draw_shaders, "first_draw", "FIRST_DRAW",
              c_string(setup.first_draw.name));
}

// The expectation: the coverage verdict table, the reference's primitive, fragment count and
// edge bits per pixel, and its values and allowances where it covers.
void write_expectation(std::string& out, const Case& c, const Expectation& expected,
                       const Tolerance& tolerance,
                       const std::vector<compare::ChannelAllowance>& allowances,
                       const compare::UlpTable& ulps) {
  const Frame& f = expected.frame;
  const size_t pixels = f.pixel_count();
  const int components = c.component_count();
  out += kCVerdict;
  out += "\n/* ---- What the reference expects (glrefcheck's exact CPU rasterizer) ---- */\n";
  const bool counts = f.fragments.size() == pixels;
  out += "#define COUNTS_CHECKED " + std::to_string(int(counts)) + "\n";
  out += c_verdict_table(CoverageVerdictTable(counts, tolerance));
  out += "#define TRIANGLE_COUNT " + std::to_string(c.triangles.size()) + "\n";

  auto per_row = [&](const char* type, const char* array, const char* what, auto value) {
    out += "/* " + std::string(what) + ", per pixel, row by row from the bottom. */\n";
    out += std::string("static const ") + type + " " + array + "[PIXELS] = {";
    ListWriter w(out, "    ");
    for (int y = 0; y < f.height; ++y) {
      w.line_comment("y = " + std::to_string(y));
      for (int x = 0; x < f.width; ++x)
        w.item(value(f.index(x, y)));
    }
    w.finish();
    out += "};\n";
  };
  per_row("int", "REF_PRIMITIVE", "The reference's primitive (gl_PrimitiveID; -1: none)",
          [&](size_t i) { return std::to_string(f.primitive[i]); });
  per_row("unsigned short", "REF_FRAGMENTS", "How many fragments the reference writes",
          [&](size_t i) { return std::to_string(f.fragments.empty() ? 0 : f.fragments[i]); });
  const std::string edge_bits =
      "Edge bits (COVERAGE_VERDICT's row): " + std::to_string(edge::tie) +
      ", the centre lies exactly on an edge;\n   " + std::to_string(edge::snapping) +
      ", within the snapping band of an outer edge or clip plane; " + std::to_string(edge::shared) +
      ", within the snapping\n   band of an edge two triangles share; " +
      std::to_string(edge::unstable) + ", near a triangle the freedom may turn over; " +
      std::to_string(edge::depth_order) + ", another\n   fragment may win the depth test";
  per_row("unsigned char", "REF_EDGES", edge_bits.c_str(),
          [&](size_t i) { return std::to_string(expected.edges[i]); });

  // Values and allowances of the pixels the reference covers.
  size_t covered = 0;
  std::string values, allowed;
  {
    ListWriter v(values, "    "), a(allowed, "    ");
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x < f.width; ++x) {
        const size_t i = f.index(x, y);
        const int32_t p = f.primitive[i];
        if (p == Frame::kNoPrimitive) continue;
        ++covered;
        const std::string at = std::to_string(x) + ", " + std::to_string(y);
        v.line_comment(at);
        a.line_comment(at);
        for (Channel ch : channels_of(components)) {
          v.item(hex_literal(f.values(ch)[i]));
          a.item(hex_literal(allowances[ch.slot()].at(i, ulps.ulp(p, ch))));
        }
      }
    v.finish();
    a.finish();
  }
  out +=
      "/* At each pixel the reference covers (REF_PRIMITIVE >= 0), in pixel order: depth, then "
      "every\n   component (CHANNEL_NAMES)... */\n";
  out += "#define COVERED " + std::to_string(covered) + "\n";
  out += "static const float REF_VALUES[] = {" + values + "};\n";
  out +=
      "/* ...and the largest |GL - reference| a conforming implementation can produce there. */\n";
  out += "static const double REF_ALLOWED[] = {" + allowed + "};\n";
}

// The fragments that may win the depth test instead of the reference's, with what the
// comparator allows each.
void write_candidates(std::string& out, const Case& c, const Expectation& expected,
                      const std::vector<compare::ChannelAllowance>& allowances,
                      const compare::UlpTable& ulps) {
  const int components = c.component_count();
  out +=
      "/* Where another fragment may win the depth test (EDGE_DEPTH_ORDER): its primitive, "
      "depth and\n   components, and their allowances; sorted by pixel (y * FB_WIDTH + x). */\n";
  out += "#define CANDIDATE_COUNT " + std::to_string(expected.candidates.size()) + "\n";
  out += "static const struct candidate CANDIDATES[] = {\n";
  for (const Candidate& o : expected.candidates) {
    out += "    {" + std::to_string(o.pixel) + ", " + std::to_string(o.primitive) + ", {";
    out += hex_literal(o.depth);
    for (float v : o.values)
      out += ", " + hex_literal(v);
    out += "}, {";
    // What the comparator allows GL's fragment there when it is this candidate's.
    const compare::Judged as_candidate{true, &o};
    for (Channel ch : channels_of(components)) {
      const double a =
          as_candidate.allowed(allowances[ch.slot()], o.pixel, ulps.ulp(o.primitive, ch), ch);
      out += (ch.is_depth() ? "" : ", ") + hex_literal(a);
    }
    out += "}},\n";
  }
  if (expected.candidates.empty()) out += "    {-1, -1, {0}, {0}} /* none */\n";
  out += "};\n";
}

// The traces a conforming implementation may give where the edge bits excuse a count.
void write_traces(std::string& out, const CReproducerSetup& setup) {
  out +=
      "/* Where the edge bits excuse coverage (EDGE_SNAPPING, EDGE_UNSTABLE, EDGE_SHARED), the "
      "traces a\n   conforming implementation may give: fragments, the sum of p + 1 and the sum "
      "of a hash of p\n   over them (TRACES[first .. first + count)); sorted by pixel. A pixel "
      "not listed is not\n   judged by its trace. */\n";
  size_t listed = 0;
  std::string pixels_text, traces_text;
  for (const AdmittedTraces& a : setup.admitted) {
    pixels_text += "    {" + std::to_string(a.pixel) + ", " + std::to_string(listed) + ", " +
                   std::to_string(a.traces.size()) + "},\n";
    for (const FragmentTrace& t : a.traces)
      traces_text += "    {" + std::to_string(t.count) + ", " + std::to_string(t.id_sum) + ", " +
                     std::to_string(t.hash_sum) + "},\n";
    listed += a.traces.size();
  }
  if (setup.admitted.empty()) pixels_text = "    {-1, 0, 0} /* none */\n";
  if (listed == 0) traces_text = "    {0, 0, 0} /* none */\n";
  out += "#define TRACED_COUNT " + std::to_string(setup.admitted.size()) + "\n";
  out += "static const struct traced TRACED_PIXELS[] = {\n" + pixels_text + "};\n";
  out += "static const unsigned TRACES[][3] = {\n" + traces_text + "};\n";
  out += "static const struct trace_list TRACE_LIST = {TRACED_COUNT, TRACED_PIXELS, TRACES};\n";
}

}  // namespace

size_t reproducer_values(const Case& c) {
  return size_t(std::max(c.fb_width, 0)) * size_t(std::max(c.fb_height, 0)) *
         (3 + size_t(std::max(c.component_count(), 0)));
}

std::string c_compile_command(const std::string& file) {
  std::string program = file;
  if (program.size() > 2 && program.ends_with(".c")) program.resize(program.size() - 2);
  return "cc -std=c99 -O2 -o " + shell_word(program) + " " + shell_word(file) + " -ldl -lm";
}

std::string c_run_command(const std::string& file) {
  std::string program = file;
  if (program.size() > 2 && program.ends_with(".c")) program.resize(program.size() - 2);
  if (program.find('/') == std::string::npos) program = "./" + program;
  return shell_word(program);
}

std::string c_verdict_table(const CoverageVerdictTable& table) {
  using Observation = compare::CoverageObservation;
  std::string out;
  out +=
      "/* The coverage verdict, computed by glrefcheck with its comparator's rules for every "
      "value of the\n   edge bits (REF_EDGES): the label (enum label) by what GL kept (enum "
      "kept), its fragment\n   count against the reference's (enum count) and whether its "
      "fragment trace is admitted (0, 1). */\n";
  out += "static const verdict_row COVERAGE_VERDICT[" +
         std::to_string(CoverageVerdictTable::kEdgeBitValues) + "] = {\n";
  for (int edges = 0; edges < CoverageVerdictTable::kEdgeBitValues; ++edges) {
    out += "    {";
    for (int kept = 0; kept < compare::kKeptKinds; ++kept) {
      out += kept ? ", {" : "{";
      for (int count = 0; count < compare::kCountKinds; ++count) {
        const Observation seen{Observation::Kept(kept), Observation::Count(count)};
        out += (count ? ", {" : "{") + std::to_string(table.label(uint8_t(edges), seen, false)) +
               ", " + std::to_string(table.label(uint8_t(edges), seen, true)) + "}";
      }
      out += "}";
    }
    out += "}, /* " + std::to_string(edges) + " */\n";
  }
  out += "};\n";
  out +=
      "/* Whether a label fails this case (0: the specification's freedom explains it, and the "
      "case allows\n   that). */\n";
  out += "static const unsigned char LABEL_FAILS[] = {";
  for (int code = 0; code < kLabelCodes; ++code)
    out += (code ? ", " : "") + std::to_string(int(table.fails(uint8_t(code))));
  out += "};\n";
  return out;
}

std::string c_reproducer(const Case& c, const Expectation& expected, const Tolerance& tolerance,
                         const CReproducerSetup& setup) {
  check_inputs(c, expected, tolerance, setup);
  std::string out;
  out.reserve(expected.frame.pixel_count() * 64 + 65536);
  write_header(out, c, tolerance, setup);
  write_case(out, c, setup);
  const compare::UlpTable ulps(c);
  std::vector<compare::ChannelAllowance> allowances;
  for (Channel ch : channels_of(c.component_count()))
    allowances.emplace_back(c, expected, tolerance, ch);
  write_expectation(out, c, expected, tolerance, allowances, ulps);
  write_candidates(out, c, expected, allowances, ulps);
  write_traces(out, setup);
  const std::optional<std::string> outside = outside_specified_range(c);
  out += "/* Why the case asks for more than GL specifies, if it does. */\n";
  out += "static const char OUTSIDE_SPECIFIED_RANGE[] = " + c_string(outside.value_or("")) + ";\n";
  out +=
      "/* Whether the allowances are the specification's, whose infinite ones bound nothing. */\n";
  out += std::string("static const int SPEC_ALLOWANCE = ") +
         (tolerance.mode == ToleranceMode::spec ? "1" : "0") + ";\n";
  out += kCRuntime;
  return out;
}

}  // namespace glrc::reproducer
