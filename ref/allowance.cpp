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

double value_freedom(const Case& c, const TriangleSetup& t, double scale, int generations) {
  double w = 1, m = 1 + std::max(c.fb_width, c.fb_height);
  for (uint32_t index : t.index)
    w = std::max(w, std::fabs(double(c.vertices[index].clip[3])));
  m = std::max({m, 1 + std::fabs(double(c.viewport.x)) + c.viewport.width,
                1 + std::fabs(double(c.viewport.y)) + c.viewport.height});
  return (kValueRoundings + kClippedValueRoundings * generations) * kFloatUnitRoundoff * scale +
         kDenormalFlushes * 0x1p-126 * m * w;
}

Allowance::Allowance(const LinearForm& numerator, const LinearForm& denominator, double spread,
                     double values, const std::vector<std::array<double, 2>>& anchors)
    : spread_(spread), values_(values) {
  double c[6];
  normalized_doubles(numerator, denominator, c);
  an_ = c[0], bn_ = c[1], cn_ = c[2], ad_ = c[3], bd_ = c[4], cd_ = c[5];
  // The forms take pixel coordinates px = x - 1/2.
  auto at = [&](double x, double y) -> std::array<double, 4> {
    return {x, y, std::fabs(an_ * (x - 0.5) + bn_ * (y - 0.5) + cn_),
            std::fabs(ad_ * (x - 0.5) + bd_ * (y - 0.5) + cd_)};
  };
  anchors_.push_back(at(0, 0));
  for (const auto& a : anchors)
    if (std::isfinite(a[0]) && std::isfinite(a[1])) anchors_.push_back(at(a[0], a[1]));
}

double Allowance::at(int px, int py, float value, double delta, double extra) const {
  const double v = double(value);
  const double x = px + 0.5, y = py + 0.5;  // window coordinates of the centre
  const double d = ad_ * px + bd_ * py + cd_;
  if (!(std::fabs(d) > 0) || !std::isfinite(v)) return std::numeric_limits<double>::infinity();
  // The value's gradient per pixel: ∇(N/D) = (∇N - v∇D) / D.
  const double vx = (an_ - v * ad_) / d, vy = (bn_ - v * bd_) / d;
  const double position = std::min(1.5 * delta * (std::fabs(vx) + std::fabs(vy)), spread_);
  // Each plane evaluated in float from an anchor: its terms' magnitudes, at the worst anchor.
  double terms = 0;
  for (const auto& a : anchors_) {
    const double en = a[2] + std::fabs(an_ * (x - a[0])) + std::fabs(bn_ * (y - a[1]));
    const double ed = a[3] + std::fabs(ad_ * (x - a[0])) + std::fabs(bd_ * (y - a[1]));
    terms = std::max(terms, en + std::fabs(v) * ed);
  }
  const double evaluation = kEvaluationRoundings * kFloatUnitRoundoff * terms / std::fabs(d);
  return position + evaluation + values_ + extra;
}

}  // namespace glrc::ref
