// A pixel the snapped triangle covers but the triangle its plane comes from does not, beyond
// that plane's vanishing line: the perspective-correct interpolation there is 0/0, and no value
// is wrong. Such a pixel is not judged; a NaN from GL there makes the case outside what GL
// specifies (skip), never a pass; anywhere else NaN still fails.
#include <gtest/gtest.h>

#include <cmath>

#include "compare/compare.hpp"
#include "ref/reference.hpp"

namespace glrc::compare {
namespace {

// Window coordinates (24 x 24 viewport): v0 (22.5, 12.5) and v1 (12.5, 22.5) at w = 24, and
// v2 (12.5 + e, 12.5 + e), e = 5/8192, at w = 24 * 8192. Snapped to 1/256 pixel, v2 lands on
// the centre of pixel (12, 12), the corner of a right triangle whose bottom and left edges
// include it. On the unsnapped triangle that centre has lambda_2 = 10 / (10 - 2e) = 8192/8191,
// lambda_0 + lambda_1 = -1/8191, so sum lambda_i / w_i = (-1/8191 + 1/8191) / 24 = 0: the
// smooth value's denominator vanishes exactly there.
Case vanishing_line() {
  Case c;
  c.name = "vanishing_line";
  c.fb_width = 24, c.fb_height = 24;
  c.viewport = {0, 0, 24, 24};
  c.varyings = {{"v", 1, Interpolation::smooth}};
  c.vertices = {{{21, 1, 0, 24}, {1}}, {{1, 21, 0, 24}, {2}}, {{8202, 8202, 0, 196608}, {4}}};
  c.triangles = {{0, 1, 2}};
  return c;
}

const Model kModel{8, Planes::unsnapped, TieBreak::bottom_left};

TEST(Undetermined, TheReferenceGivesNaNBeyondTheVanishingLineWithAnUnboundedAllowance) {
  const Case c = vanishing_line();
  const Expectation r = ref::render(c, kModel, 8);
  const size_t corner = r.frame.index(12, 12);
  ASSERT_EQ(r.frame.primitive[corner], 0);
  EXPECT_TRUE(std::isnan(r.frame.components[0][corner]));
  EXPECT_EQ(r.allowed.components[0][corner], INFINITY);
  // Its neighbours inside the triangle are ordinary numbers.
  EXPECT_TRUE(std::isfinite(r.frame.components[0][r.frame.index(13, 12)]));
  EXPECT_TRUE(std::isfinite(r.frame.components[0][r.frame.index(12, 13)]));
}

TEST(Undetermined, APixelWithoutADeterminedValueIsNotJudgedAndNaNThereIsNoPass) {
  const Case c = vanishing_line();
  const Expectation r = ref::render(c, kModel, 8);
  const size_t corner = r.frame.index(12, 12);
  Tolerance t;
  t.subpixel_bits = 8;

  // The reference against itself: NaN at the corner, nothing else wrong: outside what GL
  // specifies, not a failure and not a pass.
  const CaseResult self = compare(c, r, r.frame, t);
  EXPECT_EQ(self.status, Status::skip) << self.message;
  EXPECT_NE(self.message.find("v.x at 12,12"), std::string::npos) << self.message;
  EXPECT_EQ(self.channels[1].undetermined, 1u);
  EXPECT_EQ(self.channels[1].non_finite, 0u);
  EXPECT_EQ(self.channels[1].compared + 1, self.coverage.both);
  // The largest allowance applied is that of a judged pixel, not the corner's +inf.
  EXPECT_TRUE(std::isfinite(self.channels[1].tolerance_ulps));
  EXPECT_GT(self.channels[1].tolerance_ulps, 0);

  // An implementation anchoring its planes at the snapped vertices draws v2's value there.
  Frame snapped = r.frame;
  snapped.components[0][corner] = 4.0f;
  const CaseResult finite = compare(c, r, snapped, t);
  EXPECT_EQ(finite.status, Status::pass) << finite.message;
  EXPECT_EQ(finite.channels[1].undetermined, 1u);

  // A NaN anywhere the value is determined still fails, the corner's notwithstanding.
  Frame wrong = r.frame;
  wrong.components[0][r.frame.index(13, 13)] = NAN;
  const CaseResult fails = compare(c, r, wrong, t);
  EXPECT_EQ(fails.status, Status::fail);
  EXPECT_EQ(fails.channels[1].non_finite, 1u);

  // With fixed thresholds the corner is not judged either; exact mode asks for its bits, and
  // GL's NaN never passes there.
  Tolerance ulps = t;
  ulps.mode = ToleranceMode::ulps;
  EXPECT_EQ(compare(c, r, snapped, ulps).status, Status::pass);
  Tolerance exact = t;
  exact.mode = ToleranceMode::exact;
  EXPECT_EQ(compare(c, r, r.frame, exact).status, Status::fail);
}

// The edge v1-v2 lies within float32 rounding of the planes x = w_c, y = -w_c and z = -w_c and
// passes within 1e-6 of the eye (v1 is -0.659 times v2 but for an ulp or two): clipping cuts
// it into a vertex at w_c = 5.2e-7 whose own rounding error is 1.65 times that, so the w_c an
// implementation computes may be 0 (llvmpipe's is, found by glrefcheck fuzz on Mesa 22.3.6: NaN
// for a smooth value of 0 at every vertex, and depth 1 where the exact depth is 0.25). Found by
// `glrefcheck fuzz --generator clip --replay 2026:34121`, shrunk.
Case near_the_eye() {
  Case c;
  c.name = "near_the_eye";
  c.fb_width = 53, c.fb_height = 1;
  c.viewport = {0, 0, 53, 1};
  c.varyings = {{"v", 1, Interpolation::smooth}};
  c.vertices = {{{-1.5f, 1, 0, 1}, {0}},
                {{-7.216813f, 7.216813f, 7.216813f, -7.216813f}, {0}},
                {{10.947852f, -10.947854f, -10.947851f, 10.947851f}, {0}}};
  c.triangles = {{0, 1, 2}};
  return c;
}

TEST(Undetermined, ATriangleWithinRoundingOfTheEyeHasNoBoundOnItsValues) {
  const Case c = near_the_eye();
  const Expectation r = ref::render(c, kModel, 8);
  const size_t at = r.frame.index(1, 0);
  ASSERT_EQ(r.frame.primitive[at], 0);
  EXPECT_EQ(r.frame.components[0][at], 0.0f);  // the value itself is determined: 0
  EXPECT_EQ(r.allowed.components[0][at], INFINITY);
  EXPECT_EQ(r.allowed.depth[at], INFINITY);
  for (size_t i = 0; i < r.frame.pixel_count(); ++i)
    EXPECT_TRUE(r.edges[i] & edge::unstable) << i;
  Tolerance t;
  t.subpixel_bits = 8;

  // Any number passes; NaN (0 times an infinite 1/w_c) is outside what GL specifies.
  Frame drawn = r.frame;
  drawn.components[0][at] = 1e30f;
  drawn.depth[at] = 1;
  EXPECT_EQ(compare(c, r, drawn, t).status, Status::pass);
  drawn.components[0][at] = NAN;
  const CaseResult nan = compare(c, r, drawn, t);
  EXPECT_EQ(nan.status, Status::skip) << nan.message;
  EXPECT_NE(nan.message.find("within rounding of the eye"), std::string::npos) << nan.message;
  EXPECT_EQ(nan.channels[1].undetermined, 1u);
}

}  // namespace
}  // namespace glrc::compare
