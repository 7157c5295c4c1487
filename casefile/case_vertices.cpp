// The case schema, second part: the transform, the vertices and the triangles, the bulk of a
// large case. The hot path (a vertex's numbers) takes plain JSON numbers without building a
// field path; paths are made only for a message.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "casefile/case_schema.hpp"
#include "core/primitive_assembly.hpp"

namespace glrc::casefile {
namespace {

using typed_json::fmt_double;
using typed_json::json_quoted;
using typed_json::kFloatOverflow;
using typed_json::path_index;
using typed_json::path_key;

}  // namespace

std::vector<TransformOp> Loader::load_ops(const CaseJson& list, const std::string& path) const {
  if (!list.is_array()) r_.fail(path, "an array of operations", Reader::describe(list));
  std::vector<TransformOp> ops;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = path_index(path, i);
    const CaseJson& op = r_.object(list[i], p);
    if (op.size() != 1)
      r_.fail(p, "an object with exactly one of the keys translate, rotate, scale, look_at",
              std::to_string(op.size()) + " keys");
    r_.check_keys(op, p, {"translate", "rotate", "scale", "look_at"});
    const std::string& key = op.begin().key();
    const CaseJson& value = op.begin().value();
    const std::string vp = path_key(p, key);
    TransformOp o;
    if (key == "translate") {
      o.kind = TransformOp::Kind::translate;
      o.v = vec3(value, vp);
    } else if (key == "scale") {
      o.kind = TransformOp::Kind::scale;
      o.v = vec3(value, vp);
    } else if (key == "rotate") {
      o.kind = TransformOp::Kind::rotate;
      r_.object(value, vp);
      r_.check_keys(value, vp, {"degrees", "axis"});
      o.degrees =
          r_.float32(r_.required(value, vp, "degrees", "a number"), path_key(vp, "degrees"));
      o.v = vec3(r_.required(value, vp, "axis", "3 numbers"), path_key(vp, "axis"));
      if (o.v[0] == 0 && o.v[1] == 0 && o.v[2] == 0)
        r_.fail(path_key(vp, "axis"), "a non-zero axis", "[0, 0, 0]");
    } else {
      o.kind = TransformOp::Kind::look_at;
      r_.object(value, vp);
      r_.check_keys(value, vp, {"eye", "center", "up"});
      o.v = vec3(r_.required(value, vp, "eye", "3 numbers"), path_key(vp, "eye"));
      o.center = vec3(r_.required(value, vp, "center", "3 numbers"), path_key(vp, "center"));
      o.up = vec3(r_.required(value, vp, "up", "3 numbers"), path_key(vp, "up"));
      const double f[3] = {o.center[0] - o.v[0], o.center[1] - o.v[1], o.center[2] - o.v[2]};
      if (f[0] == 0 && f[1] == 0 && f[2] == 0)
        r_.fail(path_key(vp, "center"), "a point other than eye", "the eye's position");
      const double s[3] = {f[1] * o.up[2] - f[2] * o.up[1], f[2] * o.up[0] - f[0] * o.up[2],
                           f[0] * o.up[1] - f[1] * o.up[0]};
      if (s[0] == 0 && s[1] == 0 && s[2] == 0)
        r_.fail(path_key(vp, "up"), "a direction not parallel to center - eye", "a parallel one");
    }
    ops.push_back(o);
  }
  return ops;
}

