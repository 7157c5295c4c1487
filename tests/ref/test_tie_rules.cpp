// The four tie-break rules: which pixel centres exactly on an edge a triangle takes, by the
// edge's inward normal, on the snapped and on the exact (no snapping) coverage path.
#include <gtest/gtest.h>

#include <vector>

#include "ref/reference.hpp"

namespace glrc::ref {
namespace {

constexpr int kSize = 32;

// Window position (x, y) on a 32x32 viewport at w = 1: clip x/16 - 1, exact for the quarter
// positions used here.
Vertex at(float x, float y) {
  return {{x / 16 - 1, y / 16 - 1, 0, 1}, {}};
}

Case one_triangle(Vertex a, Vertex b, Vertex c) {
  Case k;
  k.name = "tie_rules";
  k.fb_width = k.fb_height = kSize;
  k.viewport = {0, 0, kSize, kSize};
  k.vertices = {a, b, c};
  k.triangles = {{0, 1, 2}};
  return k;
}

bool covered(const Case& c, const Model& m, int x, int y) {
  return render(c, m).frame.primitive[size_t(y) * kSize + size_t(x)] == 0;
}

const TieBreak kRules[] = {TieBreak::bottom_left, TieBreak::top_left, TieBreak::bottom_right,
                           TieBreak::top_right};

bool left_rule(TieBreak t) {
  return t == TieBreak::bottom_left || t == TieBreak::top_left;
}
bool bottom_rule(TieBreak t) {
  return t == TieBreak::bottom_left || t == TieBreak::bottom_right;
}

// A triangle with a vertical edge on x = 10.5, through the pixel centres of column 10, lying
// to its right (`to_right`: a left edge, inward normal +x) or to its left; and one with a
// horizontal edge on y = 10.5 lying above it (`above`: a bottom edge) or below. Vertices are a
// quarter pixel off any centre.
Case vertical_edge(bool to_right) {
  const float s = to_right ? 1 : -1;
  return one_triangle(at(10.5f, 6.25f), at(10.5f, 18.75f), at(10.5f + 8 * s, 12.25f));
}
Case horizontal_edge(bool above) {
  const float s = above ? 1 : -1;
  return one_triangle(at(6.25f, 10.5f), at(18.75f, 10.5f), at(12.25f, 10.5f + 8 * s));
}

TEST(TieRules, AxisAlignedEdgesFollowTheRule) {
  for (int bits : {0, 4, 8}) {
    for (TieBreak rule : kRules) {
      Model m;
      m.subpixel_bits = bits, m.tie_break = rule;
      for (bool side : {true, false}) {
        const int s = side ? 1 : -1;
        const Case v = vertical_edge(side);
        EXPECT_EQ(covered(v, m, 10, 12), side ? left_rule(rule) : !left_rule(rule))
            << m.describe() << " triangle to the right: " << side;
        EXPECT_TRUE(covered(v, m, 10 + 2 * s, 12)) << m.describe();  // strictly inside
        const Case h = horizontal_edge(side);
        EXPECT_EQ(covered(h, m, 12, 10), side ? bottom_rule(rule) : !bottom_rule(rule))
            << m.describe() << " triangle above: " << side;
        EXPECT_TRUE(covered(h, m, 12, 10 + 2 * s)) << m.describe();
      }
    }
  }
}

// A slanted edge through pixel centres, direction (1, 2), from (8.25, 9) to (12.75, 18): it
// passes through the centres (8.5, 9.5), (9.5, 11.5), ..., (12.5, 17.5). Its inward normal
// points to -x when the triangle lies to its left, so the right rules take its centres, and to
// +x on the other side, so the left rules do. Horizontal rules play no part.
const Vertex kSlantA = at(8.25f, 9.0f), kSlantB = at(12.75f, 18.0f);
const Vertex kLeftOfSlant = at(3.25f, 16.25f), kRightOfSlant = at(18.25f, 8.25f);

TEST(TieRules, SlantedEdgesFollowLeftOrRight) {
  for (int bits : {0, 8}) {
    for (TieBreak rule : kRules) {
      Model m;
      m.subpixel_bits = bits, m.tie_break = rule;
      const Case left_of_edge = one_triangle(kSlantA, kSlantB, kLeftOfSlant);
      const Case right_of_edge = one_triangle(kSlantA, kSlantB, kRightOfSlant);
      EXPECT_EQ(covered(left_of_edge, m, 10, 13), !left_rule(rule)) << m.describe();
      EXPECT_EQ(covered(right_of_edge, m, 10, 13), left_rule(rule)) << m.describe();
    }
  }
}

// Two triangles sharing a slanted edge through centres: under every rule each centre on it is
// covered exactly once.
TEST(TieRules, SharedEdgeCoveredOnce) {
  Case c = one_triangle(kSlantA, kSlantB, kLeftOfSlant);
  c.vertices.push_back(kRightOfSlant);
  c.triangles.push_back({1, 0, 3});
  for (int bits : {0, 4, 8}) {
    for (TieBreak rule : kRules) {
      Model m;
      m.subpixel_bits = bits, m.tie_break = rule;
      const Frame f = render(c, m).frame;
      for (int x : {8, 10})
        EXPECT_EQ(f.fragments[size_t(x == 8 ? 9 : 13) * kSize + size_t(x)], 1)
            << m.describe() << " at " << x;
    }
  }
}

TEST(TieRules, DescribeNamesEveryRule) {
  Model m;
  m.tie_break = TieBreak::bottom_right;
  EXPECT_EQ(m.describe(), "subpixel_bits=8 planes=unsnapped tie=bottom-right");
  m.tie_break = TieBreak::top_right;
  EXPECT_EQ(m.describe(), "subpixel_bits=8 planes=unsnapped tie=top-right");
}

}  // namespace
}  // namespace glrc::ref
