// The planted faults of primitive assembly (assembly_faults.hpp). GL assembles the case's draws
// itself, so a fault cannot reach inside it: instead each draw is replaced by a GL_TRIANGLES
// list of the triangles the broken assembly makes, one list per draw, so that gl_PrimitiveID
// still counts each draw's triangles from 0 and only the vertices change.
#include "selftest/assembly_faults.hpp"

#include <array>
#include <cstdint>

#include "core/primitive_assembly.hpp"

namespace glrc::selftest {
namespace {

using Triangles = std::vector<std::array<uint32_t, 3>>;

// c drawn as lists of `triangles` instead of its draws: draw d's list holds triangles
// first_triangle[d] .. first_triangle[d + 1] - 1.
void draw_as_lists(Case& c, const Triangles& triangles) {
  const std::vector<uint32_t> first = assemble(c.draws, c.provoking).first_triangle;
  std::vector<Draw> lists(c.draws.size());
  for (size_t d = 0; d < lists.size(); ++d) {
    lists[d].index_type = IndexType::unsigned_int;
    for (uint32_t t = first[d]; t < first[d + 1]; ++t)
      lists[d].indices.insert(lists[d].indices.end(), triangles[t].begin(), triangles[t].end());
  }
  c.draws = std::move(lists);
  c.triangles = triangles;
}

// Strip triangle i of a strip under the first-vertex convention is (v_i, v_i+2, v_i+1) for odd
// i; the fault rotates it to (v_i+1, v_i, v_i+2): the winding is kept, v_i+1 provokes.
void strip_odd_provoked_by_second(Case& c) {
  if (c.draws.empty() || c.provoking != ProvokingVertex::first) return;
  const AssembledTriangles a = assemble(c.draws, c.provoking);
  Triangles t = a.triangles;
  bool any = false;
  for (size_t k = 0; k < t.size(); ++k)
    if (a.kind[k] == 2) {  // an odd strip triangle
      t[k] = {t[k][2], t[k][0], t[k][1]};
      any = true;
    }
  if (any) draw_as_lists(c, t);
}

// Each fan's triangles after a restart keep the hub of the draw's first fan (the first vertex
// not reset): every triangle of the later fans has its hub replaced, the count unchanged.
void fan_hub_not_reset(Case& c) {
  if (c.draws.empty()) return;
  const AssembledTriangles a = assemble(c.draws, c.provoking);
  Triangles t = a.triangles;
  // The hub is the first vertex of a last-convention fan triangle, the last of a first one.
  const size_t hub = c.provoking == ProvokingVertex::first ? 2 : 0;
  bool any = false;
  for (size_t d = 0; d < c.draws.size(); ++d) {
    const Draw& draw = c.draws[d];
    if (draw.mode != PrimitiveMode::triangle_fan || draw.restart == Restart::off) continue;
    const std::vector<uint32_t> e = draw.elements();
    size_t next = a.first_triangle[d], start = 0;
    bool first_fan = true;
    uint32_t first_hub = 0;
    for (size_t i = 0; i <= e.size(); ++i) {
      if (i < e.size() && !draw.restarts_at(e[i])) continue;
      const size_t n = i - start >= 3 ? i - start - 2 : 0;
      if (n > 0 && first_fan) {
        first_hub = e[start];
        first_fan = false;
      } else {
        for (size_t k = next; k < next + n; ++k)
          if (t[k][hub] != first_hub) t[k][hub] = first_hub, any = true;
      }
      next += n;
      start = i + 1;
    }
  }
  if (any) draw_as_lists(c, t);
}

}  // namespace

void add_assembly_faults(std::vector<Fault>& list) {
  list.push_back({"strip-provoking-first-wrong",
                  "a triangle strip's odd triangles take their flat values from v_i+1 instead of "
                  "v_i under the first-vertex convention (the draw module's 2014 and 2019 bugs)",
                  strip_odd_provoked_by_second, nullptr});
  list.push_back({"fan-hub-not-reset",
                  "a triangle fan after a primitive restart keeps the first fan's hub instead of "
                  "starting from the vertex after the restart",
                  fan_hub_not_reset, nullptr});
}

}  // namespace glrc::selftest
