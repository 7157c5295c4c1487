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
  const ref::Reference r = ref::render(c, kModel, 8);
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
  const ref::Reference r = ref::render(c, kModel, 8);
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

}  // namespace
}  // namespace glrc::compare
