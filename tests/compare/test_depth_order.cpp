// Where two triangles' depths at a pixel are within their depth allowances either may win the
// depth test: the winner's values are judged against its own triangle, and the pixel is not a
// coverage failure. Anywhere else, or with values not of the winner's triangle, it still fails.
#include <gtest/gtest.h>

#include <cmath>

#include "compare/compare.hpp"
#include "ref/reference.hpp"

namespace glrc::compare {
namespace {

// The two interpenetrating triangles whose depth planes cross, depth test less.
Case crossing() {
  Case c;
  c.name = "depth_cross";
  c.depth_func = DepthFunc::less;
  c.varyings = {{"c", 1, Interpolation::smooth}};
  const float z0 = 0.4999997f, z1 = 0.5000009f, z2 = 0.5000003f, z3 = 0.4999991f;
  c.vertices = {{{-1, -1, z0, 1}, {0}}, {{3, -1, z1, 1}, {1}}, {{-1, 3, z0, 1}, {2}},
                {{-1, -1, z2, 1}, {3}}, {{3, -1, z3, 1}, {4}}, {{-1, 3, z2, 1}, {5}}};
  c.triangles = {{0, 1, 2}, {3, 4, 5}};
  return c;
}

// The GL frame an implementation produces when every contested pixel goes to the candidate.
Frame other_winner(const Expectation& e) {
  Frame gl = e.frame;
  for (const Candidate& k : e.candidates) {
    gl.primitive[k.pixel] = k.primitive;
    gl.depth[k.pixel] = k.depth;
    for (size_t j = 0; j < k.values.size(); ++j)
      gl.components[j][k.pixel] = k.values[j];
  }
  return gl;
}

TEST(DepthOrder, EitherTriangleMayWinWhereTheirDepthsAreWithinTheAllowance) {
  const Case c = crossing();
  const Expectation e = ref::render(c, Model{}, 8);
  ASSERT_GT(e.candidates.size(), 100u);
  size_t marked = 0;
  for (uint8_t bits : e.edges)
    marked += (bits & edge::depth_order) != 0;
  EXPECT_GE(marked, e.candidates.size());
  const CaseResult r = compare(c, e, other_winner(e), Tolerance{});
  EXPECT_EQ(r.status, Status::pass) << r.message;
  EXPECT_EQ(r.coverage.failures, 0u);
  EXPECT_EQ(r.coverage.other_primitive, 0u);  // compared against the candidate instead
}

TEST(DepthOrder, TheWinnersValuesMustBeItsOwn) {
  const Case c = crossing();
  const Expectation e = ref::render(c, Model{}, 8);
  ASSERT_FALSE(e.candidates.empty());
  Frame gl = other_winner(e);
  // The candidate's primitive, with the reference winner's value: a mixed-up fragment.
  const Candidate& k = e.candidates.front();
  gl.components[0][k.pixel] = e.frame.components[0][k.pixel];
  const CaseResult r = compare(c, e, gl, Tolerance{});
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(r.channels[1].over_tolerance, 1u);
}

TEST(DepthOrder, AWinnerFarBehindIsStillAFailure) {
  Case c = crossing();
  // The second triangle well behind the first: no pixel is contested.
  for (size_t v = 3; v < 6; ++v)
    c.vertices[v].clip[2] = 0.9f;
  const Expectation e = ref::render(c, Model{}, 8);
  EXPECT_TRUE(e.candidates.empty());
  Frame gl = e.frame;
  const size_t i = gl.index(10, 10);
  ASSERT_EQ(gl.primitive[i], 0);
  gl.primitive[i] = 1;
  const CaseResult r = compare(c, e, gl, Tolerance{});
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(r.coverage.fill_rule, 1u);
}

TEST(SpecifiedRange, AFailureBeyond2To32IsReportedAsOutsideTheRange) {
  Case c = crossing();
  c.depth_func = DepthFunc::always;
  c.vertices[1].values[0] = 1e30f;
  EXPECT_NE(outside_specified_range(c)->find("vertices[1].c.x = 1e+30"), std::string::npos);
  const Expectation e = ref::render(c, Model{}, 8);
  Frame gl = e.frame;
  // A hole in the middle of the triangle: a fill-rule error anywhere else.
  const size_t i = gl.index(5, 5);
  ASSERT_GE(gl.primitive[i], 0);
  gl.primitive[i] = Frame::kNoPrimitive;
  gl.fragments[i] = 0;
  const CaseResult r = compare(c, e, gl, Tolerance{});
  EXPECT_EQ(r.status, Status::skip);
  EXPECT_EQ(r.message.rfind("outside GL's specified range: vertices[1].c.x", 0), 0u) << r.message;
  // An unused vertex or a flat value beyond the range is never computed on: still a failure.
  Case unused = c;
  unused.vertices[1].values[0] = 1;
  unused.vertices.push_back({{1e10f, 0, 0, 1}, {0}});
  EXPECT_FALSE(outside_specified_range(unused));
  EXPECT_EQ(compare(unused, e, gl, Tolerance{}).status, Status::fail);
  Case flat = c;
  flat.vertices[1].values[0] = 1;
  flat.varyings.push_back({"f", 1, Interpolation::flat});
  for (Vertex& v : flat.vertices)
    v.values.push_back(5e9f);
  EXPECT_FALSE(outside_specified_range(flat));
  Case denormal = unused;
  denormal.vertices[0].clip = {0x1p-149f, 0x1p-149f, 0, 0x1p-149f};
  EXPECT_NE(
      outside_specified_range(denormal)->find("vertices[0].clip[0] = 1.4013e-45 is a denormal"),
      std::string::npos);
  // Inside the range the same difference fails.
  c.vertices[1].values[0] = 0x1p32f;
  EXPECT_FALSE(outside_specified_range(c));
}

}  // namespace
}  // namespace glrc::compare
