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
                     double values, const WindowPolygon& polygon, const WindowPolygon& guard_band,
                     double margin)
    : spread_(spread), values_(values) {
  double c[6];
  normalized_doubles(numerator, denominator, c);
  an_ = c[0], bn_ = c[1], cn_ = c[2], ad_ = c[3], bd_ = c[4], cd_ = c[5];
  // The forms take pixel coordinates px = x - 1/2.
  auto n_at = [&](double x, double y) { return an_ * (x - 0.5) + bn_ * (y - 0.5) + cn_; };
  auto d_at = [&](double x, double y) { return ad_ * (x - 0.5) + bd_ * (y - 0.5) + cd_; };
  anchors_.push_back({0, 0, std::fabs(n_at(0, 0)), std::fabs(d_at(0, 0))});
  if (!(margin >= 0)) margin = 0;
  bool finite = true;
  for (const WindowPolygon* p : {&polygon, &guard_band})
    for (const auto& a : *p) {
      const bool here = std::isfinite(a[0]) && std::isfinite(a[1]);
      if (here)
        anchors_.push_back({a[0], a[1], std::fabs(n_at(a[0], a[1])), std::fabs(d_at(a[0], a[1]))});
      finite = finite && (here || p != &polygon);
    }
  if (finite) {
    // Every triangle of the polygon's vertices may be one of the implementation's fan.
    const size_t n = polygon.size();
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j)
        for (size_t k = j + 1; k < n; ++k) {
          const std::array<double, 2> q[3] = {polygon[i], polygon[j], polygon[k]};
          const double area2 =
              (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[2][0] - q[0][0]) * (q[1][1] - q[0][1]);
          // Three vertices on one line (on one clip plane): nothing to draw.
          if (!(std::fabs(area2) > 0)) continue;
          FanTriangle t{};
          t.box[0] = std::min({q[0][0], q[1][0], q[2][0]}) - margin;
          t.box[1] = std::min({q[0][1], q[1][1], q[2][1]}) - margin;
          t.box[2] = std::max({q[0][0], q[1][0], q[2][0]}) + margin;
          t.box[3] = std::max({q[0][1], q[1][1], q[2][1]}) + margin;
          const double orientation = area2 > 0 ? 1 : -1;
          for (int e = 0; e < 3; ++e) {
            const auto& a = q[e];
            const auto& b = q[(e + 1) % 3];
            // Left of a->b for a counter-clockwise triangle: inside.
            double ea = -(b[1] - a[1]) * orientation, eb = (b[0] - a[0]) * orientation;
            const double length = std::hypot(ea, eb);
            ea /= length, eb /= length;
            t.edge[e][0] = ea, t.edge[e][1] = eb, t.edge[e][2] = -(ea * a[0] + eb * a[1]) + margin;
          }
          for (int a = 0; a < 3; ++a) {
            const auto& qi = q[a];
            const auto& qj = q[(a + 1) % 3];
            const auto& qk = q[(a + 2) % 3];
            const double e1x = qj[0] - qi[0], e1y = qj[1] - qi[1];
            const double e2x = qk[0] - qi[0], e2y = qk[1] - qi[1];
            const double n_i = n_at(qi[0], qi[1]), d_i = d_at(qi[0], qi[1]);
            const double dn1 = std::fabs(n_at(qj[0], qj[1]) - n_i),
                         dn2 = std::fabs(n_at(qk[0], qk[1]) - n_i);
            const double dd1 = std::fabs(d_at(qj[0], qj[1]) - d_i),
                         dd2 = std::fabs(d_at(qk[0], qk[1]) - d_i);
            const double inverse = 1 / std::fabs(area2);
            SetupAnchor& s = t.anchor[a];
            s.x = qi[0], s.y = qi[1], s.n = n_i, s.d = d_i;
            s.nx = (dn1 * std::fabs(e2y) + dn2 * std::fabs(e1y)) * inverse;
            s.ny = (dn1 * std::fabs(e2x) + dn2 * std::fabs(e1x)) * inverse;
            s.dx = (dd1 * std::fabs(e2y) + dd2 * std::fabs(e1y)) * inverse;
            s.dy = (dd1 * std::fabs(e2x) + dd2 * std::fabs(e1x)) * inverse;
            s.kappa = (std::fabs(e1x * e2y) + std::fabs(e2x * e1y)) * inverse;
          }
          fan_.push_back(t);
        }
  }
}

double Allowance::setup_at(double x, double y, double n, double d, double v) const {
  double worst = 0;
  for (const FanTriangle& t : fan_) {
    if (x < t.box[0] || x > t.box[2] || y < t.box[1] || y > t.box[3]) continue;
    bool inside = true;
    for (const auto& e : t.edge)
      inside = inside && e[0] * x + e[1] * y + e[2] >= 0;
    if (!inside) continue;
    for (const SetupAnchor& s : t.anchor) {
      const double ax = std::fabs(x - s.x), ay = std::fabs(y - s.y);
      const double in = s.nx * ax + s.ny * ay + s.kappa * std::fabs(n - s.n);
      const double id = s.dx * ax + s.dy * ay + s.kappa * std::fabs(d - s.d);
      worst = std::max(worst, in + std::fabs(v) * id);
    }
  }
  return worst;
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
  const double n = an_ * px + bn_ * py + cn_;
  const double setup =
      kSetupRoundings * kFloatUnitRoundoff * setup_at(x, y, n, d, v) / std::fabs(d);
  return position + evaluation + setup + values_ + extra;
}

}  // namespace glrc::ref
