#include "ref/depth_offset.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ref/allowance.hpp"
#include "ref/viewport.hpp"

namespace glrc::ref {
namespace {

// r = 2^(e − 23) for the largest |z_w| `largest` (e its exponent: 2^e <= largest < 2^(e+1));
// 0 for 0.
double resolvable_difference(double largest) {
  if (!(largest > 0)) return 0.0;
  int e = 0;
  std::frexp(largest, &e);  // largest = f·2^e, f in [1/2, 1)
  return std::ldexp(1.0, e - 1 - kDepthMantissaBits);
}

// glPolygonOffsetClamp's clamp of o (14.13): monotone, so it maps bounds to bounds.
double clamped(const PolygonOffset& p, double o) {
  if (!p.clamp || *p.clamp == 0.0f) return o;
  return *p.clamp > 0 ? std::min(o, double(*p.clamp)) : std::max(o, double(*p.clamp));
}

// {lo, hi} of s·[lo, hi] for a scale s of either sign (0·INF taken as 0: a factor of 0 adds
// nothing, whatever the slope).
std::array<double, 2> scaled(double s, const std::array<double, 2>& v) {
  if (s == 0) return {0.0, 0.0};
  return s > 0 ? std::array<double, 2>{s * v[0], s * v[1]}
               : std::array<double, 2>{s * v[1], s * v[0]};
}

}  // namespace

std::array<std::array<double, 2>, 2> slope_bounds(const std::array<std::array<double, 2>, 3>& p,
                                                  const std::array<double, 3>& z,
                                                  const std::array<double, 3>& delta,
                                                  const std::array<double, 3>& depth) {
  // Differences from vertex 0, each moved by at most the two vertices' freedoms.
  const double dx1 = p[1][0] - p[0][0], dy1 = p[1][1] - p[0][1];
  const double dx2 = p[2][0] - p[0][0], dy2 = p[2][1] - p[0][1];
  const double dz1 = z[1] - z[0], dz2 = z[2] - z[0];
  const double a1 = delta[0] + delta[1], a2 = delta[0] + delta[2];
  const double b1 = depth[0] + depth[1], b2 = depth[0] + depth[2];
  // |Δ(u·v)| <= |u|·β + |v|·α + α·β for moves |Δu| <= α, |Δv| <= β.
  auto move = [](double u, double alpha, double v, double beta) {
    return std::fabs(u) * beta + std::fabs(v) * alpha + alpha * beta;
  };
  // 2A = dx1·dy2 − dx2·dy1; ∂z/∂x = (dz1·dy2 − dz2·dy1)/2A; ∂z/∂y = (dx1·dz2 − dx2·dz1)/2A.
  const double area = dx1 * dy2 - dx2 * dy1;
  const double nx = dz1 * dy2 - dz2 * dy1, ny = dx1 * dz2 - dx2 * dz1;
  const double e_area = move(dx1, a1, dy2, a2) + move(dx2, a2, dy1, a1);
  const double e_nx = move(dz1, b1, dy2, a2) + move(dz2, b2, dy1, a1);
  const double e_ny = move(dx1, a1, dz2, b2) + move(dx2, a2, dz1, b1);
  // The doubles' own rounding (a few ulps of each product) and the implementation's float
  // arithmetic on its slopes (a few float ulps): 2^-20 of each bound, outwards.
  constexpr double kOut = 1 + 0x1p-20, kIn = 1 - 0x1p-20;
  const double least_area = (std::fabs(area) - e_area) * kIn;
  std::array<std::array<double, 2>, 2> out{};
  const double n[2] = {nx, ny}, e[2] = {e_nx, e_ny};
  for (int k = 0; k < 2; ++k) {
    const double most_n = (std::fabs(n[k]) + e[k]) * kOut;
    const double least_n = std::max(0.0, (std::fabs(n[k]) - e[k]) * kIn);
    out[k][0] = least_n / ((std::fabs(area) + e_area) * kOut);
    out[k][1] = least_area > 0 ? most_n / least_area : INFINITY;
  }
  return out;
}

DepthOffset depth_offset(const Case& c, const TriangleSetup& t) {
  DepthOffset out;
  if (!c.polygon_offset) return out;
  const PolygonOffset& po = *c.polygon_offset;
  // The exact slopes: z_w = N(x, y)/W with N = Σ E'_i·w_c,i·z_w,i and W = Σ E'_i·w_c,i, the
  // homogeneous edge forms E'_i (setup.hpp); W is constant over the window (its a and b are 0),
  // so ∂z_w/∂x_w = N.a / W.c, ∂z_w/∂y_w = N.b / W.c, for every piece of the clipped polygon.
  mpq_class m = 0;
  if (t.has_edges) {
    LinearForm numerator, w;
    mpq_class scratch;
    for (int i = 0; i < 3; ++i) {
      numerator.add_product(t.homogeneous_edges[i], t.v[i].wz_w, scratch);
      w.add_product(t.homogeneous_edges[i], t.v[i].w_c, scratch);
    }
    const mpq_class gx = abs(numerator.a / w.c), gy = abs(numerator.b / w.c);
    const mpq_class largest = gx > gy ? gx : gy;
    // (14.12) and (14.11), the latter in double: the midpoint lies between them.
    m = (largest + mpq_class(std::hypot(gx.get_d(), gy.get_d()))) / 2;
  }
  // The largest |z_w| the primitive spans: at a vertex of its polygon (z_w is linear over it).
  double largest = 0;
  bool clipped = false;
  for (uint32_t i : t.index)
    clipped = clipped || !inside_view_volume(c, c.vertices[i].clip) ||
              outside_clip_distances(c, c.vertices[i]);
  if (!clipped) {
    mpq_class most = 0;
    for (const WindowVertex& v : t.v)
      most = std::max(most, mpq_class(abs(z_w(v))));
    largest = most.get_d();
    // Exactly: the double's rounding may not cross a power of two the rational is below.
    if (largest > 0 && mpq_class(largest) > most) largest = std::nextafter(largest, 0.0);
  } else {
    for (const PolygonVertex& v : clipped_polygon(c, t, 4))
      largest = std::max(largest, std::fabs(v.z_w));
  }
  const double r = resolvable_difference(largest);
  out.m = m.get_d(), out.r = r;
  mpq_class o = m * mpq_class(double(po.factor)) + mpq_class(r) * mpq_class(double(po.units));
  if (po.clamp && *po.clamp != 0.0f) {
    const mpq_class bound(double(*po.clamp));
    if (*po.clamp > 0 && o > bound) o = bound;
    if (*po.clamp < 0 && o < bound) o = bound;
  }
  out.value = o;
  return out;
}

double depth_offset_freedom(const Case& c, const PositionFreedom& freedom,
                            const DepthOffset& reference) {
  if (!c.polygon_offset) return 0.0;
  const PolygonOffset& po = *c.polygon_offset;
  const std::vector<PolygonVertex>& poly = freedom.polygon_vertices();
  if (poly.size() < 3) return 0.0;  // nothing drawn
  // Each vertex's z_w within its clipping freedom and the float rounding of the viewport
  // transform (z_n·s + t: z_n to 2^-23 relative, the sum to half an ulp of z_w; |z_n·s| <=
  // |z_w| + 1, the translation in [0, 1]), twice over.
  auto depth_rounding = [](const PolygonVertex& v) {
    return v.depth + 0x1p-21 * (2 * std::fabs(v.z_w) + 1);
  };
  // The pieces an implementation may set up: a fan of the clipped polygon from any of its
  // vertices (Mesa's clipper emits one; which vertex it starts from is its own), the triangle
  // itself when nothing is clipped.
  std::array<double, 2> m{INFINITY, 0.0}, largest{INFINITY, 0.0};
  const size_t n = poly.size();
  for (size_t hub = 0; hub < (n > 3 ? n : 1); ++hub)
    for (size_t k = 1; k + 1 < n; ++k) {
      const PolygonVertex* v[3] = {&poly[hub], &poly[(hub + k) % n], &poly[(hub + k + 1) % n]};
      std::array<std::array<double, 2>, 3> p{};
      std::array<double, 3> z{}, delta{}, depth{};
      double most = 0, rounding = 0;
      for (int i = 0; i < 3; ++i) {
        p[size_t(i)] = {v[i]->x_w, v[i]->y_w};
        z[size_t(i)] = v[i]->z_w, delta[size_t(i)] = v[i]->delta;
        depth[size_t(i)] = depth_rounding(*v[i]);
        most = std::max(most, std::fabs(v[i]->z_w));
        rounding = std::max(rounding, depth[size_t(i)]);
      }
      const auto s = slope_bounds(p, z, delta, depth);
      m[0] = std::min(m[0], std::max(s[0][0], s[1][0]));
      m[1] = std::max(m[1], std::hypot(s[0][1], s[1][1]));
      largest[0] = std::min(largest[0], most - rounding);
      largest[1] = std::max(largest[1], most + rounding);
    }
  // Any triangulation's pieces: the least largest |z_w| of a piece is that of the three
  // vertices of least |z_w| (found by a campaign: llvmpipe's pieces of a polygon reaching
  // z_w 1.04 had one below 1, so half the r of the others, with units 382363).
  std::vector<double> least;
  for (const PolygonVertex& v : poly)
    least.push_back(std::fabs(v.z_w) - depth_rounding(v));
  std::sort(least.begin(), least.end());
  largest[0] = std::min(largest[0], least[2]);
  // The reference's own m and r lie within (the doubles' rounding aside).
  m = {std::min(m[0], reference.m), std::max(m[1], reference.m)};
  if (!(m[1] < INFINITY) && po.factor != 0.0f) return INFINITY;
  // Below 2^-100 the exponent arithmetic may flush r to 0.
  std::array<double, 2> r{largest[0] < 0x1p-100 ? 0.0 : resolvable_difference(largest[0]),
                          resolvable_difference(largest[1])};
  r = {std::min(r[0], reference.r), std::max(r[1], reference.r)};
  const auto slope_term = scaled(po.factor, m), unit_term = scaled(po.units, r);
  // The float products and their sum, a few roundings each.
  const double rounding = 0x1p-21 * (std::fabs(double(po.factor)) * (po.factor != 0 ? m[1] : 0.0) +
                                     std::fabs(double(po.units)) * r[1]);
  const double lo = clamped(po, slope_term[0] + unit_term[0] - rounding);
  const double hi = clamped(po, slope_term[1] + unit_term[1] + rounding);
  const double o = reference.value.get_d();
  // z_w + o rounded once more (and an implementation that adds o to its plane's constant
  // rounds that sum): an ulp of the larger magnitude.
  const double sum = 0x1p-23 * (largest[1] + std::max(std::fabs(lo), std::fabs(hi)));
  return std::max(hi - o, o - lo) * (1 + 0x1p-40) + sum;
}

}  // namespace glrc::ref
