// ComponentValues: every component's value at a pixel at once, the division shared by the
// components of one denominator. Each must be the very float the exact path gives.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "ref/interpolation.hpp"

namespace glrc::ref {
namespace {

mpq_class pow2(int e) {
  return e >= 0 ? mpq_class(mpz_class(1) << e) : mpq_class(mpz_class(1), mpz_class(1) << -e);
}

ComponentPlane ratio_plane(const LinearForm& n, const LinearForm& d) {
  ComponentPlane p;
  p.plane = {n, d};
  p.ratio = p.plane.evaluator();
  return p;
}

ComponentPlane flat_plane(float v) {
  ComponentPlane p;
  p.flat = true;
  p.flat_value = v;
  return p;
}

LinearForm random_form(std::mt19937_64& rng, int spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-spread, spread);
  auto r = [&]() -> mpq_class {
    return mpq_class(std::ldexp(u(rng), e(rng))) / mpq_class(std::ldexp(u(rng), e(rng)));
  };
  return {r(), r(), r()};
}

// Every component at every sampled pixel against RatioEvaluator::exact_at, bit for bit: one
// pixel at a time, and kRowBlock sampled pixels at a time (the block form; lanes from two rows
// where a row's samples run out).
int disagreements(const std::vector<ComponentPlane>& planes, long step) {
  const ComponentValues values(planes);
  std::vector<float> out(planes.size()), block(planes.size() * kRowBlock);
  double bx[kRowBlock], by[kRowBlock];
  int lanes = 0, wrong = 0;
  auto want = [&](size_t k, long px, long py) {
    return planes[k].flat ? planes[k].flat_value : planes[k].ratio.exact_at(px, py);
  };
  for (long py = 0; py < 1000; py += step)
    for (long px = 0; px < 1000; px += step + 4) {
      values.values(px, py, out.data());
      for (size_t k = 0; k < planes.size(); ++k)
        wrong += std::bit_cast<uint32_t>(out[k]) != std::bit_cast<uint32_t>(want(k, px, py));
      bx[lanes] = double(px), by[lanes] = double(py);
      if (++lanes < kRowBlock) continue;
      lanes = 0;
      values.values(bx, by, block.data());
      for (size_t k = 0; k < planes.size(); ++k)
        for (int j = 0; j < kRowBlock; ++j)
          wrong += std::bit_cast<uint32_t>(block[k * kRowBlock + size_t(j)]) !=
                   std::bit_cast<uint32_t>(want(k, long(bx[j]), long(by[j])));
    }
  return wrong;
}

TEST(ComponentValues, SharedDenominatorsGiveTheExactBits) {
  std::mt19937_64 rng(13);
  for (int t = 0; t < 60; ++t) {
    // Two denominators shared by three numerators each (smooth and noperspective components),
    // and a flat component between them.
    LinearForm d1 = random_form(rng, 20), d2 = random_form(rng, 20);
    d1.c = abs(d1.a) * 2000 + abs(d1.b) * 2000 + 1;
    d2.c = -(abs(d2.a) * 2000 + abs(d2.b) * 2000 + pow2(-30));  // negative, nearly zero at 0,0
    std::vector<ComponentPlane> planes;
    for (int k = 0; k < 3; ++k) {
      planes.push_back(ratio_plane(random_form(rng, 20), d1));
      planes.push_back(ratio_plane(random_form(rng, 20), d2));
    }
    planes.insert(planes.begin() + 2, flat_plane(-7.25f));
    ASSERT_EQ(disagreements(planes, 37), 0) << t;
  }
}

TEST(ComponentValues, ManyComponentsOfOneDenominator) {
  // 19 smooth components over one denominator: the block form takes them in groups (8, 8, 3).
  std::mt19937_64 rng(15);
  for (int t = 0; t < 10; ++t) {
    LinearForm d = random_form(rng, 20);
    d.c = abs(d.a) * 2000 + abs(d.b) * 2000 + 1;
    std::vector<ComponentPlane> planes;
    for (int k = 0; k < 19; ++k)
      planes.push_back(ratio_plane(random_form(rng, 20), d));
    ASSERT_EQ(disagreements(planes, 41), 0) << t;
  }
}

TEST(ComponentValues, DenominatorsCrossingZeroAndWideMagnitudes) {
  std::mt19937_64 rng(14);
  for (int t = 0; t < 60; ++t) {
    // D passes through zero inside the sampled pixels: near it only the exact path may answer
    // (a pixel with D = 0 is NaN on both paths).
    const LinearForm d = random_form(rng, 4);
    std::vector<ComponentPlane> planes;
    for (int k = 0; k < 4; ++k)
      planes.push_back(ratio_plane(random_form(rng, 60), d));
    ASSERT_EQ(disagreements(planes, 23), 0) << t;
  }
}

TEST(ComponentValues, NearATieTheExactPathDecides) {
  // N/D = 1 + 2^-24 + 2^-80 and 1 + 2^-24 exactly (a tie, to even: 1) over a shared D = 3:
  // the double quotient cannot tell them apart.
  const LinearForm d{0, 0, 3};
  const std::vector<ComponentPlane> planes = {
      ratio_plane({0, 0, 3 * (1 + pow2(-24) + pow2(-80))}, d),
      ratio_plane({0, 0, 3 * (1 + pow2(-24))}, d),
      ratio_plane({0, 0, 3 * (1 + pow2(-24) - pow2(-80))}, d)};
  std::vector<float> out(3);
  ComponentValues(planes).values(3, 5, out.data());
  EXPECT_EQ(out[0], std::nextafter(1.0f, 2.0f));
  EXPECT_EQ(out[1], 1.0f);
  EXPECT_EQ(out[2], 1.0f);
}

TEST(ComponentValues, NearATieTheExactPathDecidesInABlock) {
  // The same three ties in the block form, beside a component the fast path decides on its own
  // (N/D = 0.75 + x/1024): every lane of the block has an undecided component, and each of its
  // components must still be the exact float.
  const LinearForm d{0, 0, 3};
  const std::vector<ComponentPlane> planes = {
      ratio_plane({0, 0, 3 * (1 + pow2(-24) + pow2(-80))}, d),
      ratio_plane({mpq_class(3, 1024), 0, mpq_class(9, 4)}, d),
      ratio_plane({0, 0, 3 * (1 + pow2(-24))}, d),
      ratio_plane({0, 0, 3 * (1 + pow2(-24) - pow2(-80))}, d)};
  double px[kRowBlock], py[kRowBlock];
  for (int j = 0; j < kRowBlock; ++j)
    px[j] = 100 + j, py[j] = 7;
  std::vector<float> out(planes.size() * kRowBlock);
  ComponentValues(planes).values(px, py, out.data());
  for (int j = 0; j < kRowBlock; ++j) {
    EXPECT_EQ(out[0 * kRowBlock + size_t(j)], std::nextafter(1.0f, 2.0f)) << j;
    EXPECT_EQ(out[1 * kRowBlock + size_t(j)], 0.75f + float(100 + j) / 1024) << j;
    EXPECT_EQ(out[2 * kRowBlock + size_t(j)], 1.0f) << j;
    EXPECT_EQ(out[3 * kRowBlock + size_t(j)], 1.0f) << j;
  }
}

}  // namespace
}  // namespace glrc::ref

