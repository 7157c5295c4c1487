// Primitive assembly (primitive_assembly.hpp).
#include "core/primitive_assembly.hpp"

#include <numeric>

namespace glrc {

std::vector<uint32_t> Draw::elements() const {
  if (indexed()) return indices;
  std::vector<uint32_t> out(count);
  std::iota(out.begin(), out.end(), first);
  return out;
}

namespace {

constexpr uint8_t kListTriangle = 0, kStripEven = 1, kStripOdd = 2, kFanTriangle = 3;

// The triangles of one primitive (a run of vertices between restarts), appended to `out`.
void assemble_run(PrimitiveMode mode, const uint32_t* v, size_t n, ProvokingVertex pv,
                  AssembledTriangles& out) {
  const bool first = pv == ProvokingVertex::first;
  auto emit = [&](uint32_t a, uint32_t b, uint32_t c, uint8_t kind) {
    out.triangles.push_back({a, b, c});
    out.kind.push_back(kind);
  };
  switch (mode) {
    case PrimitiveMode::triangles:
      for (size_t i = 0; i + 2 < n; i += 3)
        emit(v[i], v[i + 1], v[i + 2], kListTriangle);
      break;
    case PrimitiveMode::triangle_strip:
      for (size_t i = 0; i + 2 < n; ++i) {
        if (i % 2 == 0)
          emit(v[i], v[i + 1], v[i + 2], kStripEven);
        else if (first)
          emit(v[i], v[i + 2], v[i + 1], kStripOdd);
        else
          emit(v[i + 1], v[i], v[i + 2], kStripOdd);
      }
      break;
    case PrimitiveMode::triangle_fan:
      for (size_t i = 0; i + 2 < n; ++i) {
        if (first)
          emit(v[i + 1], v[i + 2], v[0], kFanTriangle);
        else
          emit(v[0], v[i + 1], v[i + 2], kFanTriangle);
      }
      break;
  }
}

}  // namespace

AssembledTriangles assemble(const std::vector<Draw>& draws, ProvokingVertex pv) {
  AssembledTriangles out;
  for (const Draw& d : draws) {
    out.first_triangle.push_back(uint32_t(out.triangles.size()));
    const std::vector<uint32_t> e = d.elements();
    size_t start = 0;
    for (size_t i = 0; i <= e.size(); ++i) {
      if (i < e.size() && !d.restarts_at(e[i])) continue;
      assemble_run(d.mode, e.data() + start, i - start, pv, out);
      start = i + 1;
    }
  }
  out.first_triangle.push_back(uint32_t(out.triangles.size()));
  return out;
}

std::vector<Draw> draws_of(const Case& c) {
  if (!c.draws.empty()) return c.draws;
  Draw d;
  d.index_type = IndexType::unsigned_int;
  d.indices.reserve(c.triangles.size() * 3);
  for (const auto& t : c.triangles)
    d.indices.insert(d.indices.end(), t.begin(), t.end());
  return {d};
}

void assemble_triangles(Case& c) {
  if (!c.draws.empty()) c.triangles = assemble(c.draws, c.provoking).triangles;
}

bool several_draws(const Case& c) {
  return c.draws.size() > 1;
}

}  // namespace glrc