Projection Loader::load_projection(const CaseJson& p, const std::string& path) const {
  r_.object(p, path);
  if (p.size() != 1)
    r_.fail(path, "an object with exactly one of the keys perspective, frustum, ortho",
            std::to_string(p.size()) + " keys");
  r_.check_keys(p, path, {"perspective", "frustum", "ortho"});
  const std::string& key = p.begin().key();
  const CaseJson& value = p.begin().value();
  const std::string vp = path_key(path, key);
  r_.object(value, vp);
  Projection out;
  auto get = [&](std::string_view k) -> double {
    return r_.float32(r_.required(value, vp, k, "a number"), path_key(vp, k));
  };
  if (key == "perspective") {
    r_.check_keys(value, vp, {"fovy_degrees", "aspect", "near", "far"});
    out.kind = Projection::Kind::perspective;
    out.p = {get("fovy_degrees"), get("aspect"), get("near"), get("far"), 0, 0};
    if (!(out.p[0] > 0 && out.p[0] < 180))
      r_.fail(path_key(vp, "fovy_degrees"), "a number in (0, 180)", fmt_double(out.p[0]));
    if (!(out.p[1] > 0)) r_.fail(path_key(vp, "aspect"), "a number > 0", fmt_double(out.p[1]));
  } else {
    r_.check_keys(value, vp, {"left", "right", "bottom", "top", "near", "far"});
    out.kind = key == "frustum" ? Projection::Kind::frustum : Projection::Kind::ortho;
    out.p = {get("left"), get("right"), get("bottom"), get("top"), get("near"), get("far")};
    if (out.p[0] == out.p[1])
      r_.fail(path_key(vp, "right"), "a value other than left", fmt_double(out.p[1]));
    if (out.p[2] == out.p[3])
      r_.fail(path_key(vp, "top"), "a value other than bottom", fmt_double(out.p[3]));
  }
  const double n = key == "perspective" ? out.p[2] : out.p[4];
  const double f = key == "perspective" ? out.p[3] : out.p[5];
  if (key != "ortho") {
    // A perspective divide by the eye distance needs both planes in front of the eye.
    if (!(n > 0)) r_.fail(path_key(vp, "near"), "a number > 0", fmt_double(n));
    if (!(f > 0)) r_.fail(path_key(vp, "far"), "a number > 0", fmt_double(f));
  }
  if (n == f) r_.fail(path_key(vp, "far"), "a value other than near", fmt_double(f));
  return out;
}

std::optional<Transform> Loader::load_transform(const CaseJson& t) const {
  r_.object(t, "transform");
  r_.check_keys(t, "transform", {"model", "view", "projection"});
  Transform out;
  if (const CaseJson* m = Reader::find(t, "model")) out.model = load_ops(*m, "transform.model");
  if (const CaseJson* v = Reader::find(t, "view")) out.view = load_ops(*v, "transform.view");
  if (const CaseJson* p = Reader::find(t, "projection"))
    out.projection = load_projection(*p, "transform.projection");
  return out;
}

void Loader::load_distances(const CaseJson& v, size_t i, Vertex& vertex, Case& c) const {
  // The first vertex sets how many of each there are; every other must have as many.
  std::vector<float> f;
  for (const bool clip : {true, false}) {
    const char* key = clip ? "clip_distance" : "cull_distance";
    int& count = clip ? c.distances.clip : c.distances.cull;
    const CaseJson* d = Reader::find(v, key);
    const auto path = [&] { return path_key(path_index("vertices", i), key); };
    if (i == 0) {
      if (d) {
        if (!d->is_array() || d->empty() || d->size() > size_t(kMaxDistances))
          r_.fail(path(), "an array of 1 to 8 numbers", Reader::describe(*d));
        count = int(d->size());
      }
    } else if (count == 0 ? d != nullptr
                          : d == nullptr || !d->is_array() || d->size() != size_t(count)) {
      r_.fail(path(),
              count == 0 ? "nothing, as vertex 0 has no " + std::string(key)
                         : std::to_string(count) + " numbers, as vertex 0 has",
              d ? Reader::describe(*d) : "nothing");
    }
    if (!d) continue;
    f.clear();
    r_.float32s_into(*d, path, {size_t(count)}, f);
    for (size_t k = 0; k < f.size(); ++k)
      if (!std::isfinite(f[k]))
        r_.fail(path_index(path(), k), "a finite number", Reader::describe((*d)[k]));
    // The clip distances first (this loop's order), then the cull distances.
    vertex.distances.insert(vertex.distances.end(), f.begin(), f.end());
  }
  if (i == 0 && c.distances.clip + c.distances.cull > kMaxDistances)
    r_.fail(path_index("vertices", 0),
            "at most 8 clip and cull distances together (GL_MAX_COMBINED_CLIP_AND_CULL_DISTANCES)",
            std::to_string(c.distances.clip + c.distances.cull));
}

