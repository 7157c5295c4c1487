#include "identify/depth_offset.hpp"

#include <algorithm>
#include <cmath>

namespace glrc::identify {
namespace {

constexpr float kUnits = 65536.0f;

// The median of v (its upper middle for an even count); 0 for none.
double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The plane's slopes of a probe triangle, from its vertices as GL takes them (w_c = 1).
std::array<double, 2> slopes(const Case& c, const std::array<uint32_t, 3>& t) {
  std::array<std::array<double, 3>, 3> p{};
  for (size_t i = 0; i < 3; ++i) {
    const auto& clip = c.vertices[t[i]].clip;
    p[i] = {double(clip[0]) * kViewportScale, double(clip[1]) * kViewportScale,
            (double(clip[2]) + 1) / 2};
  }
  const double dx1 = p[1][0] - p[0][0], dy1 = p[1][1] - p[0][1], dz1 = p[1][2] - p[0][2];
  const double dx2 = p[2][0] - p[0][0], dy2 = p[2][1] - p[0][1], dz2 = p[2][2] - p[0][2];
  const double area = dx1 * dy2 - dx2 * dy1;
  return {(dz1 * dy2 - dz2 * dy1) / area, (dx1 * dz2 - dx2 * dz1) / area};
}

}  // namespace

std::vector<Case> depth_offset_cases(Random& rnd) {
  Case base = probe_case("identify_depth_offset", "polygon offset: the triangles alone");
  for (int cell = 0; cell < 16; ++cell) {
    const Point o = cell_origin(cell, 16);
    // Depth z0 + g·(x − cx) ± g·(y − cy) over the cell, g a power of two from 2^-9 to 2^-7 per
    // pixel and z0 5/8: within [1/2, 3/4] over the 16-pixel cell, on the 2^-20 grid.
    const double g = std::ldexp(1.0, -rnd.integer(7, 9));
    const double sign = rnd.coin() ? 1.0 : -1.0;
    const double cx = o.x + 8, cy = o.y + 8;
    std::array<Vertex, 3> v;
    for (size_t i = 0; i < 3; ++i) {
      const Point p{o.x + rnd.integer(1 * 64, 15 * 64) / 64.0,
                    o.y + rnd.integer(1 * 64, 15 * 64) / 64.0};
      v[i] = window_vertex(p, 0.625 + g * (p.x - cx) + sign * g * (p.y - cy));
    }
    add_triangle(base, v);
  }
  Case slope = base, units = base;
  slope.name = "identify_depth_offset_slope", slope.description = "polygon offset: factor 1";
  slope.polygon_offset = PolygonOffset{1.0f, 0.0f, std::nullopt};
  units.name = "identify_depth_offset_units", units.description = "polygon offset: units 65536";
  units.polygon_offset = PolygonOffset{0.0f, kUnits, std::nullopt};
  return {base, slope, units};
}

DepthOffsetFinding identify_depth_offset(const std::vector<Probe>& probes) {
  DepthOffsetFinding f;
  if (probes.size() != 3) return f;
  f.available = true;
  const Case& c = probes[0].c;
  const Frame &base = probes[0].gl, &slope = probes[1].gl, &units = probes[2].gl;
  // Every probe triangle's depths lie in [1/2, 3/4]: e = -1, r = 2^-24.
  const double r = std::ldexp(1.0, -24);
  std::vector<double> slope_ratios, units_ratios;
  for (size_t i = 0; i < base.pixel_count(); ++i) {
    const int32_t p = base.primitive[i];
    if (p < 0 || slope.primitive[i] != p || units.primitive[i] != p) continue;
    ++f.pixels;
    const auto g = slopes(c, c.triangles[size_t(p)]);
    const double m = std::max(std::fabs(g[0]), std::fabs(g[1]));
    slope_ratios.push_back((double(slope.depth[i]) - double(base.depth[i])) / m);
    units_ratios.push_back((double(units.depth[i]) - double(base.depth[i])) / (kUnits * r));
  }
  f.slope_ratio = median(slope_ratios);
  f.units_ratio = median(units_ratios);
  // The depths' float rounding moves a ratio by far less than 1e-3.
  f.slope = std::fabs(f.slope_ratio - 1) < 1e-3                ? "max"
            : std::fabs(f.slope_ratio - std::sqrt(2.0)) < 1e-3 ? "length"
                                                               : "other";
  f.units = std::fabs(f.units_ratio - 1) < 1e-3   ? "r"
            : std::fabs(f.units_ratio - 2) < 1e-3 ? "2r"
                                                  : "other";
  return f;
}

}  // namespace glrc::identify
