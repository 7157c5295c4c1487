#include "ref/viewport.hpp"

#include <cmath>

namespace glrc::ref {

namespace {

// Whether d has at most 29 significant bits, so that its product with a float (24) is exact in
// a double (53). False for a value that is not finite.
bool short_significand(double d) {
  if (!std::isfinite(d)) return false;
  int e = 0;
  const double m = std::ldexp(std::frexp(d, &e), 29);  // |m| < 2^29, exact
  return m == std::trunc(m);
}

// s = a + b rounded, and whether that is exact: TwoSum's error term is 0. For finite a and b.
bool exact_sum(double a, double b, double& s) {
  s = a + b;
  const double bb = s - a;
  return std::isfinite(s) && (a - (s - bb)) + (b - bb) == 0;
}

// (a·p + b·q) / 2 exactly, into `out`, without a rational product, for floats a and b and
// doubles p and q of at most 29 significant bits: both products are exact doubles, and their
// sum is s + e exactly (Knuth's TwoSum, exact in round-to-nearest binary64 barring overflow;
// a product fused into a sum changes nothing, every product being exact). False, and `out`
// untouched, when p or q is longer, or a value is not finite: the caller then computes it in
// rationals. The rational is the same either way: GMP keeps it canonical.
bool exact_half_sum(float a, double p, float b, double q, mpq_class& out) {
  if (!short_significand(p) || !short_significand(q) || !std::isfinite(a) || !std::isfinite(b))
    return false;
  const double x = double(a) * p, y = double(b) * q;
  const double s = x + y;
  if (!std::isfinite(s)) return false;
  const double yy = s - x;
  const double e = (x - (s - yy)) + (y - yy);
  out = s;
  if (e != 0) {
    // e in a rational kept per thread: a temporary would be an allocation per vertex.
    thread_local mpq_class error;
    error = e;
    out += error;
  }
  mpq_div_2exp(out.get_mpq_t(), out.get_mpq_t(), 1);
  return true;
}

}  // namespace

double viewport_step(const Viewport& vp) {
  const auto on_grid = [](float f) {
    const double s = std::ldexp(double(f), kViewportSubpixelBits);
    return s == std::floor(s);
  };
  if (on_grid(vp.x) && on_grid(vp.y) && on_grid(vp.width) && on_grid(vp.height)) return 0;
  return std::ldexp(1.0, -kViewportSubpixelBits);
}

double viewport_shift(const Viewport& vp, double x_w, double y_w) {
  const double step = viewport_step(vp);
  if (step == 0) return 0;
  return step * (1 + std::max(std::fabs(x_w - vp.x) / vp.width, std::fabs(y_w - vp.y) / vp.height));
}

WindowVertex to_window(const Vertex& v, const Case& c) {
  const Viewport& vp = c.viewport;
  WindowVertex out;
  // The clip coordinates as rationals straight into the vertex (z_c, w_c), or only where the
  // rational arithmetic below needs them (x_c, y_c): each is an allocation, and a mesh of
  // small triangles transforms tens of thousands of vertices.
  out.z_c = double(v.clip[2]);
  out.w_c = double(v.clip[3]);
  const mpq_class& w_c = out.w_c;
  // x_h = x_c·(width/2) + w_c·(x + width/2) = (x_c·width + w_c·(2x + width)) / 2; integers
  // below 2^29 have short significands. The viewport's bounds are floats (glViewportIndexedf):
  // 2x + width is used only where its double is exact.
  double centre2 = 0;
  if (!exact_sum(2.0 * vp.x, vp.width, centre2) ||
      !exact_half_sum(v.clip[0], double(vp.width), v.clip[3], centre2, out.x_h)) {
    const mpq_class x_c(double(v.clip[0]));
    const mpq_class half_w = mpq_class(vp.width) / 2;
    out.x_h = x_c * half_w + w_c * (vp.x + half_w);
  }
  // GL_UPPER_LEFT: y_c negated (window_y_c), exact in float.
  const float y_c_window = float(window_y_c(c, v.clip[1]));
  if (!exact_sum(2.0 * vp.y, vp.height, centre2) ||
      !exact_half_sum(y_c_window, double(vp.height), v.clip[3], centre2, out.y_h)) {
    const mpq_class y_c{double(y_c_window)};
    const mpq_class half_h = mpq_class(vp.height) / 2;
    out.y_h = y_c * half_h + w_c * (vp.y + half_h);
  }
  const mpq_class& z_c = out.z_c;
  // w_c·z_w = (z_c·(f − n) + w_c·(n + f)) / 2, with f − n and n + f doubles that must be exact
  // (TwoSum's error 0) and short. GL_ZERO_TO_ONE: z_c·(f − n) + w_c·n, the same half sum of
  // 2(f − n) and 2n (doublings, exact).
  const double n = c.depth_near, f = c.depth_far;
  const bool zero_to_one = c.clip_depth == ClipDepth::zero_to_one;
  double difference = 0, sum = 0;
  bool exact = exact_sum(f, -n, difference);
  if (zero_to_one)
    difference *= 2, sum = 2 * n;
  else
    exact = exact && exact_sum(n, f, sum);
  if (!exact || !exact_half_sum(v.clip[2], difference, v.clip[3], sum, out.wz_w)) {
    const mpq_class qn(n), qf(f);
    if (zero_to_one)
      out.wz_w = z_c * (qf - qn) + w_c * qn;
    else
      out.wz_w = z_c * (qf - qn) / 2 + w_c * (qn + qf) / 2;
  }
  for (mpq_class* q : {&out.x_h, &out.y_h, &out.wz_w})
    q->canonicalize();
  for (int i = 0; i < c.distances.clip; ++i)
    if (c.distances.plane_enabled(i))
      out.clip_distances.emplace_back(double(v.distances[size_t(i)]));
  return out;
}

}  // namespace glrc::ref