void Loader::load_vertices(const CaseJson& list, const std::optional<Transform>& transform,
                           Case& c) const {
  if (!list.is_array() || list.empty())
    r_.fail("vertices", "a non-empty array of vertex objects", Reader::describe(list));
  // Positions are transformed together once all are read, so that one matrix set serves all.
  std::vector<size_t> from_position;
  std::vector<std::array<double, 4>> positions;
  c.vertices.reserve(list.size());
  const size_t components = size_t(c.component_count());
  for (size_t i = 0; i < list.size(); ++i) {
    // Field paths are made only for a message: a large case has millions of fields.
    const auto path = [&] { return path_index("vertices", i); };
    const CaseJson& v = list[i];
    if (!v.is_object()) r_.object(v, path());
    // Allowed keys: clip, position, and the varyings' names.
    for (const auto& [key, value] : v.items()) {
      if (key == "clip" || key == "position" || key == "clip_distance" || key == "cull_distance")
        continue;
      // A named reference: Clang before 16 cannot capture a structured binding.
      const std::string& name = key;
      const bool varying =
          std::any_of(c.varyings.begin(), c.varyings.end(),
                      [&](const Varying& var) { return var.name == name && !var.is_builtin(); });
      if (!varying) {
        std::string keys = "clip, position, clip_distance, cull_distance";
        for (const auto& var : c.varyings)
          if (!var.is_builtin()) keys += ", " + var.name;
        r_.fail(path_key(path(), key), "one of the keys " + keys + " (varyings must be declared)",
                "unknown key " + json_quoted(key));
      }
    }
    Vertex vertex;
    const CaseJson* clip = Reader::find(v, "clip");
    const CaseJson* pos = Reader::find(v, "position");
    if (clip && pos) r_.fail(path(), "exactly one of clip, position", "both");
    if (!clip && !pos) r_.fail(path(), "exactly one of clip, position", "neither");
    std::vector<float> f;
    if (clip) {
      r_.float32s_into(
          *clip, [&] { return path_key(path(), "clip"); }, {4}, f);
      vertex.clip = {f[0], f[1], f[2], f[3]};
    } else {
      if (!transform)
        r_.fail(path_key(path(), "position"),
                "clip coordinates, or a \"transform\" in the case to use position", "no transform");
      r_.float32s_into(
          *pos, [&] { return path_key(path(), "position"); }, {3, 4}, f);
      positions.push_back({f[0], f[1], f[2], f.size() == 4 ? double(f[3]) : 1.0});
      from_position.push_back(i);
    }
    vertex.values.reserve(components);
    for (const auto& var : c.varyings) {
      if (var.is_builtin()) {  // no value per vertex (core/case.hpp)
        vertex.values.insert(vertex.values.end(), size_t(var.size), 0.0f);
        continue;
      }
      const auto vp = [&] { return path_key(path(), var.name); };
      const auto what = [&] {
        return var.size == 1 ? "a number (varying " + var.name + ")"
                             : std::to_string(var.size) + " numbers (varying " + var.name + ")";
      };
      const CaseJson* value = Reader::find(v, var.name);
      if (!value) r_.fail(vp(), what(), "nothing (every vertex needs every varying)");
      if (var.size == 1 && !value->is_array()) {
        const auto x = Reader::plain_float32(*value);
        vertex.values.push_back(x ? *x : r_.float32(*value, vp()));
      } else {
        if (!value->is_array()) r_.fail(vp(), what(), Reader::describe(*value));
        if (value->size() != size_t(var.size)) r_.fail(vp(), what(), std::to_string(value->size()));
        for (size_t k = 0; k < value->size(); ++k) {
          const auto x = Reader::plain_float32((*value)[k]);
          vertex.values.push_back(x ? *x : r_.float32((*value)[k], path_index(vp(), k)));
        }
      }
    }
    load_distances(v, i, vertex, c);
    c.vertices.push_back(std::move(vertex));
  }
  if (!positions.empty()) {
    const auto clips = to_clip(*transform, positions);
    for (size_t k = 0; k < clips.size(); ++k) {
      const std::string path = path_key(path_index("vertices", from_position[k]), "position");
      std::array<float, 4>& out = c.vertices[from_position[k]].clip;
      for (int j = 0; j < 4; ++j) {
        const double d = clips[k][j];
        if (!(std::fabs(d) < kFloatOverflow))
          r_.fail(path, "clip coordinates finite in float32 after the transform",
                  "clip[" + std::to_string(j) + "] = " + fmt_double(d));
        // The one rounding from the double transform to the float32 gl_Position.
        out[j] =
            std::fabs(d) > double(std::numeric_limits<float>::max())
                ? (d < 0 ? -std::numeric_limits<float>::max() : std::numeric_limits<float>::max())
                : static_cast<float>(d);
      }
    }
  }
}

