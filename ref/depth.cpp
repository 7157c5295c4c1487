#include "ref/depth.hpp"

namespace glrc::ref {

Plane depth_plane(const TriangleSetup& t, const Barycentrics& b, const mpq_class* offset) {
  // Kept per thread: unsnapped planes' weights are copied into their limbs, where six
  // rationals were made and freed per triangle (snapped planes' z_w is a quotient, swapped in).
  thread_local std::array<mpq_class, 3> alpha, beta;
  for (int i = 0; i < 3; ++i) {
    if (b.screen_space) {
      alpha[i] = z_w(t.v[i]);
      beta[i] = 1;
    } else {
      alpha[i] = t.v[i].wz_w;  // w_i·z_w,i
      beta[i] = t.v[i].w_c;
    }
  }
  if (offset)
    for (int i = 0; i < 3; ++i)
      alpha[i] += *offset * beta[i];
  return plane(b, alpha, beta);
}

}  // namespace glrc::ref
