#include "ref/exact.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace glrc::ref {

namespace {

// Unit roundoff of double.
constexpr double kU = 0x1p-53;

uint32_t bits_of(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// A double approximation of q with relative error below 2^-52, or false when q is outside the
// range where that holds (so no fast path may rely on it).
bool to_double(const mpq_class& q, double& out) {
  out = q.get_d();  // truncates: relative error < 2^-52 for normal results
  if (q == 0) return out == 0.0;
  double m = std::fabs(out);
  return std::isfinite(out) && m > 0x1p-900 && m < 0x1p900;
}

}  // namespace

float round_to_float(const mpz_class& num, const mpz_class& den) {
  if (num == 0) return 0.0f;
  const bool negative = num < 0;
  mpz_class n = abs(num);
  // n/den lies in [2^(e-1), 2^(e+1)).
  const long e = long(mpz_sizeinbase(n.get_mpz_t(), 2)) - long(mpz_sizeinbase(den.get_mpz_t(), 2));
  const float sign = negative ? -1.0f : 1.0f;
  if (e > 130) return sign * std::numeric_limits<float>::infinity();
  if (e < -160) return sign * 0.0f;  // below half the smallest subnormal: rounds to zero
  // q = floor(n·2^s / den) with 26 or 27 bits; `sticky` says whether anything was cut off.
  const long s = 26 - e;
  mpz_class q, r;
  if (s >= 0) {
    mpz_class scaled = n << s;
    mpz_fdiv_qr(q.get_mpz_t(), r.get_mpz_t(), scaled.get_mpz_t(), den.get_mpz_t());
  } else {
    mpz_class scaled_den = den << -s;
    mpz_fdiv_qr(q.get_mpz_t(), r.get_mpz_t(), n.get_mpz_t(), scaled_den.get_mpz_t());
  }
  const bool sticky = r != 0;
  const long k = long(mpz_sizeinbase(q.get_mpz_t(), 2));
  const long exponent = k - 1 - s;  // value in [2^exponent, 2^(exponent+1))
  // Bits of q to drop: down to 24 significant bits, or down to the 2^-149 position for
  // subnormal results.
  const long drop = exponent >= -126 ? k - 24 : s - 149;
  // drop >= 2 always (k >= 26; subnormal exponent < -126 gives s > k + 125).
  mpz_class kept = q >> drop;
  mpz_class rest = q - (kept << drop);
  const mpz_class half = mpz_class(1) << (drop - 1);
  const int order = cmp(rest, half);
  if (order > 0 || (order == 0 && (sticky || mpz_odd_p(kept.get_mpz_t())))) kept += 1;
  // kept <= 2^24: exact in double; the power-of-two scaling is exact; the cast to float is exact
  // unless the value is 2^128 or more, which becomes infinity as IEEE rounding requires.
  const double magnitude = std::ldexp(kept.get_d(), int(drop - s));
  return sign * float(magnitude);
}

bool Dyadic::of(const mpq_class& q, Dyadic& out) {
  const mpz_srcptr den = q.get_den_mpz_t();
  const mp_bitcnt_t zeros = mpz_scan1(den, 0);  // den >= 1: a power of two iff one bit is set
  if (mpz_sizeinbase(den, 2) != zeros + 1) return false;
  out.m = q.get_num();
  out.e = -long(zeros);
  return true;
}

mpq_class Dyadic::rational() const {
  mpq_class q;
  to(q);
  return q;
}

void Dyadic::to(mpq_class& out) const {
  mpz_ptr num = mpq_numref(out.get_mpq_t()), den = mpq_denref(out.get_mpq_t());
  mpz_set_ui(den, 1);
  if (sgn(m) == 0) {
    mpz_set_ui(num, 0);
    return;
  }
  if (e >= 0) {
    mpz_mul_2exp(num, m.get_mpz_t(), mp_bitcnt_t(e));
    return;
  }
  // m/2^-e in lowest terms: the twos they share cancel (m's trailing zeros, at most -e of them).
  const mp_bitcnt_t shared = std::min<mp_bitcnt_t>(mpz_scan1(m.get_mpz_t(), 0), mp_bitcnt_t(-e));
  mpz_tdiv_q_2exp(num, m.get_mpz_t(), shared);
  mpz_mul_2exp(den, den, mp_bitcnt_t(-e) - shared);
}

double truncated_quotient(const mpq_class& n, const mpq_class& d) {
  // (n.num·d.den) / (n.den·d.num), not in lowest terms: mpq_get_d divides the two integers and
  // truncates, which gives the same double for any pair of the same ratio.
  thread_local mpq_class q;
  mpz_mul(mpq_numref(q.get_mpq_t()), n.get_num_mpz_t(), d.get_den_mpz_t());
  mpz_mul(mpq_denref(q.get_mpq_t()), n.get_den_mpz_t(), d.get_num_mpz_t());
  return mpq_get_d(q.get_mpq_t());
}

void sum_of_products(Dyadic& out, const Dyadic* const* a, const Dyadic* const* b, int n) {
  // Each product exactly, then every one shifted up to the smallest exponent among the nonzero
  // ones and added: integers throughout. The products and the total in integers kept per
  // thread, which soon hold enough limbs: no allocation per call but out's own.
  thread_local mpz_class product[3], total;
  long exponent[3] = {};
  long smallest = std::numeric_limits<long>::max();
  for (int i = 0; i < n; ++i) {
    mpz_mul(product[i].get_mpz_t(), a[i]->m.get_mpz_t(), b[i]->m.get_mpz_t());
    exponent[i] = a[i]->e + b[i]->e;
    if (sgn(product[i]) != 0) smallest = std::min(smallest, exponent[i]);
  }
  if (smallest == std::numeric_limits<long>::max()) {  // every product 0
    out.m = 0;
    out.e = 0;
    return;
  }
  mpz_set_ui(total.get_mpz_t(), 0);
  for (int i = 0; i < n; ++i) {
    if (sgn(product[i]) == 0) continue;
    mpz_mul_2exp(product[i].get_mpz_t(), product[i].get_mpz_t(),
                 mp_bitcnt_t(exponent[i] - smallest));
    mpz_add(total.get_mpz_t(), total.get_mpz_t(), product[i].get_mpz_t());
  }
  mpz_set(out.m.get_mpz_t(), total.get_mpz_t());
  out.e = smallest;
}

void cross_term(Dyadic& out, const Dyadic& a, const Dyadic& b, const Dyadic& c, const Dyadic& d) {
  // As sum_of_products, the second product subtracted.
  thread_local mpz_class first, second;
  mpz_mul(first.get_mpz_t(), a.m.get_mpz_t(), b.m.get_mpz_t());
  mpz_mul(second.get_mpz_t(), c.m.get_mpz_t(), d.m.get_mpz_t());
  long e1 = a.e + b.e, e2 = c.e + d.e;
  if (sgn(first) == 0) e1 = e2;
  if (sgn(second) == 0) e2 = e1;
  const long smallest = std::min(e1, e2);
  mpz_mul_2exp(first.get_mpz_t(), first.get_mpz_t(), mp_bitcnt_t(e1 - smallest));
  mpz_mul_2exp(second.get_mpz_t(), second.get_mpz_t(), mp_bitcnt_t(e2 - smallest));
  mpz_sub(out.m.get_mpz_t(), first.get_mpz_t(), second.get_mpz_t());
  out.e = smallest;
}

mpz_class to_mpz(int128 v) {
  const bool negative = v < 0;
  const uint128 u = negative ? -uint128(v) : uint128(v);
  mpz_class z(static_cast<unsigned long>(u >> 64));
  z <<= 64;
  z += static_cast<unsigned long>(u & ~0UL);
  return negative ? mpz_class(-z) : z;
}

float round_to_float(const mpq_class& q) {
  return round_to_float(q.get_num(), q.get_den());
}

SignEvaluator::SignEvaluator(const LinearForm& f) : form_(f) {
  fast_ = to_double(f.a, a_) && to_double(f.b, b_) && to_double(f.c, c_);
  da_ = f.a.get_d(), db_ = f.b.get_d(), dc_ = f.c.get_d();
  const double norm = std::hypot(da_, db_);
  inv_norm_ = norm > 0 ? 1.0 / norm : 0.0;
  // What row_bound needs of the form on every row, once.
  spans_ = inv_norm_ > 0 && std::isfinite(inv_norm_) && std::isfinite(da_) && std::isfinite(db_) &&
           std::isfinite(dc_);
  scale_ = spans_ ? 1 / inv_norm_ : 0.0;
  inverse_abs_da_ = da_ != 0 ? 1 / std::fabs(da_) : 0.0;
  inverse_da_ = da_ != 0 ? 1 / da_ : 0.0;
}

int SignEvaluator::sign(long px, long py) const {
  if (fast_) {
    const double x = double(px), y = double(py);
    const double v = a_ * x + b_ * y + c_;
    // Each coefficient carries relative error 2^-52, each product and sum at most u more, fused
    // or not: |v - exact| <= 5u·S. 8u·S covers that and the rounding of S itself.
    const double bound = 8 * kU * (std::fabs(a_ * x) + std::fabs(b_ * y) + std::fabs(c_));
    if (v > bound) return 1;
    if (v < -bound) return -1;
  }
  return form_ ? sgn(form_->at(px, py)) : 0;  // a default evaluator's form is 0
}

SignEvaluator::RowBound SignEvaluator::row_bound(double grow, long x_lo, long x_hi, long y_lo,
                                                 long y_hi) const {
  RowBound every;  // kind every
  if (!spans_) return every;
  const double x_max = std::max(std::fabs(double(x_lo)), std::fabs(double(x_hi)));
  const double y_max = std::max(std::fabs(double(y_lo)), std::fabs(double(y_hi)));
  // With F = da·x + db·y + dc (exact, of the double coefficients) and S = |da·x| + |db·y| +
  // |dc| <= terms over the rows: distance() is F computed (off by at most 4u·S, fused or not)
  // times inv_norm_ (u more), and F is off from the exact form by 2u·S (its coefficients,
  // which get_d truncates), the norm by a few u (hypot's and the reciprocal's roundings): the
  // widening below takes over twice all of it. Beyond a quarter pixel the walk takes every
  // pixel.
  const double terms = std::fabs(da_) * x_max + std::fabs(db_) * y_max + std::fabs(dc_);
  if (8 * kU * terms * inv_norm_ > 0.25) return every;
  // So every pixel with distance() >= -grow, and every one within grow of the exact line, has
  //   da·x >= -grow·scale·(1 + 4u) - (db·y + dc) - 5u·terms
  // with scale = 1/inv_norm_ (scale_ rounded it), which is x >= x(y) - (4u·grow·scale +
  // 5u·terms)/|da| for da > 0 (<= and + for da < 0), with x(y) = alpha·y + beta:
  //   alpha = -db/da,   beta = (-grow·scale - dc)/da.
  const double scale = scale_;
  const double gs = grow * scale;
  if (da_ == 0) {
    // No x bound: every pixel of a row or none, by the row's value of db·y + dc, which is
    // checked at both ends of the rows (linear in y: between them too).
    RowBound none;
    none.kind = RowBound::none;
    const double slack = 16 * kU * (gs + terms);
    for (const double y : {double(y_lo), double(y_hi)})
      if (-gs - (db_ * y + dc_) - slack <= 0) return every;
    return none;
  }
  RowBound b;
  b.kind = da_ > 0 ? RowBound::from : RowBound::to;
  // Each computed by the reciprocal of da: beta off by at most 4u·(gs + |dc|)/|da|, alpha·y by
  // 3u·|db·y|/|da|, their sum and the step by widen by u·|x| and u·widen more: with T = gs +
  // |dc| + |db|·y_max, under 10u·T/|da| + u·widen in all, on top of the slack above. widen
  // takes 32u·(T + terms)/|da|, more than twice that, and 2^-20 pixel for underflow.
  b.alpha = -db_ * inverse_da_;
  b.beta = (-gs - dc_) * inverse_da_;
  const double t = gs + std::fabs(dc_) + std::fabs(db_) * y_max;
  b.widen = 32 * kU * (t + terms) * inverse_abs_da_ + 0x1p-20;
  // Every x(y) over the rows finite, no larger than t/|da|.
  if (!std::isfinite(b.alpha) || !std::isfinite(b.beta) || !std::isfinite(b.widen) ||
      !std::isfinite(t * inverse_abs_da_ * 2))
    return every;
  return b;
}

RatioEvaluator::RatioEvaluator(const LinearForm& numerator, const LinearForm& denominator) {
  fast_ = to_double(numerator.a, fan_) && to_double(numerator.b, fbn_) &&
          to_double(numerator.c, fcn_) && to_double(denominator.a, fad_) &&
          to_double(denominator.b, fbd_) && to_double(denominator.c, fcd_);
  // One common denominator for all six coefficients: the ratio is unchanged and the exact path
  // then needs integers only. The multiple and the quotients in integers kept per thread, the
  // products made in the evaluator's own: temporaries were a dozen allocations per plane of
  // every triangle.
  thread_local mpz_class common, factor;
  mpz_set_ui(common.get_mpz_t(), 1);
  for (const mpq_class* q :
       {&numerator.a, &numerator.b, &numerator.c, &denominator.a, &denominator.b, &denominator.c})
    mpz_lcm(common.get_mpz_t(), common.get_mpz_t(), q->get_den_mpz_t());
  auto scaled = [&](mpz_class& out, const mpq_class& q) {
    mpz_divexact(factor.get_mpz_t(), common.get_mpz_t(), q.get_den_mpz_t());
    mpz_mul(out.get_mpz_t(), q.get_num_mpz_t(), factor.get_mpz_t());
  };
  scaled(an_, numerator.a), scaled(bn_, numerator.b), scaled(cn_, numerator.c);
  scaled(ad_, denominator.a), scaled(bd_, denominator.b), scaled(cd_, denominator.c);
}

float RatioEvaluator::exact_at(long px, long py) const {
  // Scratch per thread: the reference's tiles evaluate one triangle's planes in parallel, and
  // GMP integers allocated once per thread, not per call.
  thread_local mpz_class n, d;
  n = an_ * px + bn_ * py + cn_;
  d = ad_ * px + bd_ * py + cd_;
  if (d < 0) {
    n = -n;
    d = -d;
  }
  if (d == 0) return std::numeric_limits<float>::quiet_NaN();  // never inside a triangle
  return round_to_float(n, d);
}

bool RatioEvaluator::fast_coefficients(double out[6]) const {
  const double c[6] = {fan_, fbn_, fcn_, fad_, fbd_, fcd_};
  std::copy(c, c + 6, out);
  return fast_;
}

float RatioEvaluator::at(long px, long py) const {
  if (fast_) {
    const double x = double(px), y = double(py);
    const double n = fan_ * x + fbn_ * y + fcn_;
    const double d = fad_ * x + fbd_ * y + fcd_;
    // Bounds as in SignEvaluator::sign.
    const double en = 8 * kU * (std::fabs(fan_ * x) + std::fabs(fbn_ * y) + std::fabs(fcn_));
    const double ed = 8 * kU * (std::fabs(fad_ * x) + std::fabs(fbd_ * y) + std::fabs(fcd_));
    const double ad = std::fabs(d);
    if (ad > 4 * ed) {
      const double q = n / d;
      // |n/d - ñ/d̃| <= (en + |q|·ed) / (|d̃| - ed); plus the rounding of the division and of
      // q ± err themselves (4u|q|); then 1% for the rounding of this bound's own arithmetic.
      const double err =
          ((en + std::fabs(q) * ed) / (ad - ed) + 4 * kU * std::fabs(q)) * 1.01 + 0x1p-1000;
      const float lo = float(q - err), hi = float(q + err);
      if (bits_of(lo) == bits_of(hi) && std::isfinite(lo)) return lo;
    }
  }
  return exact_at(px, py);
}

GLRC_BLOCK_FORM void RatioEvaluator::at(const double* px, const double* py, float* out) const {
  constexpr int n = kRowBlock;
  double decided[n] = {};
  if (fast_) {
    // at()'s fast path and its bound, lane by lane; every quantity 64 bits wide.
    double value[n];
    for (int j = 0; j < n; ++j) {
      const double x = px[j], y = py[j];
      const double nv = fan_ * x + fbn_ * y + fcn_;
      const double d = fad_ * x + fbd_ * y + fcd_;
      const double en = 8 * kU * (std::fabs(fan_ * x) + std::fabs(fbn_ * y) + std::fabs(fcn_));
      const double ed = 8 * kU * (std::fabs(fad_ * x) + std::fabs(fbd_ * y) + std::fabs(fcd_));
      const double ad = std::fabs(d);
      const double q = nv / d;
      const double err =
          ((en + std::fabs(q) * ed) / (ad - ed) + 4 * kU * std::fabs(q)) * 1.01 + 0x1p-1000;
      // Both ends rounded to float and back (exact, one to one): the same float when equal
      // with the same sign (-0 and +0 compare equal; NaN never does).
      const double lo = double(float(q - err)), hi = double(float(q + err));
      const bool same = (lo == hi) & (std::copysign(1.0, lo) == std::copysign(1.0, hi));
      const bool finite = std::fabs(lo) <= double(std::numeric_limits<float>::max());
      decided[j] = ((ad > 4 * ed) & same & finite) ? 1.0 : 0.0;
      value[j] = lo;
    }
    // Whether any lane is undecided, as an integer OR (vectorized; a branch per lane is not).
    int64_t undecided = 0;
    for (int j = 0; j < n; ++j) {
      out[j] = float(value[j]);
      undecided |= int64_t(decided[j] != 1);
    }
    if (undecided == 0) return;
  }
  for (int j = 0; j < n; ++j)
    if (decided[j] != 1) out[j] = exact_at(long(px[j]), long(py[j]));
}

}  // namespace glrc::ref
