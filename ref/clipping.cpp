#include "ref/clipping.hpp"

#include <cmath>

namespace glrc::ref {

DepthClip depth_clip(const TriangleSetup& t) {
  DepthClip clip;
  // The visible part is sum b_i·vertex_i with b_i >= 0, so if every vertex satisfies a plane,
  // every point does: only a triangle with a vertex outside needs the per-pixel test.
  // -w_c in a rational kept per thread: as an expression's temporary it was allocated and freed
  // for every vertex of every triangle.
  thread_local mpq_class minus_w;
  for (const auto& v : t.v) {
    mpq_neg(minus_w.get_mpq_t(), v.w_c.get_mpq_t());
    if (v.z_c < minus_w) clip.crosses_near = true;
    if (v.z_c > v.w_c) clip.crosses_far = true;
  }
  // b_i is proportional to E'_i with a positive factor, so sign(z_c + w_c) at the pixel is
  // sign(sum E'_i (z_i + w_i)); likewise for the far plane. Built only for a plane crossed:
  // exact products, per triangle.
  if (!clip.crosses_near && !clip.crosses_far) return clip;  // most triangles: no exact work
  mpq_class scratch;
  auto form = [&](int plane) {
    LinearForm f;
    for (int i = 0; i < 3; ++i)
      f.add_product(t.homogeneous_edges[i], mpq_class(t.v[i].w_c + plane * t.v[i].z_c), scratch);
    return SignEvaluator(f);
  };
  if (clip.crosses_near) clip.near = form(1);
  if (clip.crosses_far) clip.far = form(-1);
  // 1 ± z_n at a pixel is form / Δ with Δ = Σ E'_i·w_c,i, constant over the window; the scale
  // is |Δ| over the form's gradient (doubles: it sizes a band, it decides no bit).
  LinearForm w;
  for (int i = 0; i < 3; ++i)
    w.add_product(t.homogeneous_edges[i], t.v[i].w_c, scratch);
  auto scale = [&](int plane) {
    LinearForm f;
    for (int i = 0; i < 3; ++i)
      f.add_product(t.homogeneous_edges[i], mpq_class(t.v[i].w_c + plane * t.v[i].z_c), scratch);
    const double g = std::hypot(f.a.get_d(), f.b.get_d());
    return g > 0 ? std::fabs(w.c.get_d()) / g : 0.0;
  };
  if (clip.crosses_near) clip.near_scale = scale(1);
  if (clip.crosses_far) clip.far_scale = scale(-1);
  return clip;
}

}  // namespace glrc::ref
