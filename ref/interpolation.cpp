#include "ref/interpolation.hpp"

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

RatioEvaluator plane(const Barycentrics& b, const std::array<mpq_class, 3>& alpha,
                     const std::array<mpq_class, 3>& beta) {
  LinearForm n, d;
  for (int i = 0; i < 3; ++i) {
    n += b.l[i] * alpha[i];
    d += b.l[i] * beta[i];
  }
  return RatioEvaluator(n, d);
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
    for (int i = 0; i < 3; ++i) {
      const mpq_class v(double(c.vertices[t.index[i]].values[k]));
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
    p.ratio = plane(b, alpha, beta);
    planes.push_back(std::move(p));
  }
  return planes;
}

}  // namespace glrc::ref
