// to_window (ref/viewport.hpp): the window position's x_h and y_h are computed from two exact
// double products and an exact sum where the magnitudes allow, in rationals otherwise; either
// way they must be the very rational of the specification's formula, x_c·(w/2) + w_c·(x + w/2);
// and w_c·z_w likewise, z_c·(f − n)/2 + w_c·(n + f)/2; under glClipControl, y_c negated
// (GL_UPPER_LEFT) and w_c·z_w = z_c·(f − n) + w_c·n (GL_ZERO_TO_ONE).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "ref/viewport.hpp"

namespace glrc::ref {
namespace {

mpq_class expected(float x_c, float w_c, int width, int x) {
  const mpq_class half = mpq_class(width) / 2;
  mpq_class q = mpq_class(double(x_c)) * half + mpq_class(double(w_c)) * (x + half);
  q.canonicalize();
  return q;
}

mpq_class expected_depth(float z_c, float w_c, float n, float f, ClipDepth mode) {
  const mpq_class qn{double(n)}, qf{double(f)};
  mpq_class q = mode == ClipDepth::zero_to_one
                    ? mpq_class(mpq_class(double(z_c)) * (qf - qn) + mpq_class(double(w_c)) * qn)
                    : mpq_class(mpq_class(double(z_c)) * (qf - qn) / 2 +
                                mpq_class(double(w_c)) * (qn + qf) / 2);
  q.canonicalize();
  return q;
}

void check(float x_c, float y_c, float w_c, const Viewport& vp, float z_c = 0.5f, float n = 0.0f,
           float f = 1.0f) {
  for (const ClipOrigin origin : {ClipOrigin::lower_left, ClipOrigin::upper_left})
    for (const ClipDepth mode : {ClipDepth::negative_one_to_one, ClipDepth::zero_to_one}) {
      Case c;
      c.viewport = vp;
      c.depth_near = n, c.depth_far = f;
      c.clip_origin = origin, c.clip_depth = mode;
      Vertex v;
      v.clip = {x_c, y_c, z_c, w_c};
      const WindowVertex w = to_window(v, c);
      const float y_d = origin == ClipOrigin::upper_left ? -y_c : y_c;
      EXPECT_EQ(w.x_h, expected(x_c, w_c, vp.width, vp.x)) << x_c << " " << w_c;
      EXPECT_EQ(w.y_h, expected(y_d, w_c, vp.height, vp.y)) << y_c << " " << w_c;
      // Canonical, as GMP's own arithmetic leaves it: equal rationals, equal parts.
      EXPECT_EQ(w.x_h.get_den(), expected(x_c, w_c, vp.width, vp.x).get_den());
      EXPECT_EQ(w.wz_w, expected_depth(z_c, w_c, n, f, mode))
          << z_c << " " << w_c << " " << n << " " << f << " " << int(mode);
    }
}

TEST(Viewport, WindowPositionsAreTheExactRationals) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> exponent(-149, 127), size(0, 1 << 14),
      offset(-(1 << 14), 1 << 14);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  auto random_float = [&] {
    // Every binade, subnormals and the largest included.
    return std::ldexp(unit(rng), exponent(rng));
  };
  for (int k = 0; k < 5000; ++k) {
    const Viewport vp{offset(rng), offset(rng), size(rng), size(rng)};
    check(random_float(), random_float(), random_float(), vp, random_float(), random_float(),
          random_float());
    // The common case: sums that cancel, a depth range in [0, 1].
    check(unit(rng), unit(rng), 1.0f + unit(rng), vp, unit(rng), std::fabs(unit(rng)),
          std::fabs(unit(rng)));
  }
  const float largest = std::numeric_limits<float>::max();
  const float tiny = std::numeric_limits<float>::denorm_min();
  for (const Viewport& vp : {Viewport{0, 0, 1024, 768}, Viewport{-7, 3, 1, 1}, Viewport{0, 0, 0, 0},
                             // Beyond 2^29: computed in rationals.
                             Viewport{1 << 30, -(1 << 30), 1 << 30, 1 << 30}})
    for (float a : {0.0f, -0.0f, 1.0f, -1.0f, largest, -largest, tiny, -tiny, 0.1f})
      for (float w : {1.0f, -1.0f, largest, tiny, 0.0f, 3e-20f})
        for (const auto& [n, f] : {std::pair{0.0f, 1.0f},
                                   {1.0f, 0.0f},
                                   {tiny, 1.0f},
                                   {largest, -largest},
                                   {0.25f, 0.75f},
                                   {1e-30f, 1.0f}})
          check(a, -a, w, vp, a, n, f);
}

}  // namespace
}  // namespace glrc::ref
