// The case schema's draws (cases/README.md, "draws"): each draw command as core/draw.hpp holds
// it, checked against the vertices, then assembled into the case's triangles
// (core/primitive_assembly.hpp).
#include <string>

#include "casefile/case_schema.hpp"
#include "core/primitive_assembly.hpp"

namespace glrc::casefile {
namespace {

using typed_json::path_index;
using typed_json::path_key;

}  // namespace

Draw Loader::load_draw(const CaseJson& d, const std::string& path, const Case& c) const {
  r_.object(d, path);
  r_.check_keys(d, path,
                {"mode", "first", "count", "indices", "index_type", "restart", "restart_index"});
  Draw out;
  out.mode = r_.name<PrimitiveMode>(r_.required(d, path, "mode", "a primitive mode"),
                                    path_key(path, "mode"));
  const long long n = static_cast<long long>(c.vertices.size());
  const CaseJson* indices = Reader::find(d, "indices");
  if (!indices) {
    for (const char* key : {"index_type", "restart", "restart_index"})
      if (Reader::find(d, key))
        r_.fail(path_key(path, key), "no such key in a glDrawArrays draw (one without \"indices\")",
                "a value");
    out.first =
        uint32_t(Reader::find(d, "first")
                     ? r_.integer(*Reader::find(d, "first"), path_key(path, "first"), 0, n - 1,
                                  "an integer vertex index in 0.." + std::to_string(n - 1))
                     : 0);
    const long long left = n - out.first;
    out.count = uint32_t(r_.integer(
        r_.required(d, path, "count", "a vertex count"), path_key(path, "count"), 1, left,
        "an integer in 1.." + std::to_string(left) + " (first + count at most the " +
            std::to_string(n) + " vertices)"));
    return out;
  }
  for (const char* key : {"first", "count"})
    if (Reader::find(d, key))
      r_.fail(path_key(path, key), "no such key in a glDrawElements draw (one with \"indices\")",
              "a value");
  out.index_type = IndexType::unsigned_int;
  if (const CaseJson* t = Reader::find(d, "index_type")) {
    // "none" is no index type a file may name (it is a glDrawArrays draw, without "indices").
    const std::string types = "\"unsigned_byte\", \"unsigned_short\" or \"unsigned_int\"";
    out.index_type = r_.name<IndexType>(*t, path_key(path, "index_type"), types);
    if (out.index_type == IndexType::none) r_.fail(path_key(path, "index_type"), types, "\"none\"");
  }
  if (const CaseJson* r = Reader::find(d, "restart"))
    out.restart = r_.name<Restart>(*r, path_key(path, "restart"));
  const CaseJson* ri = Reader::find(d, "restart_index");
  if (out.restart == Restart::index) {
    if (!ri)
      r_.fail(path_key(path, "restart_index"),
              "an integer in 0..4294967295 (glPrimitiveRestartIndex), as restart is \"index\"",
              "nothing");
    out.restart_index = uint32_t(r_.integer(*ri, path_key(path, "restart_index"), 0, 0xffffffffLL,
                                            "an integer in 0..4294967295"));
  } else if (ri) {
    r_.fail(path_key(path, "restart_index"), "no restart_index unless restart is \"index\"",
            "a value");
  }
  if (!indices->is_array() || indices->empty())
    r_.fail(path_key(path, "indices"), "a non-empty array of vertex indices",
            Reader::describe(*indices));
  const long long top = max_index(out.index_type);
  const std::string what =
      "an integer vertex index in 0.." + std::to_string(n - 1) +
      (out.restart != Restart::off ? " or the restart index " + std::to_string(out.restart_value())
                                   : std::string());
  out.indices.reserve(indices->size());
  for (size_t i = 0; i < indices->size(); ++i) {
    const std::string p = path_index(path_key(path, "indices"), i);
    const long long v = r_.integer((*indices)[i], p, 0, top,
                                   "an integer in 0.." + std::to_string(top) + " (" +
                                       std::string(name_of(out.index_type)) + ")");
    if (v >= n && !out.restarts_at(uint32_t(v))) r_.fail(p, what, std::to_string(v));
    out.indices.push_back(uint32_t(v));
  }
  return out;
}

void Loader::load_draws(const CaseJson& list, Case& c) const {
  if (!list.is_array() || list.empty())
    r_.fail("draws", "a non-empty array of draws", Reader::describe(list));
  for (size_t i = 0; i < list.size(); ++i)
    c.draws.push_back(load_draw(list[i], path_index("draws", i), c));
  assemble_triangles(c);
  if (c.triangles.empty())
    r_.fail("draws", "draws that assemble at least one triangle",
            "none (every primitive incomplete)");
}

}  // namespace glrc::casefile
