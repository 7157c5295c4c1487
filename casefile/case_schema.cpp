// The case schema, first part: the top level, geometry, state, varyings and tolerance (the
// vertices and the transform are in case_vertices.cpp). Every error is one line through the
// typed reader, "<file>: <field path>: expected <what>, got <what>"; unknown keys are errors
// everywhere: a misspelt optional field would otherwise silently take its default.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <string_view>

#include "casefile/case_schema.hpp"

namespace glrc::casefile {
namespace {

using typed_json::path_index;
using typed_json::path_key;

constexpr double kMaxDouble = std::numeric_limits<double>::max();

}  // namespace

// The x, y, width, height of the scissor box: integers, origins within ±kMaxViewport, sizes
// from 0 to kMaxViewport.
Scissor Loader::load_scissor(const CaseJson& o) const {
  const std::string name = "scissor";
  r_.object(o, name);
  r_.check_keys(o, name, {"x", "y", "width", "height"});
  const std::string origin =
      "an integer in " + std::to_string(-kMaxViewport) + ".." + std::to_string(kMaxViewport - 1);
  const std::string extent = "an integer in 0.." + std::to_string(kMaxViewport);
  auto field = [&](const char* key, const std::string& what, int lo, int hi) {
    return int_in(r_.required(o, name, key, what), path_key(name, key), lo, hi);
  };
  Scissor r;
  r.x = field("x", origin, -kMaxViewport, kMaxViewport - 1);
  r.y = field("y", origin, -kMaxViewport, kMaxViewport - 1);
  r.width = field("width", extent, 0, kMaxViewport);
  r.height = field("height", extent, 0, kMaxViewport);
  return r;
}

// The viewport's x, y, width, height: numbers (or decimal strings), each rounded to float32
// once as glViewportIndexedf takes them; whole numbers are glViewport's. Origins within
// ±kMaxViewport, sizes from 1 to kMaxViewport.
Viewport Loader::load_viewport(const CaseJson& o) const {
  const std::string name = "viewport";
  r_.object(o, name);
  r_.check_keys(o, name, {"x", "y", "width", "height"});
  const std::string origin =
      "a number in " + std::to_string(-kMaxViewport) + ".." + std::to_string(kMaxViewport - 1);
  const std::string extent = "a number in 1.." + std::to_string(kMaxViewport);
  auto field = [&](const char* key, const std::string& what, double lo, double hi) {
    const CaseJson& v = r_.required(o, name, key, what);
    const std::string path = path_key(name, key);
    const float f = r_.float32(v, path);
    if (!(f >= lo && f <= hi)) r_.fail(path, what, Reader::describe(v));
    return f;
  };
  Viewport r;
  r.x = field("x", origin, -kMaxViewport, kMaxViewport - 1);
  r.y = field("y", origin, -kMaxViewport, kMaxViewport - 1);
  r.width = field("width", extent, 1, kMaxViewport);
  r.height = field("height", extent, 1, kMaxViewport);
  return r;
}

void Loader::load_geometry(const CaseJson& root, Case& c) const {
  const CaseJson* fb = Reader::find(root, "framebuffer");
  const CaseJson* vp = Reader::find(root, "viewport");
  if (fb) {
    r_.object(*fb, "framebuffer");
    r_.check_keys(*fb, "framebuffer", {"width", "height"});
    c.fb_width = int_in(r_.required(*fb, "framebuffer", "width", "an integer in 1..4096"),
                        "framebuffer.width", 1, kMaxSize);
    c.fb_height = int_in(r_.required(*fb, "framebuffer", "height", "an integer in 1..4096"),
                         "framebuffer.height", 1, kMaxSize);
  }
  if (vp) {
    const Viewport v = load_viewport(*vp);
    // With a framebuffer the viewport may reach beyond it (only its pixels are drawn).
    // Without one the framebuffer is the viewport's extent, which must itself be a legal size.
    if (!fb) {
      if (v.x < 0 || v.y < 0 || v.x + v.width > kMaxSize || v.y + v.height > kMaxSize)
        r_.fail("framebuffer",
                "a framebuffer, as the viewport reaches outside 0..4096 and cannot give its size",
                "none");
      c.fb_width = int(std::ceil(v.x + v.width));
      c.fb_height = int(std::ceil(v.y + v.height));
    }
    c.viewport = v;
  } else {
    c.viewport = Viewport{0, 0, c.fb_width, c.fb_height};
  }
  if (const CaseJson* sc = Reader::find(root, "scissor")) {
    c.scissor = load_scissor(*sc);
  }

  if (const CaseJson* dr = Reader::find(root, "depth_range")) {
    r_.object(*dr, "depth_range");
    r_.check_keys(*dr, "depth_range", {"near", "far"});
    auto read = [&](std::string_view key, float def) {
      const CaseJson* v = Reader::find(*dr, key);
      if (!v) return def;
      const std::string path = path_key("depth_range", key);
      const float f = r_.float32(*v, path);
      if (!(f >= 0.0f && f <= 1.0f)) r_.fail(path, "a number in [0, 1]", Reader::describe(*v));
      return f;
    };
    c.depth_near = read("near", 0.0f);
    c.depth_far = read("far", 1.0f);
  }
}

void Loader::load_state(const CaseJson& state, Case& c) const {
  r_.object(state, "state");
  r_.check_keys(state, "state",
                {"cull", "front_face", "provoking_vertex", "depth_func", "depth_clear",
                 "clip_origin", "clip_depth", "depth_clamp"});
  if (const CaseJson* v = Reader::find(state, "cull")) c.cull = r_.name<CullFace>(*v, "state.cull");
  if (const CaseJson* v = Reader::find(state, "front_face"))
    c.front_face = r_.name<FrontFace>(*v, "state.front_face");
  if (const CaseJson* v = Reader::find(state, "provoking_vertex"))
    c.provoking = r_.name<ProvokingVertex>(*v, "state.provoking_vertex");
  if (const CaseJson* v = Reader::find(state, "clip_origin"))
    c.clip_origin = r_.name<ClipOrigin>(*v, "state.clip_origin");
  if (const CaseJson* v = Reader::find(state, "clip_depth"))
    c.clip_depth = r_.name<ClipDepth>(*v, "state.clip_depth");
  if (const CaseJson* v = Reader::find(state, "depth_func"))
    c.depth_func = r_.name<DepthFunc>(*v, "state.depth_func");
  if (const CaseJson* v = Reader::find(state, "depth_clear")) {
    c.depth_clear = r_.float32(*v, "state.depth_clear");
    if (!(c.depth_clear >= 0.0f && c.depth_clear <= 1.0f))
      r_.fail("state.depth_clear", "a number in [0, 1]", Reader::describe(*v));
  }
  if (const CaseJson* v = Reader::find(state, "depth_clamp")) {
    if (!v->is_boolean())
      r_.fail("state.depth_clamp", "true or false (GL_DEPTH_CLAMP)", Reader::describe(*v));
    c.depth_clamp = v->get<bool>();
  }
}

PolygonOffset Loader::load_polygon_offset(const CaseJson& o) const {
  r_.object(o, "polygon_offset");
  r_.check_keys(o, "polygon_offset", {"factor", "units", "clamp"});
  PolygonOffset p;
  // Each a finite float32 (glPolygonOffset's GLfloats; Inf or NaN would make every offset so).
  auto read = [&](std::string_view key) -> std::optional<float> {
    const CaseJson* v = Reader::find(o, key);
    if (!v) return std::nullopt;
    const std::string path = path_key("polygon_offset", key);
    const float f = r_.float32(*v, path);
    if (!std::isfinite(f)) r_.fail(path, "a finite number", Reader::describe(*v));
    return f;
  };
  p.factor = read("factor").value_or(0.0f);
  p.units = read("units").value_or(0.0f);
  p.clamp = read("clamp");
  return p;
}

namespace {

// GLSL keywords and reserved words (GLSL 4.60 section 3.6, plus a few type names): a varying
// named after one would not compile in the harness's shaders.
bool glsl_reserved(const std::string& name) {
  static const std::set<std::string, std::less<>> kWords = {
      "active",     "asm",       "atomic_uint", "attribute",   "bool",       "break",
      "buffer",     "bvec2",     "bvec3",       "bvec4",       "case",       "cast",
      "centroid",   "class",     "coherent",    "common",      "const",      "continue",
      "default",    "discard",   "dmat2",       "dmat2x2",     "dmat2x3",    "dmat2x4",
      "dmat3",      "dmat3x2",   "dmat3x3",     "dmat3x4",     "dmat4",      "dmat4x2",
      "dmat4x3",    "dmat4x4",   "do",          "double",      "dvec2",      "dvec3",
      "dvec4",      "else",      "enum",        "extern",      "external",   "false",
      "filter",     "fixed",     "flat",        "float",       "for",        "fvec2",
      "fvec3",      "fvec4",     "goto",        "half",        "highp",      "hvec2",
      "hvec3",      "hvec4",     "if",          "iimage1D",    "iimage2D",   "iimage3D",
      "image1D",    "image2D",   "image3D",     "in",          "inline",     "inout",
      "input",      "int",       "interface",   "invariant",   "isampler1D", "isampler2D",
      "isampler3D", "ivec2",     "ivec3",       "ivec4",       "layout",     "long",
      "lowp",       "main",      "mat2",        "mat2x2",      "mat2x3",     "mat2x4",
      "mat3",       "mat3x2",    "mat3x3",      "mat3x4",      "mat4",       "mat4x2",
      "mat4x3",     "mat4x4",    "mediump",     "namespace",   "noinline",   "noperspective",
      "out",        "output",    "partition",   "patch",       "precise",    "precision",
      "public",     "readonly",  "resource",    "restrict",    "return",     "sample",
      "sampler1D",  "sampler2D", "sampler3D",   "samplerCube", "short",      "sizeof",
      "smooth",     "static",    "struct",      "subroutine",  "superp",     "switch",
      "template",   "this",      "true",        "typedef",     "uimage1D",   "uimage2D",
      "uimage3D",   "uint",      "union",       "unsigned",    "usampler1D", "usampler2D",
      "usampler3D", "using",     "uvec2",       "uvec3",       "uvec4",      "varying",
      "vec2",       "vec3",      "vec4",        "void",        "volatile",   "while",
      "writeonly"};
  return kWords.count(name) > 0;
}

}  // namespace

void Loader::load_varyings(const CaseJson& list, Case& c) const {
  if (!list.is_array()) r_.fail("varyings", "an array of 0 to 7 varyings", Reader::describe(list));
  if (list.size() > kMaxVaryings)
    r_.fail("varyings", "at most 7 varyings", std::to_string(list.size()));
  std::set<std::string> seen;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = path_index("varyings", i);
    const CaseJson& v = r_.object(list[i], path);
    if (const CaseJson* b = Reader::find(v, "builtin")) {
      c.varyings.push_back(load_builtin(v, *b, path));
      if (!seen.insert(c.varyings.back().name).second)
        r_.fail(path_key(path, "builtin"), "a built-in not listed before", Reader::describe(*b));
      continue;
    }
    for (const char* layout : {"origin_upper_left", "pixel_center_integer"})
      if (const CaseJson* q = Reader::find(v, layout))
        r_.fail(path_key(path, layout), "a \"builtin\" beside it (gl_FragCoord's layout qualifier)",
                Reader::describe(*q));
    r_.check_keys(v, path, {"name", "size", "interpolation"});
    Varying var;
    const CaseJson& name = r_.required(v, path, "name", "a GLSL identifier");
    if (!name.is_string())
      r_.fail(path_key(path, "name"), "a GLSL identifier", Reader::describe(name));
    var.name = name.get<std::string>();
    const std::string& n = var.name;
    const bool identifier = !n.empty() &&
                            (std::isalpha(static_cast<unsigned char>(n[0])) || n[0] == '_') &&
                            std::all_of(n.begin(), n.end(), [](char ch) {
                              return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
                            });
    if (!identifier || n.size() > 64)
      r_.fail(path_key(path, "name"),
              "a GLSL identifier ([A-Za-z_][A-Za-z0-9_]*, at most 64 chars)",
              Reader::describe(name));
    if (n.rfind("gl_", 0) == 0)
      r_.fail(path_key(path, "name"), "a name not starting with \"gl_\" (reserved by GLSL)",
              Reader::describe(name));
    if (n.find("__") != std::string::npos)
      r_.fail(path_key(path, "name"), "a name without \"__\" (reserved by GLSL)",
              Reader::describe(name));
    if (glsl_reserved(n))
      r_.fail(path_key(path, "name"), "a name that is not a GLSL keyword", Reader::describe(name));
    // A vertex object holds "clip"/"position" and the distances beside the varyings' names.
    if (n == "clip" || n == "position" || n == "clip_distance" || n == "cull_distance")
      r_.fail(path_key(path, "name"),
              "a name other than clip, position, clip_distance and cull_distance (vertex keys)",
              Reader::describe(name));
    if (!seen.insert(n).second)
      r_.fail(path_key(path, "name"), "a name not used by another varying", Reader::describe(name));
    if (const CaseJson* size = Reader::find(v, "size"))
      var.size = int_in(*size, path_key(path, "size"), 1, 4);
    if (const CaseJson* interp = Reader::find(v, "interpolation"))
      var.interpolation = r_.name<Interpolation>(*interp, path_key(path, "interpolation"));
    c.varyings.push_back(var);
  }
}

