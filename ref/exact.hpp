// Exact arithmetic for the reference: rationals (GMP), rounding a rational to the nearest
// float32, and linear forms in the integer pixel coordinates (px, py) evaluated exactly, with a
// double-precision fast path taken only when its rigorous error bound proves the same result.
#pragma once

#include <gmpxx.h>

#include "ref/blocks.hpp"

#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

namespace glrc::ref {

// Signed 128-bit integers for snapped fixed-point edge functions (GCC/Clang extension).
__extension__ typedef __int128 int128;
__extension__ typedef unsigned __int128 uint128;

// GMP has no 128-bit constructor.
mpz_class to_mpz(int128 v);

// The float32 nearest to num/den (den > 0), ties to even, with float32's subnormals and
// overflow to infinity. Exact: depends on nothing but the two integers.
float round_to_float(const mpz_class& num, const mpz_class& den);
float round_to_float(const mpq_class& q);

// m·2^e exactly: a dyadic rational. Every number of an unsnapped plane is one (a float32 clip
// coordinate or value, the viewport's halves, their products and sums), and products and sums
// of them need neither the gcd that mpq_class takes after every operation nor a common
// denominator: the mantissas are multiplied, or shifted to the smaller exponent and added.
// rational() gives the canonical mpq_class, the same rational mpq_class arithmetic gives, so
// whatever is built from it has the same bits.
struct Dyadic {
  mpz_class m;  // 0: the value 0, whatever e is
  long e = 0;

  // q as m·2^e when its denominator is a power of two (always true of 0); false otherwise.
  static bool of(const mpq_class& q, Dyadic& out);
  mpq_class rational() const;
  // rational() into `out`, whose limbs are reused: no temporary to allocate and free.
  void to(mpq_class& out) const;
  int sign() const { return sgn(m); }
};

// n/d (d > 0) truncated to a double, as mpq_class(n / d).get_d() gives it, without the gcds
// of the division's canonical form: the quotient's truncation depends on its value alone.
double truncated_quotient(const mpq_class& n, const mpq_class& d);

// out = Σ_i a_i·b_i, exactly, over n <= 3 terms (out may be none of the inputs).
void sum_of_products(Dyadic& out, const Dyadic* const* a, const Dyadic* const* b, int n);
// out = a·b - c·d exactly (a cross product's component).
void cross_term(Dyadic& out, const Dyadic& a, const Dyadic& b, const Dyadic& c, const Dyadic& d);

// f(px, py) = a·px + b·py + c with exact rational coefficients.
struct LinearForm {
  mpq_class a, b, c;

