#include "ref/viewport.hpp"

namespace glrc::ref {

WindowVertex to_window(const Vertex& v, const Case& c) {
  const mpq_class x_c(double(v.clip[0])), y_c(double(v.clip[1])), z_c(double(v.clip[2])),
      w_c(double(v.clip[3]));
  const Viewport& vp = c.viewport;
  const mpq_class half_w = mpq_class(vp.width) / 2, half_h = mpq_class(vp.height) / 2;
  const mpq_class n(double(c.depth_near)), f(double(c.depth_far));
  WindowVertex out;
  out.x_h = x_c * half_w + w_c * (vp.x + half_w);
  out.y_h = y_c * half_h + w_c * (vp.y + half_h);
  out.z_c = z_c;
  out.w_c = w_c;
  out.wz_w = z_c * (f - n) / 2 + w_c * (n + f) / 2;
  for (mpq_class* q : {&out.x_h, &out.y_h, &out.wz_w})
    q->canonicalize();
  return out;
}

}  // namespace glrc::ref