Varying Loader::load_builtin(const CaseJson& v, const CaseJson& builtin,
                             const std::string& path) const {
  const Builtin b = r_.name<Builtin>(builtin, path_key(path, "builtin"));
  if (b == Builtin::front_facing) {
    r_.check_keys(v, path, {"builtin"});
    return builtin_varying(b);
  }
  r_.check_keys(v, path, {"builtin", "origin_upper_left", "pixel_center_integer"});
  FragCoordLayout layout;
  if (const CaseJson* o = Reader::find(v, "origin_upper_left"))
    layout.origin_upper_left = r_.boolean(*o, path_key(path, "origin_upper_left"));
  if (const CaseJson* p = Reader::find(v, "pixel_center_integer"))
    layout.pixel_center_integer = r_.boolean(*p, path_key(path, "pixel_center_integer"));
  return builtin_varying(b, layout);
}

void Loader::load_enabled_clip_distances(const CaseJson* list, Case& c) const {
  const uint32_t all = c.distances.clip == 0 ? 0u : (1u << c.distances.clip) - 1u;
  if (!list) {
    c.distances.enabled = all;  // every distance written is enabled
    return;
  }
  const std::string what =
      "an array of clip plane numbers, each below the vertices' clip_distance count (" +
      std::to_string(c.distances.clip) + ")";
  if (!list->is_array()) r_.fail("enabled_clip_distances", what, Reader::describe(*list));
  if (c.distances.clip == 0 && !list->empty())
    r_.fail("enabled_clip_distances", what, "plane numbers, but no vertex has a clip_distance");
  c.distances.enabled = 0;
  for (size_t i = 0; i < list->size(); ++i) {
    const std::string path = path_index("enabled_clip_distances", i);
    const int plane = int_in((*list)[i], path, 0, c.distances.clip - 1);
    if (c.distances.enabled >> plane & 1u)
      r_.fail(path, "a plane not listed before", "plane " + std::to_string(plane) + " again");
    c.distances.enabled |= 1u << plane;
  }
}