  mpq_class at(long px, long py) const { return a * px + b * py + c; }
  LinearForm& operator+=(const LinearForm& o) {
    a += o.a, b += o.b, c += o.c;
    return *this;
  }
  LinearForm operator*(const mpq_class& s) const { return {a * s, b * s, c * s}; }
  // *this += o·s, the products made in `scratch`: one rational's storage reused, where
  // += o * s makes a form of three temporaries (six allocations) per term.
  void add_product(const LinearForm& o, const mpq_class& s, mpq_class& scratch) {
    mpq_mul(scratch.get_mpq_t(), o.a.get_mpq_t(), s.get_mpq_t());
    a += scratch;
    mpq_mul(scratch.get_mpq_t(), o.b.get_mpq_t(), s.get_mpq_t());
    b += scratch;
    mpq_mul(scratch.get_mpq_t(), o.c.get_mpq_t(), s.get_mpq_t());
    c += scratch;
  }
};

// The sign of a LinearForm at integer pixels. Fast path: the form in double, with an error
// bound that holds whether or not the compiler fuses multiply-adds; exact otherwise.
class SignEvaluator {
 public:
  SignEvaluator() = default;
  explicit SignEvaluator(const LinearForm& f);
  int sign(long px, long py) const;  // -1, 0, +1
  // The form divided by the length of its gradient: the signed distance in pixels of the pixel
  // centre from the line f = 0 (approximate, for classification only).
  double distance(long px, long py) const {  // inline: per pixel of every band
    return (da_ * double(px) + db_ * double(py) + dc_) * inv_norm_;
  }
  // For every row py in [y_lo, y_hi], the pixels whose centre is at least -grow pixels from the
  // line (distance() >= -grow), as an interval RowBound::at(py) = [lo, hi] of px that may hold
  // more but never misses one; it holds every pixel whose centre is within grow of the exact
  // line too. The bound is linear in py (the line's x-intercept walked from row to row),
  // widened for the rounding of both this and distance() over all those rows by their error
  // bounds (a few ulps of the terms), not by a pixel: a thin triangle's rows are then walked
  // over the pixels it reaches. lo = -infinity or hi = +infinity for an unbounded side, lo > hi
  // for no pixel. Where distance() itself may be off by a quarter pixel or more over px in
  // [x_lo, x_hi] (coefficients beyond 2^40 pixels), or the form has no gradient, every px: the
  // caller then tests each pixel as before. For walking only the pixels a triangle can reach
  // (render.cpp).
  struct RowBound {
    enum Kind : uint8_t { every, none, from, to } kind = every;
    double alpha = 0, beta = 0, widen = 0;  // from: px >= alpha·py + beta - widen; to: <= ... +
    std::pair<double, double> at(double py) const {  // inline: per row of every triangle
      constexpr double inf = std::numeric_limits<double>::infinity();
      switch (kind) {
        case from:
          return {alpha * py + beta - widen, inf};
        case to:
          return {-inf, alpha * py + beta + widen};
        case none:
          return {inf, -inf};
        default:
          return {-inf, inf};
      }
    }
  };
  RowBound row_bound(double grow, long x_lo, long x_hi, long y_lo, long y_hi) const;

 private:
  // Only in an evaluator built from a form: a default one (a CoverageTest's edges on the snapped
  // path, no ClipPlanes to test) allocates nothing, where a LinearForm's three
  // rationals are three allocations (GMP's mpq_init makes the denominator's limb) and frees,
  // five evaluators for every triangle of a frame.
  std::optional<LinearForm> form_;
  double a_ = 0, b_ = 0, c_ = 0;                    // range-checked copies for the fast sign
  double da_ = 0, db_ = 0, dc_ = 0, inv_norm_ = 0;  // unchecked copies for distance()
  double scale_ = 0, inverse_abs_da_ = 0, inverse_da_ = 0;  // 1 / inv_norm_, 1 / |da_|, 1 / da_
  bool spans_ = false;  // row_bound can bound a span: finite copies and a gradient
  bool fast_ = false;
};

// N(px,py) / D(px,py) rounded to float32, for two LinearForms. The exact path works on integer
// coefficients over a common denominator; the fast path in double is used only when the
// interval its error bound gives rounds to a single float. Safe to call from several threads.
class RatioEvaluator {
 public:
  RatioEvaluator() = default;
  RatioEvaluator(const LinearForm& numerator, const LinearForm& denominator);
  float at(long px, long py) const;
  // at() of kRowBlock pixels (px[j], py[j]) (integer pixel coordinates as doubles) at once:
  // the same floats (each the float nearest its exact ratio), the fast path in loops over the
  // lanes (ref/blocks.hpp), the exact path for a lane it leaves undecided.
  void at(const double* px, const double* py, float* out) const;
  float exact_at(long px, long py) const;  // the exact path alone, for tests
  // The double copies the fast path uses (N's a, b, c, then D's), each within a relative 2^-52
  // of the exact coefficient; false when there is no fast path.
  bool fast_coefficients(double out[6]) const;

 private:
  mpz_class an_, bn_, cn_, ad_, bd_, cd_;
  double fan_ = 0, fbn_ = 0, fcn_ = 0, fad_ = 0, fbd_ = 0, fcd_ = 0;
  bool fast_ = false;
};

}  // namespace glrc::ref
