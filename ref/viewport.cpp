#include "ref/viewport.hpp"

#include <cmath>

namespace glrc::ref {

namespace {

// x_c·(width/2) + w_c·(x + width/2) = (x_c·width + w_c·(2x + width)) / 2, exactly, into `out`,
// without a rational product: x_c and w_c are floats (24-bit significands), so with |width| and
// |2x + width| below 2^29 both products are exact doubles, and their sum is s + e exactly
// (Knuth's TwoSum, exact in round-to-nearest binary64 barring overflow, which these
// magnitudes cannot reach; no product, so nothing for a compiler to fuse). False, and `out`
// untouched, outside those bounds or for a value that is not finite: the caller then
// computes it in rationals. The rational is the same either way: GMP keeps it canonical.
bool window_coordinate(double x_c, double w_c, long width, long x, mpq_class& out) {
  constexpr long kExact = 1L << 29;
  const long sum = 2 * x + width;
  if (!(std::abs(width) < kExact && std::abs(sum) < kExact && std::isfinite(x_c) &&
        std::isfinite(w_c)))
    return false;
  const double a = x_c * double(width), b = w_c * double(sum);
  const double s = a + b;
  const double bb = s - a;
  const double e = (a - (s - bb)) + (b - bb);
  if (!std::isfinite(s)) return false;
  out = s;
  if (e != 0) out += mpq_class(e);
  mpq_div_2exp(out.get_mpq_t(), out.get_mpq_t(), 1);
  return true;
}

}  // namespace

WindowVertex to_window(const Vertex& v, const Case& c) {
  const mpq_class x_c(double(v.clip[0])), y_c(double(v.clip[1])), z_c(double(v.clip[2])),
      w_c(double(v.clip[3]));
  const Viewport& vp = c.viewport;
  const mpq_class n(double(c.depth_near)), f(double(c.depth_far));
  WindowVertex out;
  if (!window_coordinate(v.clip[0], v.clip[3], vp.width, vp.x, out.x_h)) {
    const mpq_class half_w = mpq_class(vp.width) / 2;
    out.x_h = x_c * half_w + w_c * (vp.x + half_w);
  }
  if (!window_coordinate(v.clip[1], v.clip[3], vp.height, vp.y, out.y_h)) {
    const mpq_class half_h = mpq_class(vp.height) / 2;
    out.y_h = y_c * half_h + w_c * (vp.y + half_h);
  }
  out.z_c = z_c;
  out.w_c = w_c;
  out.wz_w = z_c * (f - n) / 2 + w_c * (n + f) / 2;
  for (mpq_class* q : {&out.x_h, &out.y_h, &out.wz_w})
    q->canonicalize();
  return out;
}

}  // namespace glrc::ref