void Loader::load_tolerance(const CaseJson& t, Case& c) const {
  r_.object(t, "tolerance");
  r_.check_keys(t, "tolerance", {"varying_ulps", "depth_ulps", "allow_boundary"});
  if (const CaseJson* v = Reader::find(t, "varying_ulps"))
    c.tolerance.varying_ulps =
        r_.number(*v, "tolerance.varying_ulps", 0, kMaxDouble, "a finite number >= 0");
  if (const CaseJson* v = Reader::find(t, "depth_ulps"))
    c.tolerance.depth_ulps =
        r_.number(*v, "tolerance.depth_ulps", 0, kMaxDouble, "a finite number >= 0");
  if (const CaseJson* v = Reader::find(t, "allow_boundary")) {
    if (!v->is_boolean())
      r_.fail("tolerance.allow_boundary", "true or false", Reader::describe(*v));
    c.tolerance.allow_boundary = v->get<bool>();
  }
}

Case Loader::load(const CaseJson& root) const {
  Case c;
  c.source_path = r_.source();
  if (!root.is_object()) r_.fail("", "a JSON object at the top level", Reader::describe(root));
  r_.check_keys(root, "",
                {"description", "framebuffer", "viewport", "scissor", "depth_range", "state",
                 "varyings", "enabled_clip_distances", "transform", "vertices", "triangles",
                 "draws", "tolerance", "work_arounds", "written_by", "polygon_offset"});
  // What wrote the file, with its stamp (cli's fuzz; report/stamp.hpp): for whoever writes it
  // again, nothing the case draws.
  if (const CaseJson* w = Reader::find(root, "written_by"); w && !w->is_string())
    r_.fail("written_by", "a string (what wrote this file, and its stamp)", Reader::describe(*w));

  const CaseJson& desc = r_.required(root, "", "description", "a one-line string");
  // Printed on terminals by list, diff and run: a control character (a line break, an escape
  // sequence, a NUL) would break the line or drive the terminal.
  if (!desc.is_string() || desc.get_ref<const std::string&>().empty() ||
      std::any_of(desc.get_ref<const std::string&>().begin(),
                  desc.get_ref<const std::string&>().end(),
                  [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; }))
    r_.fail("description", "a non-empty one-line string without control characters",
            Reader::describe(desc));
  c.description = desc.get<std::string>();

  load_geometry(root, c);
  if (const CaseJson* s = Reader::find(root, "state")) load_state(*s, c);
  if (const CaseJson* o = Reader::find(root, "polygon_offset"))
    c.polygon_offset = load_polygon_offset(*o);
  if (const CaseJson* v = Reader::find(root, "varyings")) load_varyings(*v, c);
  std::optional<Transform> transform;
  if (const CaseJson* t = Reader::find(root, "transform")) transform = load_transform(*t);
  load_vertices(r_.required(root, "", "vertices", "an array of vertices"), transform, c);
  if (const CaseJson* d = Reader::find(root, "draws")) {
    if (Reader::find(root, "triangles"))
      r_.fail("triangles", "either \"triangles\" or \"draws\", not both", "both");
    load_draws(*d, c);
  } else {
    load_triangles(Reader::find(root, "triangles"), c);
  }
  check_noperspective(c);
  load_enabled_clip_distances(Reader::find(root, "enabled_clip_distances"), c);
  if (const CaseJson* t = Reader::find(root, "tolerance")) load_tolerance(*t, c);
  if (const CaseJson* w = Reader::find(root, "work_arounds")) {
    if (!w->is_boolean())
      r_.fail("work_arounds", "true or false (whether the harness may work around a driver bug)",
              Reader::describe(*w));
    c.work_arounds = w->get<bool>();
  }
  return c;
}

