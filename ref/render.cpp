#include <cmath>

#include "ref/coverage.hpp"
#include "ref/depth.hpp"
#include "ref/interpolation.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

Reference render(const Case& c, const Model& m) {
  Reference r{Frame(c.fb_width, c.fb_height, c.component_count()),
              std::vector<uint8_t>(size_t(c.fb_width) * c.fb_height, 0)};
  Frame& f = r.frame;
  // Coverage may legally differ within one subpixel step of an edge: the model's step, or
  // 1/256 pixel when the model does not snap.
  const double step = std::ldexp(1.0, -(m.subpixel_bits > 0 ? m.subpixel_bits : 8));
  const PixelBox viewport = viewport_box(c);

  for (int p = 0; p < int(c.triangles.size()); ++p) {
    const TriangleSetup t = setup_triangle(c, m, p);
    if (!t.drawn) continue;
    const CoverageTest coverage(t, m);

    // The band reaches up to one step outside the covered pixels: look one pixel further.
    const int bx0 = std::max(viewport.x0, t.box.x0 - 1), bx1 = std::min(viewport.x1, t.box.x1 + 1);
    const int by0 = std::max(viewport.y0, t.box.y0 - 1), by1 = std::min(viewport.y1, t.box.y1 + 1);
    for (int py = by0; py <= by1; ++py)
      for (int px = bx0; px <= bx1; ++px)
        if (coverage.near_boundary(px, py, step)) r.edge_band[f.index(px, py)] = 1;

    if (t.box.empty()) continue;
    const Barycentrics b = barycentrics(t, m);
    const RatioEvaluator depth = depth_plane(t, b);
    const std::vector<ComponentPlane> planes = component_planes(c, t, b);
    for (int py = t.box.y0; py <= t.box.y1; ++py) {
      for (int px = t.box.x0; px <= t.box.x1; ++px) {
        if (!coverage.covers(px, py)) continue;
        const size_t i = f.index(px, py);
        const float z = depth.at(px, py);
        if (!depth_test(c.depth_func, z, f.depth[i])) continue;
        f.primitive[i] = p;
        f.depth[i] = z;
        for (size_t k = 0; k < planes.size(); ++k)
          f.components[k][i] = planes[k].flat ? planes[k].flat_value : planes[k].ratio.at(px, py);
      }
    }
  }
  return r;
}

}  // namespace glrc::ref
