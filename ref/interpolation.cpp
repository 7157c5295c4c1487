#include "ref/interpolation.hpp"

#include <algorithm>
#include <cmath>

namespace glrc::ref {

Barycentrics barycentrics(const TriangleSetup& t, const Model& m) {
  Barycentrics b;
  if (m.planes == Planes::snapped && t.path == CoveragePath::snapped) {
    b.screen_space = true;
    for (int i = 0; i < 3; ++i) {
      const auto& e = t.snapped_edges[i];
      b.l[i] = {mpq_class(to_mpz(e.a)), mpq_class(to_mpz(e.b)), mpq_class(to_mpz(e.c))};
    }
  } else {
    b.l = t.homogeneous_edges;
  }
  return b;
}

Plane plane(const Barycentrics& b, const std::array<mpq_class, 3>& alpha,
            const std::array<mpq_class, 3>& beta) {
  Plane p;
  for (int i = 0; i < 3; ++i) {
    p.numerator += b.l[i] * alpha[i];
    p.denominator += b.l[i] * beta[i];
  }
  return p;
}

std::vector<ComponentPlane> component_planes(const Case& c, const TriangleSetup& t,
                                             const Barycentrics& b) {
  std::vector<ComponentPlane> planes;
  const int provoking = c.provoking == ProvokingVertex::last ? 2 : 0;
  const auto owner = component_varying(c);
  for (size_t k = 0; k < owner.size(); ++k) {
    ComponentPlane p;
    const Interpolation q = c.varyings[owner[k]].interpolation;
    if (q == Interpolation::flat) {
      p.flat = true;
      p.flat_value = c.vertices[t.index[provoking]].values[k];
      planes.push_back(std::move(p));
      continue;
    }
    std::array<mpq_class, 3> alpha, beta;
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < 3; ++i) {
      const double value = double(c.vertices[t.index[i]].values[k]);
      lo = std::min(lo, value), hi = std::max(hi, value);
      p.scale = std::max(p.scale, std::fabs(value));
      const mpq_class v(value);
      const mpq_class& w = t.v[i].w_c;
      const bool perspective = q == Interpolation::smooth;
      if (b.screen_space) {
        alpha[i] = perspective ? mpq_class(v / w) : v;
        beta[i] = perspective ? mpq_class(1 / w) : mpq_class(1);
      } else {
        alpha[i] = perspective ? v : mpq_class(w * v);
        beta[i] = perspective ? mpq_class(1) : w;
      }
    }
    p.spread = hi - lo;
    p.plane = plane(b, alpha, beta);
    p.ratio = p.plane.evaluator();
    planes.push_back(std::move(p));
  }
  return planes;
}

}  // namespace glrc::ref
