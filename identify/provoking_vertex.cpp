#include "identify/provoking_vertex.hpp"

namespace glrc::identify {

// Triangles of both windings with a flat varying that differs at each vertex.
Case provoking_triangles(Random& rnd) {
  Case c = probe_case("identify_provoking",
                      "flat varying, a different value at each vertex; glProvokingVertex never "
                      "called");
  c.varyings = {Varying{"f", 1, Interpolation::flat}};
  for (int cell = 0; cell < 16; ++cell) {
    const Point o = cell_origin(cell, 16);
    std::array<Vertex, 3> v;
    for (int i = 0; i < 3; ++i) {
      const FPoint p{float(o.x + rnd.uniform(1, 15)), float(o.y + rnd.uniform(1, 15))};
      v[size_t(i)] = window_vertex(p, 0.5, {float(3 * cell + i + 1)});
    }
    add_triangle(c, v);
  }
  return c;
}

ProvokingFinding identify_provoking(const Probe& p, ProvokingVertex reported) {
  ProvokingFinding f;
  f.reported = reported;
  for (size_t i = 0; i < p.gl.pixel_count(); ++i) {
    const int32_t prim = p.gl.primitive[i];
    if (prim < 0 || size_t(prim) >= p.c.triangles.size()) continue;
    const auto& t = p.c.triangles[size_t(prim)];
    const float v = p.gl.components[0][i];
    ++f.pixels;
    if (v == p.c.vertices[t[0]].values[0])
      ++f.first;
    else if (v == p.c.vertices[t[2]].values[0])
      ++f.last;
    else
      ++f.neither;
  }
  f.identified = f.first > f.last ? ProvokingVertex::first : ProvokingVertex::last;
  return f;
}

}  // namespace glrc::identify
