#include "identify/depth_rounding.hpp"

#include <cmath>
#include <cstdlib>

namespace glrc::identify {

Case depth_triangles(Random& rnd, int category, std::vector<DepthTriangle>& exact) {
  static const char* const kNames[] = {"constant z < 0.5", "sloped z < 1/16", "sloped z < 1"};
  Case c = probe_case("identify_depth_" + std::to_string(category),
                      std::string("24-bit depth: ") + kNames[category]);
  for (int cell = 0; cell < 16; ++cell) {
    const Point o = cell_origin(cell, 16);
    DepthTriangle t;
    do {
      for (int i = 0; i < 3; ++i) {
        t.x[size_t(i)] = long(o.x) * 64 + rnd.integer(64, 15 * 64);
        t.y[size_t(i)] = long(o.y) * 64 + rnd.integer(64, 15 * 64);
      }
    } while (std::labs((t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) -
                       (t.x[2] - t.x[0]) * (t.y[1] - t.y[0])) < 40L * 64 * 64);
    const long top = category == 0 ? (1L << 22) : category == 1 ? (1L << 19) : (1L << 23) - 1;
    const long z0 = rnd.integer(1, int(top - 1));
    for (int i = 0; i < 3; ++i)
      t.z[size_t(i)] = category == 0 ? z0 : rnd.integer(1, int(top - 1));
    std::array<Vertex, 3> v;
    for (int i = 0; i < 3; ++i)
      v[size_t(i)] = window_vertex({t.x[size_t(i)] / 64.0, t.y[size_t(i)] / 64.0},
                                   std::ldexp(double(t.z[size_t(i)]), -23));
    add_triangle(c, v);
    exact.push_back(t);
  }
  return c;
}

DepthFinding identify_depth(const std::vector<Probe>& probes,
                            const std::vector<std::vector<DepthTriangle>>& exact) {
  static const char* const kNames[] = {"constant z < 0.5", "sloped z < 1/16", "sloped z < 1"};
  __extension__ typedef __int128 i128;
  DepthFinding f;
  f.total.name = "all";
  for (size_t k = 0; k < probes.size(); ++k) {
    DepthCategory cat;
    cat.name = kNames[k];
    const Frame& gl = probes[k].gl;
    for (int py = 0; py < gl.height; ++py)
      for (int px = 0; px < gl.width; ++px) {
        const size_t i = gl.index(px, py);
        const int32_t prim = gl.primitive[i];
        if (prim < 0 || size_t(prim) >= exact[k].size()) continue;
        const DepthTriangle& t = exact[k][size_t(prim)];
        const long cx = 64L * px + 32, cy = 64L * py + 32;
        auto e = [&](int a, int b) {  // edge function of vertices a -> b at the centre
          return i128((t.x[size_t(a)] - cx) * (t.y[size_t(b)] - cy) -
                      (t.y[size_t(a)] - cy) * (t.x[size_t(b)] - cx));
        };
        i128 l0 = e(1, 2), l1 = e(2, 0), l2 = e(0, 1);
        const i128 area = l0 + l1 + l2;
        if (area < 0) l0 = -l0, l1 = -l1, l2 = -l2;
        if (l0 < 0 || l1 < 0 || l2 < 0) continue;  // GL covered a centre just outside
        const i128 num = (l0 * t.z[0] + l1 * t.z[1] + l2 * t.z[2]) * ((i128(1) << 24) - 1);
        const i128 den = (area < 0 ? -area : area) << 23;
        const i128 floor = num / den, rem = num % den;
        const i128 round = 2 * rem >= den ? floor + 1 : floor;
        const auto stored = i128(gl.depth[i]);
        ++cat.pixels;
        const bool informative = 2 * rem > den;
        cat.informative += informative;
        if (stored == round && informative) ++cat.round;
        if (stored == floor && informative) ++cat.truncate;
        if (stored != round && stored != floor) ++cat.neither;
      }
    f.total.pixels += cat.pixels, f.total.informative += cat.informative;
    f.total.round += cat.round, f.total.truncate += cat.truncate, f.total.neither += cat.neither;
    f.categories.push_back(cat);
  }
  f.identified = f.total.truncate > f.total.round ? "truncate" : "round";
  return f;
}

}  // namespace glrc::identify
