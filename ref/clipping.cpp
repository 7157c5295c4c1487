#include "ref/clipping.hpp"

#include <cmath>

namespace glrc::ref {

ClipPlanes clip_planes(const TriangleSetup& t) {
  ClipPlanes out;
  // The near plane's distance is z_c + w_c, or z_c under GL_ZERO_TO_ONE (near_distance); the
  // far plane's w_c − z_c; a user plane's its gl_ClipDistance. The visible part is
  // sum b_i·vertex_i with b_i >= 0, so if every vertex is inside a plane, every point is: only
  // a plane some vertex is outside of needs the per-pixel test.
  const bool zero_to_one = t.clip_depth == ClipDepth::zero_to_one;
  const size_t users = t.v[0].clip_distances.size();
  // Plane p's distance at vertex i: p = 0 near, 1 far, 2 + k user plane k.
  auto distance = [&](size_t p, int i) -> mpq_class {
    const WindowVertex& v = t.v[i];
    if (p == 0) return zero_to_one ? v.z_c : mpq_class(v.w_c + v.z_c);
    if (p == 1) return v.w_c - v.z_c;
    return v.clip_distances[p - 2];
  };
  // -w_c in a rational kept per thread: as an expression's temporary it was allocated and freed
  // for every vertex of every triangle.
  thread_local mpq_class minus_w;
  auto outside = [&](size_t p, int i) {
    const WindowVertex& v = t.v[i];
    if (p == 0) {
      if (zero_to_one) return sgn(v.z_c) < 0;
      mpq_neg(minus_w.get_mpq_t(), v.w_c.get_mpq_t());
      return v.z_c < minus_w;
    }
    if (p == 1) return v.z_c > v.w_c;
    return sgn(v.clip_distances[p - 2]) < 0;
  };
  mpq_class scratch;
  bool w_made = false;
  LinearForm w;
  // Under GL_DEPTH_CLAMP the near and far planes clip nothing: the user planes only.
  for (size_t p = t.depth_clamp ? 2 : 0; p < 2 + users; ++p) {
    if (!outside(p, 0) && !outside(p, 1) && !outside(p, 2)) continue;
    // b_i is proportional to E'_i with a positive factor, so the sign of the distance at the
    // pixel is sign(sum E'_i·d_i), d_i vertex i's: exact products, per triangle.
    LinearForm f;
    for (int i = 0; i < 3; ++i)
      f.add_product(t.homogeneous_edges[i], distance(p, i), scratch);
    // d/w_c at a pixel is form / Δ with Δ = Σ E'_i·w_c,i; the scale is |Δ| over the form's
    // gradient (doubles: it sizes a band, it decides no bit).
    if (!w_made) {
      for (int i = 0; i < 3; ++i)
        w.add_product(t.homogeneous_edges[i], t.v[i].w_c, scratch);
      w_made = true;
    }
    ClipPlane plane;
    const double g = std::hypot(f.a.get_d(), f.b.get_d());
    plane.scale = g > 0 ? std::fabs(w.c.get_d()) / g : 0.0;
    plane.sign = SignEvaluator(f);
    out.planes.push_back(std::move(plane));
  }
  return out;
}

}  // namespace glrc::ref
