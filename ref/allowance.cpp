#include "ref/allowance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glrc::ref {

namespace {

// Both forms scaled by one power of two so that their largest coefficient is near 1: the ratio
// is unchanged and the double copies can neither overflow nor underflow.
void normalized_doubles(const LinearForm& n, const LinearForm& d, double out[6]) {
  const mpq_class* q[6] = {&n.a, &n.b, &n.c, &d.a, &d.b, &d.c};
  long e = std::numeric_limits<long>::min();
  for (const mpq_class* x : q)
    if (sgn(*x) != 0)
      e = std::max(e, long(mpz_sizeinbase(x->get_num_mpz_t(), 2)) -
                          long(mpz_sizeinbase(x->get_den_mpz_t(), 2)));
  if (e == std::numeric_limits<long>::min()) e = 0;
  for (int i = 0; i < 6; ++i) {
    mpq_class scaled = *q[i];
    if (e > 0)
      mpq_div_2exp(scaled.get_mpq_t(), q[i]->get_mpq_t(), mp_bitcnt_t(e));
    else
      mpq_mul_2exp(scaled.get_mpq_t(), q[i]->get_mpq_t(), mp_bitcnt_t(-e));
    out[i] = scaled.get_d();
  }
}

}  // namespace

float round_up(double bound) {
  const float f = float(bound);
  return double(f) < bound ? std::nextafter(f, INFINITY) : f;
}

double position_freedom(const Case& c, const TriangleSetup& t, int subpixel_bits) {
  const Viewport& vp = c.viewport;
  double m = std::max({std::fabs(double(vp.x)), std::fabs(double(vp.x) + vp.width),
                       std::fabs(double(vp.y)), std::fabs(double(vp.y) + vp.height),
                       double(c.fb_width), double(c.fb_height)});
  for (const WindowVertex& v : t.v) {
    if (sgn(v.w_c) <= 0) continue;
    m = std::max({m, std::fabs(mpq_class(v.x_h / v.w_c).get_d()),
                  std::fabs(mpq_class(v.y_h / v.w_c).get_d())});
  }
  return std::ldexp(1.0, -subpixel_bits) + kPositionRoundings * kFloatUnitRoundoff * m;
}

Allowance::Allowance(const LinearForm& numerator, const LinearForm& denominator, double delta,
                     double spread, double scale)
    : delta_(delta), spread_(spread), scale_(scale) {
  double c[6];
  normalized_doubles(numerator, denominator, c);
  an_ = c[0], bn_ = c[1], cn_ = c[2], ad_ = c[3], bd_ = c[4], cd_ = c[5];
}

double Allowance::at(int px, int py, float value) const {
  const double v = double(value);
  const double x = px + 0.5, y = py + 0.5;  // window coordinates of the centre
  const double d = ad_ * px + bd_ * py + cd_;
  const double arithmetic_values = kValueRoundings * kFloatUnitRoundoff * scale_;
  if (!(std::fabs(d) > 0) || !std::isfinite(v)) return std::numeric_limits<double>::infinity();
  // The value's gradient per pixel: ∇(N/D) = (∇N - v∇D) / D.
  const double vx = (an_ - v * ad_) / d, vy = (bn_ - v * bd_) / d;
  const double position = std::min(1.5 * delta_ * (std::fabs(vx) + std::fabs(vy)), spread_);
  // Each plane evaluated in float from the window origin: its terms' magnitudes.
  const double n0 = cn_ - (an_ + bn_) / 2, d0 = cd_ - (ad_ + bd_) / 2;
  const double en = std::fabs(n0) + std::fabs(an_ * x) + std::fabs(bn_ * y);
  const double ed = std::fabs(d0) + std::fabs(ad_ * x) + std::fabs(bd_ * y);
  const double evaluation =
      kEvaluationRoundings * kFloatUnitRoundoff * (en + std::fabs(v) * ed) / std::fabs(d);
  return position + evaluation + arithmetic_values;
}

}  // namespace glrc::ref
