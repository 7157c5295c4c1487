#include "identify/planes.hpp"

#include <algorithm>
#include <cmath>

#include "compare/compare.hpp"
#include "ref/reference.hpp"

namespace glrc::identify {

// Perspective triangles (w_c 0.5 to 3) at random float positions, with smooth and
// noperspective attributes: planes from snapped positions move every value by about the
// gradient times the snapping, far more than the float arithmetic does.
Case plane_triangles(Random& rnd, int index) {
  Case c = probe_case("identify_planes_" + std::to_string(index),
                      "perspective triangles with smooth and noperspective attributes");
  c.varyings = {Varying{"s", 4, Interpolation::smooth},
                Varying{"n", 2, Interpolation::noperspective}};
  for (int t = 0; t < 12; ++t) {
    std::array<Vertex, 3> v;
    Point p[3];
    do {
      for (Point& q : p)
        q = {rnd.uniform(1, 63), rnd.uniform(1, 63)};
    } while (std::fabs((p[1].x - p[0].x) * (p[2].y - p[0].y) -
                       (p[2].x - p[0].x) * (p[1].y - p[0].y)) < 150);
    for (int i = 0; i < 3; ++i) {
      const double w = rnd.uniform(0.5, 3);
      v[size_t(i)].clip = {float(p[i].x / kViewportScale * w), float(p[i].y / kViewportScale * w),
                           float(rnd.uniform(-0.8, 0.8) * w), float(w)};
      for (int k = 0; k < 6; ++k)
        v[size_t(i)].values.push_back(float(rnd.uniform(-8, 8)));
    }
    add_triangle(c, v);
  }
  return c;
}

PlanesFinding identify_planes(const std::vector<Probe>& probes, int bits) {
  PlanesFinding f;
  f.distinguishable = bits != 0;
  for (Planes planes : {Planes::unsnapped, Planes::snapped}) {
    Model m;
    m.subpixel_bits = bits;
    m.planes = planes;
    PlanesCandidate row;
    row.planes = planes;
    double sum = 0;
    for (const Probe& p : probes) {
      const Expectation r = ref::render(p.c, m);
      const compare::UlpTable ulps(p.c);
      for (size_t i = 0; i < p.gl.pixel_count(); ++i) {
        const int32_t prim = p.gl.primitive[i];
        if (!compare::same_primitive(p.c, r.frame.primitive[i], prim)) continue;
        for (size_t k = 0; k < r.frame.components.size(); ++k) {
          const compare::PixelError e =
              compare::pixel_error(r.frame.components[k][i], p.gl.components[k][i],
                                   ulps.ulp(prim, Channel::component(int(k))));
          ++row.compared;
          if (e.non_finite) {
            ++row.non_finite;
            continue;
          }
          row.max_ulps = std::max(row.max_ulps, e.ulps);
          sum += e.ulps;
        }
      }
    }
    row.mean_ulps = row.compared ? sum / double(row.compared) : 0;
    f.candidates.push_back(row);
  }
  const PlanesCandidate &u = f.candidates[0], &s = f.candidates[1];
  f.identified = f.distinguishable && s.max_ulps < u.max_ulps ? Planes::snapped : Planes::unsnapped;
  return f;
}

}  // namespace glrc::identify