void Loader::load_triangles(const CaseJson* list, Case& c) const {
  const size_t n = c.vertices.size();
  if (!list) {
    if (n % 3 != 0)
      r_.fail("vertices",
              "a multiple of 3 vertices (consecutive triples, as \"triangles\" is absent)",
              std::to_string(n));
    for (uint32_t i = 0; i + 2 < n; i += 3)
      c.triangles.push_back({i, i + 1, i + 2});
    return;
  }
  if (!list->is_array() || list->empty())
    r_.fail("triangles", "a non-empty array of [i, j, k] index triples", Reader::describe(*list));
  const std::string what = "an integer index in 0.." + std::to_string(n - 1);
  for (size_t t = 0; t < list->size(); ++t) {
    const std::string path = path_index("triangles", t);
    const CaseJson& tri = (*list)[t];
    if (!tri.is_array()) r_.fail(path, "3 vertex indices", Reader::describe(tri));
    if (tri.size() != 3) r_.fail(path, "3 vertex indices", std::to_string(tri.size()));
    std::array<uint32_t, 3> idx{};
    for (size_t k = 0; k < 3; ++k) {
      const long long i =
          r_.integer(tri[k], path_index(path, k), 0, static_cast<long long>(n) - 1, what);
      idx[k] = static_cast<uint32_t>(i);
    }
    c.triangles.push_back(idx);
  }
}

// GL specifies noperspective interpolation in window coordinates, which a triangle reaching
// behind the eye (w_c <= 0 at a vertex) does not have: the projected triangle is not the visible
// region, and the spec leaves the result undefined. Such a case could not have a reference.
// gl_FragCoord is not interpolated from vertex values: its z_w and 1/w_c are the fragment's own,
// defined wherever a fragment is, behind-the-eye triangles included (as the depth is).
void Loader::check_noperspective(const Case& c) const {
  auto np = std::find_if(c.varyings.begin(), c.varyings.end(), [](const Varying& v) {
    return v.interpolation == Interpolation::noperspective && !v.is_builtin();
  });
  if (np == c.varyings.end()) return;
  // Where a triangle came from, for the message: its entry of "triangles", or its draw.
  const std::vector<uint32_t> first =
      c.draws.empty() ? std::vector<uint32_t>() : assemble(c.draws, c.provoking).first_triangle;
  auto where = [&](size_t t) {
    if (first.empty()) return path_index("triangles", t);
    size_t d = 0;
    while (first[d + 1] <= t)
      ++d;
    return path_index("draws", d) + " (its triangle " + std::to_string(t - first[d]) + ")";
  };
  for (size_t t = 0; t < c.triangles.size(); ++t) {
    for (uint32_t i : c.triangles[t]) {
      const float w = c.vertices[i].clip[3];
      if (w <= 0.0f)
        r_.fail(where(t),
                "w_c > 0 at every vertex, because varying " + json_quoted(np->name) +
                    " is noperspective and GL leaves screen-linear interpolation undefined for "
                    "triangles reaching behind the eye",
                "w_c = " + fmt_double(w) + " at vertex " + std::to_string(i));
    }
  }
}

}  // namespace glrc::casefile
