// glClipControl in the reference (core/case.hpp: window_y_c, facing_reversed, near_distance).
// GL_UPPER_LEFT must draw exactly what GL_LOWER_LEFT draws with every y_c negated and the
// facing reversed: frame, allowances and candidates, bit for bit, for every suite case.
// GL_ZERO_TO_ONE must cut at z_c = 0, nowhere else, and map z_d to z_d·(f − n) + n.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "casefile/casefile.hpp"
#include "ref/reference.hpp"

namespace glrc::ref {
namespace {

// c drawn under GL_LOWER_LEFT as c is under GL_UPPER_LEFT: y_c negated, the other front face.
Case lower_left_twin(Case c) {
  c.clip_origin = ClipOrigin::lower_left;
  for (Vertex& v : c.vertices)
    v.clip[1] = -v.clip[1];
  c.front_face = c.front_face == FrontFace::ccw ? FrontFace::cw : FrontFace::ccw;
  return c;
}

TEST(ClipControl, UpperLeftIsLowerLeftWithYNegatedAndFacingReversedOnEverySuiteCase) {
  size_t n = 0, with_culling = 0;
  for (const auto& entry : std::filesystem::directory_iterator(GLRC_SOURCE_DIR "/cases")) {
    if (entry.path().extension() != ".json") continue;
    Case c = casefile::load(entry.path());
    if (c.clip_origin == ClipOrigin::upper_left) c = lower_left_twin(c);  // start lower-left
    Case upper = c;
    upper.clip_origin = ClipOrigin::upper_left;
    const Case twin = lower_left_twin(upper);
    const Model m;
    EXPECT_EQ(expectation_digest(render(upper, m)), expectation_digest(render(twin, m))) << c.name;
    with_culling += c.cull != CullFace::none;
    ++n;
  }
  EXPECT_GT(n, 100u);
  EXPECT_GT(with_culling, 3u);
}

Case near_case(ClipDepth mode) {
  Case c;
  c.name = "near";
  c.fb_width = c.fb_height = 32;
  c.viewport = {0, 0, 32, 32};
  c.depth_near = 0.25f, c.depth_far = 0.75f;
  c.clip_depth = mode;
  // A face-on triangle, w = 1, z_c from -0.5 (left) to 0.5 (right): z_n = 0 at x_w = 16.
  c.vertices = {{{-1, -1, -0.5f, 1}, {}},
                {{1, -1, 0.5f, 1}, {}},
                {{-1, 1, -0.5f, 1}, {}},
                {{1, 1, 0.5f, 1}, {}}};
  c.triangles = {{0, 1, 2}, {2, 1, 3}};
  return c;
}

TEST(ClipControl, ZeroToOneCutsAtZEqualsZeroAndMapsDepthWithoutHalving) {
  const Model m;
  const Expectation whole = render(near_case(ClipDepth::negative_one_to_one), m);
  const Expectation cut = render(near_case(ClipDepth::zero_to_one), m);
  for (int py = 0; py < 32; ++py)
    for (int px = 0; px < 32; ++px) {
      const size_t i = whole.frame.index(px, py);
      // Every centre is drawn under the default; z_n = (px + 0.5 - 16) / 16 there.
      ASSERT_NE(whole.frame.primitive[i], Frame::kNoPrimitive) << px << "," << py;
      const double z_n = (px + 0.5 - 16) / 16 * 0.5;
      EXPECT_FLOAT_EQ(whole.frame.depth[i], float(z_n * 0.25 + 0.5)) << px;
      if (px < 16) {
        EXPECT_EQ(cut.frame.primitive[i], Frame::kNoPrimitive) << px << "," << py;
      } else {
        ASSERT_NE(cut.frame.primitive[i], Frame::kNoPrimitive) << px << "," << py;
        EXPECT_FLOAT_EQ(cut.frame.depth[i], float(z_n * 0.5 + 0.25)) << px;
      }
    }
}

}  // namespace
}  // namespace glrc::ref
