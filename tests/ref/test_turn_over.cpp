// Whether a triangle may turn over or vanish is decided on the snapping grid (ref/freedom.hpp's
// orientation_may_change): a thin fan triangle whose rim vertices are a sub-pixel step apart
// keeps its orientation on every grid of 2^-4 pixels or finer, though a box of ±2^-4 around
// each vertex would let it turn over; one that some grid does turn over is found, as a brute
// force over grids, offsets and rules finds it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "ref/freedom.hpp"

namespace glrc::ref {
namespace {

using Triangle = std::array<std::array<double, 2>, 3>;

double area2(const Triangle& p) {
  return (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
}

// The first-order box bound the freedom used before: each vertex anywhere within ±h.
bool box_may_turn_over(const Triangle& p, double h) {
  double bound = 0;
  for (size_t j = 0; j < 3; ++j) {
    const auto& a = p[(j + 1) % 3];
    const auto& b = p[(j + 2) % 3];
    bound += h * (std::fabs(b[0] - a[0]) + std::fabs(b[1] - a[1]));
  }
  return !(std::fabs(area2(p)) > bound + 8 * h * h);
}

// One snapping function: grid 2^-bits, offset (ox, oy) in grid steps, rule 0 floor, 1 ceil,
// 2 nearest (ties up).
Triangle snapped(const Triangle& p, int bits, double ox, double oy, int rule) {
  const double step = std::ldexp(1.0, -bits);
  auto snap = [&](double x, double o) {
    const double t = x / step - o;
    const double k = rule == 0 ? std::floor(t) : rule == 1 ? std::ceil(t) : std::floor(t + 0.5);
    return (k + o) * step;
  };
  Triangle q{};
  for (size_t j = 0; j < 3; ++j)
    q[j] = {snap(p[j][0], ox), snap(p[j][1], oy)};
  return q;
}

// A triangle of a fan around (192.63, 473.59): rim vertices at radius r, angles a0 and a1.
Triangle fan_triangle(double r, double a0, double a1) {
  const double cx = 192.63, cy = 473.59;
  return {{{cx, cy},
           {cx + r * std::cos(a0), cy + r * std::sin(a0)},
           {cx + r * std::cos(a1), cy + r * std::sin(a1)}}};
}

TEST(TurnOver, AThinFanTriangleKeepsItsOrientationOnTheGrid) {
  // Rim vertices 0.12 pixels apart at radius 300 (a diagonal spoke): 2·area = 36 px², while a
  // box of ±1/16 pixel around each vertex moves it by up to 1/16·Σ(|E_x| + |E_y|) ~ 53.
  const double r = 300, a0 = 0.8, a1 = a0 + 0.12 / r;
  const Triangle p = fan_triangle(r, a0, a1);
  ASSERT_GT(area2(p), 30);
  const std::array<double, 3> rounding{1e-5, 1e-5, 1e-5};
  EXPECT_TRUE(box_may_turn_over(p, 0.0625 + 1e-5));
  EXPECT_FALSE(orientation_may_change(p, rounding, 4));
  EXPECT_FALSE(orientation_may_change(p, rounding, 8));
  // No snapping function turns it over (a sample of offsets and every rule, at 4 to 8 bits).
  for (int bits = 4; bits <= 8; ++bits)
    for (int rule = 0; rule < 3; ++rule)
      for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j)
          EXPECT_GT(area2(snapped(p, bits, i / 16.0, j / 16.0, rule)), 0);
}

TEST(TurnOver, ATriangleThatAGridCollapsesMayChange) {
  // Rim vertices 0.01 pixels apart: some offset puts both on one grid point along each axis.
  const Triangle p = fan_triangle(300, 0.8, 0.8 + 0.01 / 300);
  EXPECT_TRUE(orientation_may_change(p, {1e-5, 1e-5, 1e-5}, 4));
  // Float rounding alone can turn over a triangle thinner than its rounding.
  const Triangle q = fan_triangle(300, 0.8, 0.8 + 1e-7 / 300);
  EXPECT_TRUE(orientation_may_change(q, {1e-5, 1e-5, 1e-5}, 8));
}

TEST(TurnOver, EveryTurnOverABruteForceFindsIsFound) {
  // Random thin triangles: wherever some grid (4 to 6 bits), offset and rule gives a doubled
  // area of the other sign or 0, orientation_may_change must say so.
  std::mt19937_64 random(20261206);
  std::uniform_real_distribution<double> unit(0, 1);
  int flipping = 0, kept = 0;
  for (int n = 0; n < 400; ++n) {
    const double r = 2 + 200 * unit(random), a0 = 6.283 * unit(random);
    const double gap = (0.002 + 0.3 * unit(random)) / r;
    Triangle p = fan_triangle(r, a0, a0 + gap);
    // Move the apex off the rim's line a little, and the whole triangle anywhere.
    const double dx = 100 * unit(random), dy = 100 * unit(random);
    for (auto& v : p)
      v[0] += dx, v[1] += dy;
    bool flips = false;
    for (int bits = 4; bits <= 6 && !flips; ++bits)
      for (int rule = 0; rule < 3 && !flips; ++rule)
        for (int i = 0; i < 12 && !flips; ++i)
          for (int j = 0; j < 12 && !flips; ++j) {
            const double a = area2(snapped(p, bits, i / 12.0, j / 12.0, rule));
            flips = a == 0 || (a > 0) != (area2(p) > 0);
          }
    const bool may = orientation_may_change(p, {0, 0, 0}, 4);
    if (flips) {
      EXPECT_TRUE(may) << "triangle " << n;
    }
    flipping += flips;
    kept += !may;
  }
  // Both kinds occur: the test exercises the enumeration, not only the first-order bound.
  EXPECT_GT(flipping, 20);
  EXPECT_GT(kept, 20);
}

}  // namespace
}  // namespace glrc::ref
