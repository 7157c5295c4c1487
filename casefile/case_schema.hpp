// The case schema: a parsed case file's document read into a Case, each field checked as
// cases/README.md describes it (case_schema.cpp: the top level, geometry, state, varyings and
// tolerance; case_vertices.cpp: the transform, vertices and triangles). Internal to casefile/:
// casefile.cpp reads and parses the file (typed_json/document.hpp) and hands the document here.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "casefile/transform.hpp"
#include "core/case.hpp"
#include "typed_json/arena.hpp"
#include "typed_json/reader.hpp"

namespace glrc::casefile {

// A case file's document: arena-allocated (typed_json/arena.hpp), since a large case is
// millions of small containers.
using CaseJson = typed_json::ArenaJson;

inline constexpr int kMaxSize = 4096;  // framebuffer extent
// Viewport and scissor extent, and the bound of their origins (-16384..16383): GL_MAX_VIEWPORT_DIMS
// of Mesa's software drivers, so a window position stays below 2^15 (ref/freedom.hpp's rounding).
inline constexpr int kMaxViewport = 16384;
inline constexpr size_t kMaxVaryings = 7;  // 8 color attachments, one holds gl_PrimitiveID

// What the case field at `path` holds, for a number beyond double range there, which the
// parser meets before the schema sees the field ("an integer in 1..4096", "a vertex index (an
// integer)", ...; "a number within float32 range" for the numbers of vertices and transforms).
std::string expected_number_at(const std::string& path);

// Reads `root` into a Case (its source_path the reader's source; its name is the caller's).
// Every error goes through `r` (Wording::full): "<file>: <field path>: expected <what>, got
// <what>"; unknown keys are errors everywhere.
class Loader {
 public:
  explicit Loader(const typed_json::Reader& r) : r_(r) {}

  Case load(const CaseJson& root) const;

 private:
  using Reader = typed_json::Reader;

  void load_geometry(const CaseJson& root, Case& c) const;
  void load_state(const CaseJson& state, Case& c) const;
  PolygonOffset load_polygon_offset(const CaseJson& o) const;
  Viewport load_viewport(const CaseJson& o) const;
  Scissor load_scissor(const CaseJson& o) const;
  void load_varyings(const CaseJson& list, Case& c) const;
  // A varyings entry naming a built-in ({"builtin": "gl_FragCoord", ...}): its Varying.
  Varying load_builtin(const CaseJson& v, const CaseJson& builtin, const std::string& path) const;
  std::optional<Transform> load_transform(const CaseJson& t) const;
  std::vector<TransformOp> load_ops(const CaseJson& list, const std::string& path) const;
  Projection load_projection(const CaseJson& p, const std::string& path) const;
  // "enabled_clip_distances" (null: absent, every written distance enabled), after the
  // vertices have set how many there are.
  void load_enabled_clip_distances(const CaseJson* list, Case& c) const;
  // Vertex i's "clip_distance" and "cull_distance" into vertex.distances; vertex 0's set
  // Case::distances' counts.
  void load_distances(const CaseJson& v, size_t i, Vertex& vertex, Case& c) const;
  void load_vertices(const CaseJson& list, const std::optional<Transform>& transform,
                     Case& c) const;
  void load_triangles(const CaseJson* list, Case& c) const;
  void load_draws(const CaseJson& list, Case& c) const;
  Draw load_draw(const CaseJson& d, const std::string& path, const Case& c) const;
  void check_noperspective(const Case& c) const;
  void load_tolerance(const CaseJson& t, Case& c) const;

  // An integer in lo..hi ("an integer in 1..4096").
  int int_in(const CaseJson& v, const std::string& path, long long lo, long long hi) const {
    return static_cast<int>(r_.integer(
        v, path, lo, hi, "an integer in " + std::to_string(lo) + ".." + std::to_string(hi)));
  }
  // Exactly 3 numbers, each rounded to float32 once.
  std::array<double, 3> vec3(const CaseJson& v, const std::string& path) const {
    std::vector<float> f;
    r_.float32s_into(
        v, [&] { return path; }, {3}, f);
    return {f[0], f[1], f[2]};
  }

  const Reader& r_;
};

}  // namespace glrc::casefile
