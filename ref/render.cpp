#include <algorithm>
#include <cmath>
#include <map>

#include "ref/allowance.hpp"
#include "ref/coverage.hpp"
#include "ref/depth.hpp"
#include "ref/freedom.hpp"
#include "ref/interpolation.hpp"
#include "ref/mesh.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

namespace {

// How far the centre of pixel (px, py) is from the nearest side of the viewport, pixels.
double viewport_side_distance(const Viewport& vp, int px, int py) {
  const double x = px + 0.5, y = py + 0.5;
  return std::min({x - vp.x, double(vp.x) + vp.width - x, y - vp.y, double(vp.y) + vp.height - y});
}

}  // namespace

Reference render(const Case& c, const Model& m, std::optional<int> freedom_bits) {
  Reference r{Frame(c.fb_width, c.fb_height, c.component_count()),
              std::vector<uint8_t>(size_t(c.fb_width) * c.fb_height, 0), Frame()};
  Frame& f = r.frame;
  f.fragments.assign(f.pixel_count(), 0);
  const bool allowance = freedom_bits.has_value();
  const int bits = allowance ? std::max(*freedom_bits, 4) : 0;
  if (allowance) r.allowed = Frame(c.fb_width, c.fb_height, c.component_count());
  const PixelBox viewport = viewport_box(c);
  // Without an allowance, coverage may legally differ within one model subpixel step of an
  // edge (1/256 pixel when the model does not snap).
  const double model_step = std::ldexp(1.0, -(m.subpixel_bits > 0 ? m.subpixel_bits : 8));

  std::vector<TriangleSetup> setups;
  setups.reserve(c.triangles.size());
  for (int p = 0; p < int(c.triangles.size()); ++p)
    setups.push_back(setup_triangle(c, m, p));
  const std::vector<std::array<bool, 3>> shared = shared_edges(setups);
  // Fragments that may win the depth test instead of the reference's, by pixel.
  std::map<size_t, std::vector<Candidate>> candidates;
  std::vector<bool> component_smooth;
  for (int v : component_varying(c))
    component_smooth.push_back(c.varyings[size_t(v)].interpolation == Interpolation::smooth);

  for (int p = 0; p < int(c.triangles.size()); ++p) {
    const TriangleSetup& t = setups[size_t(p)];
    // A triangle this model does not draw (zero snapped area, culled) may still be drawn by
    // another implementation when its orientation is not decided by the freedom.
    if (!t.drawn && !(allowance && t.has_edges && c.cull != CullFace::front_and_back)) continue;
    const PositionFreedom freedom = allowance ? PositionFreedom(c, t, bits) : PositionFreedom();
    const bool unstable = allowance && freedom.may_turn_over();
    if (!t.drawn && !unstable) continue;
    const CoverageTest coverage(t, m);
    auto delta_at = [&](int px, int py) { return allowance ? freedom.at(px, py) : model_step; };

    // The bands reach up to delta·sqrt(2) outside the covered pixels: look that much further
    // (the viewport bounds it anyway; the clamp keeps the conversion defined).
    const double largest = allowance ? freedom.largest() : model_step;
    const int margin = 1 + int(std::min(std::ceil(largest * 1.5), 1e6));
    const int bx0 = std::max(viewport.x0, t.box.x0 - margin),
              bx1 = std::min(viewport.x1, t.box.x1 + margin);
    const int by0 = std::max(viewport.y0, t.box.y0 - margin),
              by1 = std::min(viewport.y1, t.box.y1 + margin);
    // Only the pixels within `margin` of the triangle, row by row (CoverageTest::row_span):
    // a thin triangle's bounding box holds a thousand times the pixels it reaches.
    for (int py = by0; py <= by1; ++py) {
      const auto [x0, x1] = coverage.row_span(py, margin, bx0, bx1);
      for (int px = x0; px <= x1; ++px)
        r.edges[f.index(px, py)] |=
            coverage.classify(px, py, delta_at(px, py), shared[size_t(p)], unstable);
    }

    if (!t.drawn || t.box.empty()) continue;
    const bool clipped = allowance && freedom.generations() > 0;
    const Barycentrics b = barycentrics(t, m);
    const Plane depth_forms = depth_plane(t, b);
    const RatioEvaluator depth = depth_forms.evaluator();
    const std::vector<ComponentPlane> planes = component_planes(c, t, b);
    std::vector<Allowance> allowed;
    Allowance depth_allowed;
    // The implementation's possible fan triangles, shared by every channel; and where its
    // planes may be anchored.
    const FanTriangles fan =
        allowance ? FanTriangles(freedom.polygon(), freedom.largest()) : FanTriangles();
    WindowPolygon anchors = freedom.polygon();
    for (const auto& q : freedom.guard_band_triangle())
      anchors.push_back(q);
    if (allowance) {
      const int generations = freedom.generations();
      for (const ComponentPlane& cp : planes)
        allowed.emplace_back(cp.plane.numerator, cp.plane.denominator, cp.spread,
                             value_freedom(c, t, cp.scale, generations), freedom.polygon(),
                             freedom.guard_band_triangle());
      const double n = c.depth_near, fa = c.depth_far;
      depth_allowed =
          Allowance(depth_forms.numerator, depth_forms.denominator, INFINITY,
                    value_freedom(c, t, std::max(std::fabs(n), std::fabs(fa)), generations),
                    freedom.polygon(), freedom.guard_band_triangle());
    }
    for (int py = t.box.y0; py <= t.box.y1; ++py) {
      const auto [x0, x1] = coverage.row_span(py, margin, t.box.x0, t.box.x1);
      for (int px = x0; px <= x1; ++px) {
        if (!coverage.covers(px, py)) continue;
        const size_t i = f.index(px, py);
        const float z = depth.at(px, py);
        auto value = [&](size_t k) {
          return planes[k].flat ? planes[k].flat_value : planes[k].ratio.at(px, py);
        };
        if (!allowance) {
          if (!depth_test(c.depth_func, z, f.depth[i])) continue;
          f.primitive[i] = p;
          f.depth[i] = z;
          ++f.fragments[i];
          for (size_t k = 0; k < planes.size(); ++k)
            f.components[k][i] = value(k);
          continue;
        }
        const double delta = freedom.at(px, py);
        // The clipped polygon's edges on the x and y planes lie on the viewport's sides, where
        // no pixel centre is; but they move with its vertices, inwards too.
        if (clipped && viewport_side_distance(c.viewport, px, py) <= delta)
          r.edges[i] |= edge::snapping;
        // A clipped vertex's 1/w_c error re-weights a smooth value (freedom.hpp).
        const double weight = clipped ? freedom.weight_at(px, py) : 0.0;
        const double condition = fan.condition(px + 0.5, py + 0.5);
        auto allowed_at = [&](size_t k, float v) {
          return planes[k].flat
                     ? 0.0f
                     : round_up(allowed[k].at(px, py, v, delta,
                                              component_smooth[k] ? weight * planes[k].spread : 0.0,
                                              condition));
        };
        const float z_allowed =
            round_up(depth_allowed.at(px, py, z, delta, freedom.depth_at(px, py), condition));
        // Depths within each other's allowances: either fragment may win the depth test.
        auto close = [&](float other, float other_allowed) {
          return std::fabs(double(z) - double(other)) <= double(z_allowed) + double(other_allowed);
        };
        const bool ordered = c.depth_func != DepthFunc::always && f.fragments[i] > 0;
        const bool contested = ordered && close(f.depth[i], r.allowed.depth[i]);
        if (!depth_test(c.depth_func, z, f.depth[i])) {
          if (!contested) continue;
          Candidate loser{i, p, z, z_allowed, {}, {}};
          for (size_t k = 0; k < planes.size(); ++k) {
            loser.values.push_back(value(k));
            loser.allowed.push_back(allowed_at(k, loser.values.back()));
          }
          candidates[i].push_back(std::move(loser));
          continue;
        }
        // Keep the candidates that may still win against the new winner (looked up, not
        // inserted: a pixel drawn over by a clear winner needs no entry).
        if (const auto it = candidates.find(i); it != candidates.end())
          std::erase_if(it->second,
                        [&](const Candidate& o) { return !close(o.depth, o.allowed_depth); });
        // The old winner is one when it was close.
        if (contested) {
          Candidate old{i, f.primitive[i], f.depth[i], r.allowed.depth[i], {}, {}};
          for (size_t k = 0; k < planes.size(); ++k) {
            old.values.push_back(f.components[k][i]);
            old.allowed.push_back(r.allowed.components[k][i]);
          }
          candidates[i].push_back(std::move(old));
        }
        f.primitive[i] = p;
        f.depth[i] = z;
        ++f.fragments[i];
        r.allowed.primitive[i] = p;
        r.allowed.depth[i] = z_allowed;
        for (size_t k = 0; k < planes.size(); ++k) {
          f.components[k][i] = value(k);
          r.allowed.components[k][i] = allowed_at(k, f.components[k][i]);
        }
      }
    }
  }
  for (auto& [i, list] : candidates) {
    if (list.empty()) continue;
    r.edges[i] |= edge::depth_order;
    for (Candidate& k : list)
      r.candidates.push_back(std::move(k));
  }
  return r;
}

}  // namespace glrc::ref