namespace glrc::ref {
namespace {

// sum(): the dyadic path (every form and weight dyadic) against the rational one, which a
// Barycentrics without its dyadic copy takes; and a non-dyadic weight (a snapped plane's v/w)
// falls back to the rational path with the same result.
TEST(Interpolation, DyadicSumsAreTheRationalSums) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-140, 140);
  auto dyadic = [&]() -> mpq_class {
    if (rng() % 10 == 0) return 0;
    return mpq_class(std::ldexp(u(rng), e(rng)));
  };
  for (int n = 0; n < 500; ++n) {
    Barycentrics b;
    for (auto& l : b.l)
      l = {dyadic() * dyadic() - dyadic() * dyadic(), dyadic() * dyadic(),
           (dyadic() + dyadic()) / 2};
    b.is_dyadic = true;
    for (int i = 0; i < 3; ++i)
      ASSERT_TRUE(Dyadic::of(b.l[i].a, b.dyadic[i][0]) && Dyadic::of(b.l[i].b, b.dyadic[i][1]) &&
                  Dyadic::of(b.l[i].c, b.dyadic[i][2]));
    Barycentrics rational = b;
    rational.is_dyadic = false;
    std::array<mpq_class, 3> alpha{dyadic(), dyadic(), n % 4 == 0 ? mpq_class(1) : dyadic()};
    if (n % 7 == 0) alpha[1] = mpq_class(3, 7) * alpha[1];  // not dyadic unless 0
    const LinearForm fast = sum(b, alpha), exact = sum(rational, alpha);
    EXPECT_EQ(fast.a, exact.a);
    EXPECT_EQ(fast.b, exact.b);
    EXPECT_EQ(fast.c, exact.c);
    // And both the rational Σ l_i·alpha_i itself.
    mpq_class want = 0;
    for (int i = 0; i < 3; ++i)
      want += b.l[i].c * alpha[i];
    EXPECT_EQ(fast.c, want);
  }
}

}  // namespace
}  // namespace glrc::ref
