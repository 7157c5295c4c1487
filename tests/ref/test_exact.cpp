// round_to_float and the fast paths of the exact evaluators.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "ref/exact.hpp"

namespace glrc::ref {
namespace {

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

mpq_class pow2(int e) {
  return e >= 0 ? mpq_class(mpz_class(1) << e) : mpq_class(mpz_class(1), mpz_class(1) << -e);
}

TEST(RoundToFloat, KnownValues) {
  EXPECT_EQ(bits(round_to_float(mpq_class(1, 3))), 0x3eaaaaabu);
  EXPECT_EQ(bits(round_to_float(mpq_class(-1, 3))), 0xbeaaaaabu);
  EXPECT_EQ(bits(round_to_float(mpq_class(48, 49))), bits(48.0f / 49.0f));  // single rounding
  EXPECT_EQ(bits(round_to_float(mpq_class(0))), 0u);
  // Ties to even at 2^24: 2^24+1 lies halfway between 2^24 and 2^24+2.
  EXPECT_EQ(round_to_float(mpq_class((1 << 24) + 1)), 16777216.0f);
  EXPECT_EQ(round_to_float(mpq_class((1 << 24) + 3)), 16777220.0f);
  // Subnormals: 3·2^-150 is halfway between 2^-149 and 2^-148 -> 2^-148 (even).
  EXPECT_EQ(round_to_float(pow2(-150) * 3), std::ldexp(1.0f, -148));
  EXPECT_EQ(round_to_float(pow2(-150)), 0.0f);  // tie to even: 0
  EXPECT_EQ(round_to_float(pow2(-150) + pow2(-200)), std::ldexp(1.0f, -149));
  EXPECT_EQ(bits(round_to_float(-pow2(-151))), 0x80000000u);  // -0
  // Overflow: FLT_MAX + half an ulp is a tie that rounds to even, i.e. to 2^128 = infinity.
  const mpq_class flt_max = mpq_class(double(std::numeric_limits<float>::max()));
  EXPECT_EQ(round_to_float(flt_max), std::numeric_limits<float>::max());
  EXPECT_EQ(round_to_float(flt_max + pow2(102)), std::numeric_limits<float>::max());
  EXPECT_TRUE(std::isinf(round_to_float(flt_max + pow2(103))));
  EXPECT_TRUE(std::isinf(round_to_float(pow2(300))));
  EXPECT_EQ(round_to_float(pow2(-300)), 0.0f);
}

// Every double is an exact rational, and the hardware's double->float conversion rounds to
// nearest-even: the two must agree bit for bit, subnormals and overflow included.
TEST(RoundToFloat, AgreesWithHardwareConversionOfDoubles) {
  std::mt19937_64 rng(1234);
  std::uniform_int_distribution<int> exponent(-160, 130);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  for (int n = 0; n < 200000; ++n) {
    double d = std::ldexp(mantissa(rng), exponent(rng));
    if (n % 2) d = -d;
    if (n % 7 == 0) {  // exact halfway cases between floats
      float f = float(d);
      d = (double(f) + double(std::nextafter(f, 2 * f))) / 2;
      if (d == 0 || !std::isfinite(d)) continue;  // mpq has no -0, no infinity
    }
    ASSERT_EQ(bits(round_to_float(mpq_class(d))), bits(float(d))) << std::hexfloat << d;
  }
}

LinearForm random_form(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-20, 20);
  auto r = [&]() -> mpq_class {
    return mpq_class(std::ldexp(u(rng), e(rng))) / mpq_class(std::ldexp(u(rng), e(rng)));
  };
  return {r(), r(), r()};
}

TEST(RatioEvaluator, FastPathGivesExactBits) {
  std::mt19937_64 rng(99);
  int fast_disagreements = 0;
  for (int t = 0; t < 300; ++t) {
    LinearForm n = random_form(rng), d = random_form(rng);
    d.c = abs(d.a) * 2000 + abs(d.b) * 2000 + 1;  // keeps D away from zero over the pixels
    const RatioEvaluator r(n, d);
    for (long py = 0; py < 1000; py += 37)
      for (long px = 0; px < 1000; px += 41)
        if (bits(r.at(px, py)) != bits(r.exact_at(px, py))) ++fast_disagreements;
  }
  EXPECT_EQ(fast_disagreements, 0);
}

TEST(RatioEvaluator, ExactQuotientNearATie) {
  // N/D = 1 + 2^-24 + 2^-80: just above a tie, must round up; the fast path cannot tell and
  // must defer to the exact one.
  const mpq_class v = 1 + pow2(-24) + pow2(-80);
  const RatioEvaluator r({0, 0, v}, {0, 0, 1});
  EXPECT_EQ(r.at(3, 5), std::nextafter(1.0f, 2.0f));
  const RatioEvaluator tie({0, 0, 1 + pow2(-24)}, {0, 0, 1});
  EXPECT_EQ(tie.at(3, 5), 1.0f);
}

// A random dyadic rational: 0 one time in eight, else a signed mantissa of up to 120 bits times
// 2^e for e in [-300, 300] (float32's range and beyond, so that sums align across it).
mpq_class random_dyadic(std::mt19937_64& rng) {
  if (rng() % 8 == 0) return 0;
  mpz_class m = 0;
  const int words = 1 + int(rng() % 2);
  for (int w = 0; w < words; ++w)
    m = (m << 60) + mpz_class(static_cast<unsigned long>(rng() >> 4));
  m >>= int(rng() % 100);
  if (m == 0) m = 1;
  if (rng() % 2) m = -m;
  return mpq_class(m) * pow2(int(rng() % 601) - 300);
}

TEST(Dyadic, OfAndRationalAreTheRationalItself) {
  std::mt19937_64 rng(7);
  for (int n = 0; n < 2000; ++n) {
    const mpq_class q = random_dyadic(rng);
    Dyadic d;
    ASSERT_TRUE(Dyadic::of(q, d)) << q;
    const mpq_class back = d.rational();
    EXPECT_EQ(back, q);
    // Canonical as mpq_class keeps it: no factor shared by numerator and denominator.
    EXPECT_EQ(gcd(back.get_num(), back.get_den()), 1);
    EXPECT_EQ(d.sign(), sgn(q));
  }
  Dyadic d;
  EXPECT_FALSE(Dyadic::of(mpq_class(1, 3), d));
  EXPECT_FALSE(Dyadic::of(mpq_class(5, 12), d));  // 12 = 4·3
  EXPECT_TRUE(Dyadic::of(mpq_class(5, 16), d));
  EXPECT_EQ(d.m, 5);
  EXPECT_EQ(d.e, -4);
  EXPECT_TRUE(Dyadic::of(mpq_class(-48), d));  // an integer: 2^0 below
  EXPECT_EQ(d.rational(), -48);
  EXPECT_EQ((Dyadic{mpz_class(12), -2}.rational()), 3);  // twos cancelled: 12/4 = 3/1
  EXPECT_EQ((Dyadic{mpz_class(0), -7}.rational()), 0);
  EXPECT_EQ((Dyadic{mpz_class(-3), 5}.rational()), -96);
}

TEST(Dyadic, SumsOfProductsAreTheRationalOnes) {
  std::mt19937_64 rng(11);
  for (int n = 0; n < 3000; ++n) {
    mpq_class a[3], b[3];
    Dyadic da[3], db[3];
    const int terms = 1 + int(n % 3);
    mpq_class expected = 0;
    for (int i = 0; i < terms; ++i) {
      a[i] = random_dyadic(rng), b[i] = random_dyadic(rng);
      // Now and then a sum that cancels exactly: the last term the negated first.
      if (i == 2 && n % 5 == 0) a[2] = -a[0], b[2] = b[0];
      ASSERT_TRUE(Dyadic::of(a[i], da[i]) && Dyadic::of(b[i], db[i]));
      expected += a[i] * b[i];
    }
    const Dyadic* left[3] = {&da[0], &da[1], &da[2]};
    const Dyadic* right[3] = {&db[0], &db[1], &db[2]};
    Dyadic out;
    sum_of_products(out, left, right, terms);
    EXPECT_EQ(out.rational(), expected);
    EXPECT_EQ(out.sign(), sgn(expected));
    Dyadic cross;
    cross_term(cross, da[0], db[0], da[1 % terms], db[1 % terms]);
    EXPECT_EQ(cross.rational(), mpq_class(a[0] * b[0] - a[1 % terms] * b[1 % terms]));
  }
}

TEST(TruncatedQuotient, IsTheCanonicalQuotientsDouble) {
  std::mt19937_64 rng(13);
  for (int n = 0; n < 3000; ++n) {
    // Numerators and positive denominators with common factors (3·5·7 and powers of two), so
    // that the pair divided is far from lowest terms; now and then one third, not dyadic.
    const mpz_class common = mpz_class(105) << int(rng() % 40);
    mpq_class a = random_dyadic(rng) * mpq_class(common), b = abs(random_dyadic(rng));
    if (b == 0) b = mpq_class(common);
    if (n % 3 == 0) a /= 3;
    const double want = mpq_class(a / b).get_d();
    EXPECT_EQ(truncated_quotient(a, b), want) << a << " / " << b;
  }
  EXPECT_EQ(truncated_quotient(mpq_class(1), mpq_class(3)), mpq_class(1, 3).get_d());
  EXPECT_EQ(truncated_quotient(mpq_class(-2), mpq_class(6)), mpq_class(-1, 3).get_d());
  EXPECT_EQ(truncated_quotient(mpq_class(0), mpq_class(5)), 0.0);
}

TEST(SignEvaluator, ExactNearZero) {
  // f = px - py·(1 + 2^-60): zero nowhere on the integer grid except (0,0), tiny elsewhere.
  const SignEvaluator s({1, -(1 + pow2(-60)), 0});
  EXPECT_EQ(s.sign(0, 0), 0);
  EXPECT_EQ(s.sign(7, 7), -1);  // 7 - 7 - 7·2^-60
  EXPECT_EQ(s.sign(-7, -7), 1);
  EXPECT_EQ(s.sign(8, 7), 1);
}

}  // namespace
}  // namespace glrc::ref
