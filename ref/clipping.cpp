#include "ref/clipping.hpp"

#include <cmath>

namespace glrc::ref {

DepthClip depth_clip(const TriangleSetup& t) {
  DepthClip clip;
  // The visible part is sum b_i·vertex_i with b_i >= 0, so if every vertex satisfies a plane,
  // every point does: only a triangle with a vertex outside needs the per-pixel test.
  // -w_c in a rational kept per thread: as an expression's temporary it was allocated and freed
  // for every vertex of every triangle.
  // The near plane's distance is z_c + w_c, or z_c under GL_ZERO_TO_ONE (near_distance);
  // the far plane's w_c − z_c.
  const bool zero_to_one = t.clip_depth == ClipDepth::zero_to_one;
  thread_local mpq_class minus_w;
  for (const auto& v : t.v) {
    if (zero_to_one) {
      if (sgn(v.z_c) < 0) clip.crosses_near = true;
    } else {
      mpq_neg(minus_w.get_mpq_t(), v.w_c.get_mpq_t());
      if (v.z_c < minus_w) clip.crosses_near = true;
    }
    if (v.z_c > v.w_c) clip.crosses_far = true;
  }
  // b_i is proportional to E'_i with a positive factor, so the sign of the near distance at
  // the pixel is sign(sum E'_i·d_i) with d_i vertex i's; likewise for the far plane. Built
  // only for a plane crossed: exact products, per triangle.
  if (!clip.crosses_near && !clip.crosses_far) return clip;  // most triangles: no exact work
  mpq_class scratch;
  auto distance = [&](int i, bool near) -> mpq_class {
    if (!near) return t.v[i].w_c - t.v[i].z_c;
    return zero_to_one ? t.v[i].z_c : mpq_class(t.v[i].w_c + t.v[i].z_c);
  };
  auto form = [&](bool near) {
    LinearForm f;
    for (int i = 0; i < 3; ++i)
      f.add_product(t.homogeneous_edges[i], distance(i, near), scratch);
    return f;
  };
  // The distance over w_c at a pixel (1 + z_n, z_n under GL_ZERO_TO_ONE, or 1 − z_n) is
  // form / Δ with Δ = Σ E'_i·w_c,i, constant over the window; the scale is |Δ| over the
  // form's gradient (doubles: it sizes a band, it decides no bit).
  LinearForm w;
  for (int i = 0; i < 3; ++i)
    w.add_product(t.homogeneous_edges[i], t.v[i].w_c, scratch);
  auto scale = [&](const LinearForm& f) {
    const double g = std::hypot(f.a.get_d(), f.b.get_d());
    return g > 0 ? std::fabs(w.c.get_d()) / g : 0.0;
  };
  if (clip.crosses_near) {
    const LinearForm f = form(true);
    clip.near_scale = scale(f);
    clip.near = SignEvaluator(f);
  }
  if (clip.crosses_far) {
    const LinearForm f = form(false);
    clip.far_scale = scale(f);
    clip.far = SignEvaluator(f);
  }
  return clip;
}

}  // namespace glrc::ref
