// Fragment choices and traces (ref/fragment_choices.cpp, core/fragment_trace.hpp), from both
// sides: every conforming rasterization (other subpixel bits, other tie rules, no snapping at
// all) gives a trace the choices admit at every pixel, and a double hit on a shared edge beside
// another triangle's band, which the count alone cannot tell from that triangle's fragment, is
// not admitted.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>

#include "core/fragment_trace.hpp"
#include "ref/coverage.hpp"
#include "ref/mesh.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {
namespace {

Case base_case(int w, int h) {
  Case c;
  c.name = "test";
  c.fb_width = w, c.fb_height = h;
  c.viewport = {0, 0, w, h};
  return c;
}

// Vertex at window position (x, y) of a w×h viewport at the origin, clip w_c = w_c.
Vertex at(const Case& c, double x, double y, float w_c = 1, float z = 0) {
  const float xc = float((2 * x / c.viewport.width - 1) * w_c);
  const float yc = float((2 * y / c.viewport.height - 1) * w_c);
  return {{xc, yc, z * w_c, w_c}, {}};
}

uint32_t add(Case& c, const Vertex& v) {
  c.vertices.push_back(v);
  return uint32_t(c.vertices.size() - 1);
}

bool contains(const std::vector<FragmentTrace>& list, const FragmentTrace& t) {
  return std::find(list.begin(), list.end(), t) != list.end();
}

// The trace model m's rasterization gives at pixel (px, py): every triangle it draws there.
FragmentTrace trace_of(const Case& c, const Model& m, int px, int py) {
  FragmentTrace out;
  for (int p = 0; p < int(c.triangles.size()); ++p) {
    const TriangleSetup t = setup_triangle(c, m, p);
    if (t.drawn && CoverageTest(t, m, false).covers(px, py)) out += fragment_trace(p);
  }
  return out;
}

std::vector<size_t> every_pixel(const Case& c) {
  std::vector<size_t> out(size_t(c.fb_width) * size_t(c.fb_height));
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = i;
  return out;
}

// Triangles 0 and 1 share the edge from (4, 2) to (13.01, 13) (the same two vertices); the
// centre (8.5, 7.5) lies 0.004 px from it. Triangle 2's left edge passes
// 0.01 px right of the centre: within its snapping band at 4 subpixel bits, so that the count
// there is 1 or 2.
Case shared_edge_beside_a_band() {
  Case c = base_case(16, 16);
  const uint32_t a = add(c, at(c, 4, 2)), b = add(c, at(c, 13.01, 13));
  const uint32_t left = add(c, at(c, 1, 14)), right = add(c, at(c, 15, 1));
  c.triangles.push_back({a, b, left});
  c.triangles.push_back({b, a, right});
  const uint32_t p = add(c, at(c, 8.51, 6)), q = add(c, at(c, 11, 7.5)), r = add(c, at(c, 8.51, 9));
  c.triangles.push_back({p, q, r});
  return c;
}

TEST(FragmentChoices, ADoubleHitBesideAnotherTrianglesBandIsNotAdmitted) {
  const Case c = shared_edge_beside_a_band();
  const Model m;  // 8 subpixel bits, bottom-left
  const size_t pixel = size_t(7) * 16 + 8;
  const std::vector<FragmentChoices> choices = fragment_choices(c, m, 4, {pixel});
  ASSERT_EQ(choices.size(), 1u);
  const std::optional<std::vector<FragmentTrace>> admitted_traces = admitted(choices[0]);
  ASSERT_TRUE(admitted_traces.has_value());
  const FragmentTrace t0 = fragment_trace(0), t1 = fragment_trace(1), t2 = fragment_trace(2);
  auto sum = [](std::initializer_list<FragmentTrace> list) {
    FragmentTrace out;
    for (const FragmentTrace& t : list)
      out += t;
    return out;
  };
  // One of the two fan triangles, with or without the third.
  EXPECT_TRUE(contains(*admitted_traces, sum({t0})));
  EXPECT_TRUE(contains(*admitted_traces, sum({t1})));
  EXPECT_TRUE(contains(*admitted_traces, sum({t0, t2})));
  EXPECT_TRUE(contains(*admitted_traces, sum({t1, t2})));
  // Never both (a double hit), never neither (a gap), whatever the third does.
  EXPECT_FALSE(contains(*admitted_traces, sum({t0, t1})));
  EXPECT_FALSE(contains(*admitted_traces, sum({t0, t1, t2})));
  EXPECT_FALSE(contains(*admitted_traces, sum({})));
  EXPECT_FALSE(contains(*admitted_traces, sum({t2})));
  EXPECT_EQ(admitted_traces->size(), 4u);
  // The reference's own rasterization is one of them.
  EXPECT_TRUE(contains(*admitted_traces, trace_of(c, m, 8, 7)));
  // The count alone: 2 is legal here (a fan triangle and the third), so only the trace tells.
  EXPECT_TRUE(contains(*admitted_traces, sum({t1, t2})));
  EXPECT_EQ(sum({t1, t2}).count, sum({t0, t1}).count);
}

TEST(FragmentChoices, ATriangleThatMayTurnOverIsFreeAndTheRestStayDecided) {
  // Triangle 2 is a sliver 1e-4 px thick across the shared edge: it may turn over, so it may or
  // may not cover the centre; the two fan triangles still give it one fragment.
  Case c = shared_edge_beside_a_band();
  c.triangles.pop_back();
  const uint32_t p = add(c, at(c, 2, 7.5)), q = add(c, at(c, 14, 7.5001)),
                 r = add(c, at(c, 8, 7.50005));
  c.triangles.push_back({p, q, r});
  const std::vector<FragmentChoices> choices = fragment_choices(c, Model{}, 4, {7 * 16 + 8});
  const auto traces = admitted(choices[0]);
  ASSERT_TRUE(traces.has_value());
  FragmentTrace both = fragment_trace(0);
  both += fragment_trace(1);
  EXPECT_FALSE(contains(*traces, both));
  FragmentTrace with_sliver = fragment_trace(1);
  with_sliver += fragment_trace(2);
  EXPECT_TRUE(contains(*traces, with_sliver));
  EXPECT_TRUE(contains(*traces, fragment_trace(0)));
}

TEST(FragmentChoices, AClippedPolygonMayCoverTwiceInItsBands) {
  // A thin triangle the y = -w plane cuts (found by `fuzz --generator sizes --seed 91` on
  // llvmpipe): its clipped polygon's fan folds within the clipper's rounding, and llvmpipe
  // covers the centre of (6, 21), in the bands of two of its edges, twice. A piece of the fan
  // may turn over there (PositionFreedom::turning_pieces): any count of any primitive.
  Case c = base_case(55, 61);
  c.vertices = {{{-0.99731445f, 0.18984985f, 0, 1}, {}},
                {{-0.20507812f, -1.4545898f, 0, 1}, {}},
                {{-0.4701004f, -0.90405273f, 0, 1}, {}}};
  c.triangles = {{0, 1, 2}};
  const std::vector<FragmentChoices> choices = fragment_choices(c, Model{}, 8, {21 * 55 + 6});
  EXPECT_TRUE(choices[0].anything);
  EXPECT_FALSE(admitted(choices[0]).has_value());
  // The same triangle moved up into the viewport, clipped by no plane: nothing there is left
  // free.
  for (auto& v : c.vertices)
    v.clip[1] += 0.5f;
  const std::vector<FragmentChoices> unclipped = fragment_choices(c, Model{}, 8, {21 * 55 + 6});
  EXPECT_FALSE(unclipped[0].anything);
}

TEST(FragmentChoices, ReachingTheEyeDecidesNothing) {
  // A triangle whose plane holds the eye (vertex 2 is -1/2 times vertex 0 in x, y and w):
  // every centre of the viewport may be covered any number of times.
  Case c = base_case(8, 8);
  c.vertices = {{{-0.5f, -0.25f, 0.0f, 1}, {}},
                {{0.25f, 0.5f, 0.0f, 2}, {}},
                {{0.25f, 0.125f, 0.0f, -0.5f}, {}}};
  c.triangles = {{0, 1, 2}};
  const std::vector<FragmentChoices> choices = fragment_choices(c, Model{}, 8, {0, 27, 63});
  for (const FragmentChoices& f : choices)
    EXPECT_FALSE(admitted(f).has_value());
}

// A mesh on a jittered grid (every inner edge shared, diagonals either way), and random
// triangles over it, some of them thin: every model an implementation may be (4 to 8 subpixel
// bits, each tie rule, or no snapping at all) rasterizes a trace the choices for 4 bits admit,
// at every pixel.
TEST(FragmentChoices, EveryConformingRasterizationIsAdmitted) {
  std::mt19937 rng(44);
  std::uniform_real_distribution<double> jitter(-0.45, 0.45), anywhere(1, 31), w(0.5, 2);
  size_t traced = 0, decided_pixels = 0;
  for (int scene = 0; scene < 6; ++scene) {
    Case c = base_case(32, 32);
    constexpr int kGrid = 5;
    std::vector<uint32_t> grid;
    for (int j = 0; j < kGrid; ++j)
      for (int i = 0; i < kGrid; ++i)
        grid.push_back(
            add(c, at(c, 2 + 7 * i + jitter(rng), 2 + 7 * j + jitter(rng), float(w(rng)))));
    for (int j = 0; j + 1 < kGrid; ++j)
      for (int i = 0; i + 1 < kGrid; ++i) {
        const uint32_t a = grid[size_t(j * kGrid + i)], b = grid[size_t(j * kGrid + i + 1)];
        const uint32_t d = grid[size_t((j + 1) * kGrid + i)],
                       e = grid[size_t((j + 1) * kGrid + i + 1)];
        if ((i + j + scene) % 2) {
          c.triangles.push_back({a, b, e});
          c.triangles.push_back({a, e, d});
        } else {
          c.triangles.push_back({a, b, d});
          c.triangles.push_back({b, e, d});
        }
      }
    for (int k = 0; k < 6; ++k) {
      const double x = anywhere(rng), y = anywhere(rng);
      const bool thin = k % 2 == 0;
      const uint32_t p = add(c, at(c, x, y, float(w(rng))));
      const uint32_t q = add(c, at(c, anywhere(rng), anywhere(rng), float(w(rng))));
      const uint32_t r = thin ? add(c, at(c, x + 0.3 * jitter(rng), y + 0.3 * jitter(rng)))
                              : add(c, at(c, anywhere(rng), anywhere(rng), float(w(rng))));
      c.triangles.push_back({p, q, r});
    }
    const std::vector<size_t> pixels = every_pixel(c);
    const std::vector<FragmentChoices> choices = fragment_choices(c, Model{}, 4, pixels, 2);
    // The same from render()'s own set-up of the triangles, as a check reuses it, at pixels of
    // one corner (so that the triangles kept are not all of them).
    std::shared_ptr<const CaseSetup> setup;
    render(c, Model{}, 4, 2, Expectation{}, setup);
    ASSERT_TRUE(setup);
    std::vector<size_t> corner;
    for (size_t i : pixels)
      if (i % 32 < 10 && i / 32 < 10) corner.push_back(i);
    const std::vector<FragmentChoices> reused = fragment_choices(c, Model{}, 4, corner, 2, *setup);
    ASSERT_EQ(reused.size(), corner.size());
    for (size_t k = 0; k < corner.size(); ++k)
      EXPECT_EQ(admitted(reused[k]), admitted(choices[corner[k]]))
          << "scene " << scene << ", pixel " << corner[k];
    for (const Model& m : {Model{8, Planes::unsnapped, TieBreak::bottom_left},
                           Model{4, Planes::unsnapped, TieBreak::top_left},
                           Model{6, Planes::unsnapped, TieBreak::top_right},
                           Model{0, Planes::unsnapped, TieBreak::bottom_right}}) {
      for (size_t i = 0; i < pixels.size(); ++i) {
        const auto traces = admitted(choices[i]);
        if (!traces) continue;
        ++traced;
        decided_pixels += traces->size() == 1;
        const int px = int(i % 32), py = int(i / 32);
        EXPECT_TRUE(contains(*traces, trace_of(c, m, px, py)))
            << "scene " << scene << ", " << m.describe() << ", pixel (" << px << ", " << py << ")";
      }
    }
  }
  // Nearly every pixel is traced, most of them decided.
  EXPECT_GT(traced, size_t(6 * 4 * 1024 * 9 / 10));
  EXPECT_GT(decided_pixels, traced / 2);
}

TEST(FragmentTrace, AdmittedListsEveryChoiceOnceAndGivesUpBeyondItsBound) {
  FragmentChoices f;
  f.sure = fragment_trace(7);
  f.edges = 1;
  f.members = {{1, false, {{0, true}}}, {2, false, {{0, false}}}, {3, true, {}}};
  const auto traces = admitted(f);
  ASSERT_TRUE(traces.has_value());
  // {7, 1}, {7, 2}, {7, 1, 3}, {7, 2, 3}.
  EXPECT_EQ(traces->size(), 4u);
  FragmentTrace t = fragment_trace(7);
  t += fragment_trace(2);
  t += fragment_trace(3);
  EXPECT_TRUE(contains(*traces, t));
  t += fragment_trace(1);
  EXPECT_FALSE(contains(*traces, t));
  EXPECT_TRUE(std::is_sorted(traces->begin(), traces->end(), [](const auto& a, const auto& b) {
    return std::tie(a.count, a.id_sum, a.hash_sum) < std::tie(b.count, b.id_sum, b.hash_sum);
  }));
  // Two sets of equal size and id sum ({1, 4} and {2, 3}) differ in their hashes.
  FragmentTrace a = fragment_trace(0), b = fragment_trace(1);
  a += fragment_trace(3), b += fragment_trace(2);
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.id_sum, b.id_sum);
  EXPECT_NE(a.hash_sum, b.hash_sum);
  // 13 free members: 2^13 choices, more than admitted() enumerates.
  FragmentChoices many;
  for (int p = 0; p < 13; ++p)
    many.members.push_back({p, true, {}});
  EXPECT_FALSE(admitted(many).has_value());
  many.members.pop_back();
  EXPECT_EQ(admitted(many)->size(), size_t(1) << 12);  // told apart, each
  FragmentChoices anything;
  anything.anything = true;
  EXPECT_FALSE(admitted(anything).has_value());
}

}  // namespace
}  // namespace glrc::ref
