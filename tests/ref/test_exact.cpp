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
