#include "ref/clipping.hpp"

namespace glrc::ref {

DepthClip depth_clip(const TriangleSetup& t) {
  DepthClip clip;
  // The visible part is sum b_i·vertex_i with b_i >= 0, so if every vertex satisfies a plane,
  // every point does: only a triangle with a vertex outside needs the per-pixel test.
  for (const auto& v : t.v) {
    if (v.z_c < -v.w_c) clip.crosses_near = true;
    if (v.z_c > v.w_c) clip.crosses_far = true;
  }
  // b_i is proportional to E'_i with a positive factor, so sign(z_c + w_c) at the pixel is
  // sign(sum E'_i (z_i + w_i)); likewise for the far plane.
  LinearForm near_form, far_form;
  for (int i = 0; i < 3; ++i) {
    near_form += t.homogeneous_edges[i] * mpq_class(t.v[i].z_c + t.v[i].w_c);
    far_form += t.homogeneous_edges[i] * mpq_class(t.v[i].w_c - t.v[i].z_c);
  }
  if (clip.crosses_near) clip.near = SignEvaluator(near_form);
  if (clip.crosses_far) clip.far = SignEvaluator(far_form);
  return clip;
}

}  // namespace glrc::ref