// What a field holds, for a number that overflows a double, which the parser meets before the
// loader sees the field.
std::string expected_number_at(const std::string& path) {
  const auto ends_with = [&](std::string_view tail) {
    return path.size() >= tail.size() &&
           path.compare(path.size() - tail.size(), tail.size(), tail) == 0;
  };
  if (path == "framebuffer.width" || path == "framebuffer.height")
    return "an integer in 1.." + std::to_string(kMaxSize);
  if (path == "viewport.width" || path == "viewport.height")
    return "a number in 1.." + std::to_string(kMaxViewport);
  if (path == "viewport.x" || path == "viewport.y")
    return "a number in " + std::to_string(-kMaxViewport) + ".." + std::to_string(kMaxViewport - 1);
  if (path == "scissor.width" || path == "scissor.height")
    return "an integer in 0.." + std::to_string(kMaxViewport);
  if (path == "scissor.x" || path == "scissor.y")
    return "an integer in " + std::to_string(-kMaxViewport) + ".." +
           std::to_string(kMaxViewport - 1);
  if (path.rfind("varyings[", 0) == 0 && ends_with(".size")) return "an integer in 1..4";
  if (path.rfind("triangles[", 0) == 0) return "a vertex index (an integer)";
  if (path.rfind("draws[", 0) == 0) return "an integer";
  if (path.rfind("tolerance.", 0) == 0) return "a finite number >= 0";
  return "a number within float32 range";
}

}  // namespace glrc::casefile
