// A fractional viewport judged from both sides (docs/allowance.md, "The viewport's precision"):
// GL interprets glViewportIndexedf's bounds to GL_VIEWPORT_SUBPIXEL_BITS, taken at 0, so an
// implementation that draws a fractional viewport as the whole-pixel one its bounds round to
// passes; one that draws it three pixels away fails, and so does a whole-number viewport drawn
// one pixel away (there the freedom does not apply).
#include <gtest/gtest.h>

#include <cmath>

#include "compare/compare.hpp"
#include "ref/freedom.hpp"
#include "ref/reference.hpp"

namespace glrc::compare {
namespace {

Case crossing(const Viewport& vp) {
  Case c;
  c.name = "viewport_precision";
  c.fb_width = c.fb_height = 64;
  c.viewport = vp;
  c.varyings = {{"uv", 2, Interpolation::smooth}};
  c.vertices = {{{-1.3f, -1.2f, 0.1f, 1}, {0, 0}},
                {{2.4f, -1.6f, 0.3f, 2}, {1, 0}},
                {{-0.3f, 1.5f, -0.2f, 1.25f}, {0, 1}},
                {{1.4f, 1.1f, 0.5f, 1}, {1, 1}}};
  c.triangles = {{0, 1, 2}, {2, 1, 3}};
  return c;
}

// What GL draws when it takes viewport `drawn` for the case's: the exact rendering of that one.
Status judged(const Case& c, const Viewport& drawn) {
  Case gl = c;
  gl.viewport = drawn;
  const Expectation e = ref::render(c, Model{}, 8);
  return compare(c, e, ref::render(gl, Model{}, 8).frame, Tolerance{}).status;
}

TEST(ViewportPrecision, AFractionalViewportMayBeDrawnAsTheWholePixelsItRoundsTo) {
  const Viewport fractional{3.25f, 7.5f, 50.75f, 40.5f};
  const Case c = crossing(fractional);
  EXPECT_GT(ref::viewport_shift(fractional, 30, 30), 1.0);
  EXPECT_EQ(judged(c, fractional), Status::pass);
  // Each bound rounded down, to the nearest, up: every one is GL_VIEWPORT_SUBPIXEL_BITS 0's.
  EXPECT_EQ(judged(c, {3.0f, 7.0f, 50.0f, 40.0f}), Status::pass);
  EXPECT_EQ(judged(c, {3.0f, 8.0f, 51.0f, 40.0f}), Status::pass);
  EXPECT_EQ(judged(c, {4.0f, 8.0f, 51.0f, 41.0f}), Status::pass);
  // Three pixels away is beyond it.
  EXPECT_EQ(judged(c, {6.25f, 7.5f, 50.75f, 40.5f}), Status::fail);
  EXPECT_EQ(judged(c, {3.25f, 7.5f, 53.75f, 40.5f}), Status::fail);
}

TEST(ViewportPrecision, AWholeNumberViewportHasNoSuchFreedom) {
  const Viewport whole{3, 8, 51, 40};
  const Case c = crossing(whole);
  EXPECT_EQ(ref::viewport_shift(whole, 30, 30), 0.0);
  EXPECT_EQ(judged(c, whole), Status::pass);
  EXPECT_EQ(judged(c, {4, 8, 51, 40}), Status::fail);
  EXPECT_EQ(judged(c, {3, 8, 52, 40}), Status::fail);
}

}  // namespace
}  // namespace glrc::compare
