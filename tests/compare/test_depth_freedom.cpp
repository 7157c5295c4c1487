// The depth test's freedom, from both sides. Fragment counts are taken without the depth test,
// so a hidden depth contest leaves them decided (and a hidden crack still fails); a
// bitwise-identical copy of a triangle is decided as for equal depths under every function.
#include <gtest/gtest.h>

#include <string>

#include "compare/compare.hpp"
#include "ref/reference.hpp"

namespace glrc::compare {
namespace {

// Two different triangles in one exact sloped depth plane (z_c = 0.375 x_c - 0.625 y_c +
// 0.0625 w_c, perspective), overlapping, then a nearer triangle over the whole 8x8 frame:
// cases/depth_contest_hidden.json.
Case hidden_contest() {
  Case c;
  c.name = "hidden_contest";
  c.fb_width = c.fb_height = 8;
  c.viewport = {0, 0, 8, 8};
  c.depth_func = DepthFunc::less;
  c.varyings = {{"c", 1, Interpolation::smooth}};
  c.vertices = {{{-1.25f, -1.25f, 0.390625f, 1.25f}, {0}},
                {{1.875f, -2.5f, 2.421875f, 2.5f}, {0}},
                {{-0.75f, 0.65625f, -0.64453125f, 0.75f}, {0}},
                {{2, 2, -0.375f, 2}, {1}},
                {{-1.21875f, 0.75f, -0.83203125f, 1.5f}, {1}},
                {{0.4296875f, -0.5859375f, 0.56640625f, 0.625f}, {1}},
                {{-1, -1, -0.9f, 1}, {2}},
                {{3, -1, -0.9f, 1}, {2}},
                {{-1, 3, -0.9f, 1}, {2}}};
  c.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  return c;
}

TEST(FragmentCounts, CountEveryFragmentWhetherOrNotItPassesTheDepthTest) {
  const Case c = hidden_contest();
  const Expectation e = ref::render(c, Model{}, 8);
  size_t three = 0;
  for (size_t i = 0; i < e.frame.pixel_count(); ++i) {
    EXPECT_EQ(e.frame.primitive[i], 2);  // the near triangle covers everything
    EXPECT_GE(e.frame.fragments[i], 1);
    three += e.frame.fragments[i] == 3;
  }
  // Where both hidden triangles cover a centre, all three fragments are counted.
  EXPECT_GT(three, 5u);
  // The frame alone (digest's) counts the same.
  const Frame f = ref::render_frame(c, Model{});
  EXPECT_EQ(f.fragments, e.frame.fragments);
}

TEST(FragmentCounts, AHiddenContestLeavesTheCountDecided) {
  const Case c = hidden_contest();
  const Expectation e = ref::render(c, Model{}, 8);
  // GL's frame as the reference's: passes.
  EXPECT_EQ(compare(c, e, e.frame, Tolerance{}).status, Status::pass);
  // One fragment of a hidden triangle missing where no outer edge is near: a crack beneath the
  // near triangle, which fails although the depth test hides it.
  size_t dropped = e.frame.pixel_count();
  for (size_t i = 0; i < e.frame.pixel_count(); ++i)
    if (e.frame.fragments[i] >= 2 && !(e.edges[i] & (edge::snapping | edge::unstable))) {
      dropped = i;
      break;
    }
  ASSERT_LT(dropped, e.frame.pixel_count());
  Frame gl = e.frame;
  --gl.fragments[dropped];
  const CaseResult r = compare(c, e, gl, Tolerance{});
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(r.coverage.failures, 1u);
}

TEST(FragmentCounts, ACountMismatchFailsWhereTheDepthOrderIsFree) {
  // Two exactly coplanar triangles (one depth plane, no nearer one): the pixels both cover are
  // contested, and GL may keep either; the count there is 2 either way.
  Case c = hidden_contest();
  c.triangles.pop_back();
  const Expectation e = ref::render(c, Model{}, 8);
  size_t contested = e.frame.pixel_count();
  for (size_t i = 0; i < e.frame.pixel_count(); ++i)
    if ((e.edges[i] & edge::depth_order) && !(e.edges[i] & (edge::snapping | edge::unstable))) {
      contested = i;
      break;
    }
  ASSERT_LT(contested, e.frame.pixel_count());
  EXPECT_EQ(e.frame.fragments[contested], 2);
  const Candidate* other = nullptr;
  for (const Candidate& k : e.candidates)
    if (k.pixel == contested) other = &k;
  ASSERT_NE(other, nullptr);
  Frame gl = e.frame;
  gl.primitive[contested] = other->primitive;
  gl.depth[contested] = other->depth;
  gl.components[0][contested] = other->values[0];
  EXPECT_EQ(compare(c, e, gl, Tolerance{}).status, Status::pass);  // the other one kept
  gl.fragments[contested] = 1;  // ... but only one fragment rasterized there
  const CaseResult r = compare(c, e, gl, Tolerance{});
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(r.coverage.fill_rule, 1u);
}

// A perspective triangle, then a bitwise-identical copy (other values), under `func`:
// cases/invariance_copy_*.json without the rotated copy.
Case copies(DepthFunc func) {
  Case c;
  c.name = "copies";
  c.fb_width = c.fb_height = 32;
  c.viewport = {0, 0, 32, 32};
  c.depth_func = func;
  if (func == DepthFunc::greater || func == DepthFunc::gequal) c.depth_clear = 0.0f;
  c.varyings = {{"c", 1, Interpolation::smooth}};
  const std::array<std::array<float, 4>, 3> t{{{-1.5f, -1.25f, 0.40625f, 1.5f},
                                               {2.25f, -0.5f, 0.875f, 2.25f},
                                               {-0.375f, 0.9375f, -0.21875f, 0.75f}}};
  for (int copy = 0; copy < 2; ++copy)
    for (const auto& clip : t)
      c.vertices.push_back({clip, {float(copy)}});
  c.triangles = {{0, 1, 2}, {3, 4, 5}};
  return c;
}

TEST(Invariance, AnIdenticalCopyIsDecidedAsForEqualDepths) {
  for (DepthFunc func : {DepthFunc::less, DepthFunc::greater, DepthFunc::notequal,
                         DepthFunc::lequal, DepthFunc::gequal}) {
    const Case c = copies(func);
    const std::string name(name_of(func));
    const Expectation e = ref::render(c, Model{}, 8);
    const bool copy_wins = depth_test(func, 0.5f, 0.5f);
    size_t covered = 0;
    for (size_t i = 0; i < e.frame.pixel_count(); ++i) {
      if (e.frame.primitive[i] < 0) continue;
      ++covered;
      EXPECT_EQ(e.frame.primitive[i], copy_wins ? 1 : 0) << name << " at " << i;
      EXPECT_EQ(e.frame.fragments[i], 2) << name;
    }
    EXPECT_GT(covered, 100u) << name;
    // Neither is a candidate of the depth test against the other.
    EXPECT_TRUE(e.candidates.empty()) << name;
    EXPECT_EQ(compare(c, e, e.frame, Tolerance{}).status, Status::pass) << name;
    // A GL that lets the copy win where it must lose (or lose where it must win) fails at every
    // pixel away from the edges.
    Frame gl = e.frame;
    for (int32_t& p : gl.primitive)
      if (p >= 0) p = 1 - p;
    const CaseResult r = compare(c, e, gl, Tolerance{});
    EXPECT_EQ(r.status, Status::fail) << name;
    EXPECT_GT(r.coverage.fill_rule, 50u) << name;
  }
}

TEST(Invariance, ARotatedCopyIsAnotherPrimitiveAndMayWinEitherWay) {
  Case c = copies(DepthFunc::less);
  c.triangles[1] = {4, 5, 3};  // the same positions, rotated
  const Expectation e = ref::render(c, Model{}, 8);
  // Its depths equal the first one's exactly, but GL's may differ within the allowance.
  EXPECT_GT(e.candidates.size(), 100u);
  for (const Candidate& k : e.candidates)
    EXPECT_EQ(k.primitive, 1);
}

TEST(Invariance, IdenticalTrianglesAreFoundByTheirBits) {
  Case c = copies(DepthFunc::less);
  c.vertices.push_back({{-1.5f, -1.25f, 0.40625f, 1.5f}, {2}});
  c.vertices.push_back({{-0.0f, 0, 0, 1}, {2}});
  c.vertices.push_back({{0.0f, 0, 0, 1}, {2}});
  c.triangles.push_back({6, 1, 2});  // the first one's positions through other vertices
  c.triangles.push_back({0, 1, 7});  // -0 is not +0: another primitive
  c.triangles.push_back({0, 1, 8});
  c.triangles.push_back({1, 2, 0});  // rotated
  EXPECT_EQ(identical_triangles(c), (std::vector<int32_t>{0, 0, 0, 3, 4, 5}));
}

TEST(Invariance, DepthFunctionsCompareAsGlDoes) {
  EXPECT_TRUE(depth_test(DepthFunc::always, 1, 0));
  EXPECT_FALSE(depth_test(DepthFunc::never, 0, 1));
  EXPECT_TRUE(depth_test(DepthFunc::less, 0.25f, 0.5f));
  EXPECT_FALSE(depth_test(DepthFunc::less, 0.5f, 0.5f));
  EXPECT_TRUE(depth_test(DepthFunc::lequal, 0.5f, 0.5f));
  EXPECT_TRUE(depth_test(DepthFunc::greater, 0.75f, 0.5f));
  EXPECT_FALSE(depth_test(DepthFunc::greater, 0.5f, 0.5f));
  EXPECT_TRUE(depth_test(DepthFunc::gequal, 0.5f, 0.5f));
  EXPECT_TRUE(depth_test(DepthFunc::equal, 0.5f, 0.5f));
  EXPECT_FALSE(depth_test(DepthFunc::equal, 0.5f, 0.25f));
  EXPECT_TRUE(depth_test(DepthFunc::notequal, 0.5f, 0.25f));
  EXPECT_FALSE(depth_test(DepthFunc::notequal, 0.5f, 0.5f));
}

}  // namespace
}  // namespace glrc::compare
