// The planted faults on a hand-made case and frame: each changes what it says it changes.
#include <gtest/gtest.h>

#include <cmath>

#include "core/primitive_assembly.hpp"
#include "selftest/faults.hpp"

namespace glrc::selftest {
namespace {

const Fault& fault(const std::string& name) {
  for (const Fault& f : faults())
    if (f.name == name) return f;
  throw std::runtime_error("no fault " + name);
}

TEST(Faults, TwentyFiveInAFixedOrder) {
  ASSERT_EQ(faults().size(), 25u);
  EXPECT_EQ(faults().front().name, "smooth-as-noperspective");
  EXPECT_EQ(faults()[7].name, "shared-edge-pixel-dropped");
  EXPECT_EQ(faults()[8].name, "shared-horizontal-edge-drawn-twice");
  EXPECT_EQ(faults()[9].name, "thin-shared-edge-drawn-twice");
  EXPECT_EQ(faults()[10].name, "hidden-fragment-dropped");
  EXPECT_EQ(faults()[11].name, "identical-copy-wins-depth-test");
  EXPECT_EQ(faults()[12].name, "strip-provoking-first-wrong");
  EXPECT_EQ(faults()[13].name, "fan-hub-not-reset");
  EXPECT_EQ(faults()[14].name, "scissor-box-one-pixel-wider");
  EXPECT_EQ(faults()[15].name, "upper-left-facing-not-reversed");
  EXPECT_EQ(faults()[16].name, "clip-distance-sign-flipped");
  EXPECT_EQ(faults()[17].name, "frag-coord-half-pixel-off");
  EXPECT_EQ(faults()[18].name, "frag-coord-w-not-inverted");
  EXPECT_EQ(faults()[19].name, "front-facing-inverted-under-cw");
  EXPECT_EQ(faults()[20].name, "zero-to-one-ignored");
  EXPECT_EQ(faults()[21].name, "depth-clamp-not-applied");
  EXPECT_EQ(faults()[22].name, "depth-clamp-to-unit-range");
  EXPECT_EQ(faults()[23].name, "polygon-offset-units-ignored");
  EXPECT_EQ(faults().back().name, "polygon-offset-slope-x-only");
}

// The built-in faults change only their built-in's components, at covered pixels; the facing
// one only under glFrontFace(GL_CW).
TEST(Faults, BuiltinFaultsChangeOnlyTheirBuiltin) {
  Case c;
  c.fb_width = 2, c.fb_height = 1;
  c.varyings = {{"v", 1, Interpolation::smooth},
                builtin_varying(Builtin::frag_coord),
                builtin_varying(Builtin::front_facing)};
  Frame f(2, 1, 6);
  f.primitive = {0, Frame::kNoPrimitive};
  for (int k = 0; k < 6; ++k)
    f.components[size_t(k)] = {float(k + 1), float(k + 1)};
  const Expectation e;
  Frame half = f;
  ASSERT_TRUE(fault("frag-coord-half-pixel-off").after(c, e, half));
  EXPECT_EQ(half.components[0][0], 1.0f);
  EXPECT_EQ(half.components[1][0], 1.5f);
  EXPECT_EQ(half.components[2][0], 2.5f);
  EXPECT_EQ(half.components[3][0], 4.0f);
  EXPECT_EQ(half.components[1][1], 2.0f);  // not covered
  Frame w = f;
  ASSERT_TRUE(fault("frag-coord-w-not-inverted").after(c, e, w));
  EXPECT_EQ(w.components[4][0], 0.2f);
  EXPECT_EQ(w.components[3][0], 4.0f);
  Frame facing = f;
  EXPECT_FALSE(fault("front-facing-inverted-under-cw").after(c, e, facing));
  c.front_face = FrontFace::cw;
  ASSERT_TRUE(fault("front-facing-inverted-under-cw").after(c, e, facing));
  EXPECT_EQ(facing.components[5][0], -5.0f);
  EXPECT_EQ(facing.components[4][0], 5.0f);
}

// The assembly faults change only what they name: a strip's odd triangles under the first
// convention, a fan's hub after a restart; each case stays one draw list per draw.
TEST(Faults, AssemblyFaultsChangeOnlyTheirTriangles) {
  Case c;
  c.provoking = ProvokingVertex::first;
  for (int k = 0; k < 8; ++k)
    c.vertices.push_back({{float(k), float(k % 2), 0, 1}, {}});
  Draw strip;
  strip.mode = PrimitiveMode::triangle_strip, strip.first = 0, strip.count = 4;
  Draw fans;
  fans.mode = PrimitiveMode::triangle_fan, fans.index_type = IndexType::unsigned_byte;
  fans.indices = {4, 5, 6, 255, 7, 5, 6}, fans.restart = Restart::fixed_index;
  c.draws = {strip, fans};
  assemble_triangles(c);
  Case g = c;
  fault("strip-provoking-first-wrong").before(g);
  ASSERT_EQ(g.draws.size(), 2u);
  EXPECT_EQ(g.triangles[0], c.triangles[0]);
  EXPECT_EQ(g.triangles[1], (std::array<uint32_t, 3>{2, 1, 3}));  // v_i+1 first: it provokes
  EXPECT_EQ(g.triangles[2], c.triangles[2]);
  Case h = c;
  fault("fan-hub-not-reset").before(h);
  EXPECT_EQ(h.triangles[2], c.triangles[2]);
  EXPECT_EQ(h.triangles[3], (std::array<uint32_t, 3>{5, 6, 4}));  // hub 4 kept, not 7
  EXPECT_EQ(h.draws[1].indices, (std::vector<uint32_t>{5, 6, 4, 5, 6, 4}));
  // A case without strips or fans under the first convention is left alone.
  Case plain = c;
  plain.provoking = ProvokingVertex::last;
  assemble_triangles(plain);
  Case p = plain;
  fault("strip-provoking-first-wrong").before(p);
  EXPECT_EQ(p.draws, plain.draws);
}

TEST(Faults, KeepMantissaBitsRoundsToNearestEven) {
  EXPECT_EQ(keep_mantissa_bits(1.0f, 11), 1.0f);
  EXPECT_EQ(keep_mantissa_bits(1.0f + 0x1p-12f, 11), 1.0f);                        // a tie: to even
  EXPECT_EQ(keep_mantissa_bits(1.0f + 0x1p-11f + 0x1p-12f, 11), 1.0f + 0x1p-10f);  // tie, up
  EXPECT_EQ(keep_mantissa_bits(1.0f + 0x1p-12f + 0x1p-20f, 11), 1.0f + 0x1p-11f);
  EXPECT_EQ(keep_mantissa_bits(-3.0f, 11), -3.0f);
  EXPECT_TRUE(std::isnan(keep_mantissa_bits(NAN, 11)));
}

TEST(Faults, CaseFaultsChangeTheCase) {
  Case c;
  c.viewport = {0, 0, 64, 64};
  c.varyings = {{"s", 1, Interpolation::smooth}, {"f", 1, Interpolation::flat}};
  c.vertices = {{{0.5f, 0, 0, 2}, {0, 1}}};
  Case g = c;
  fault("smooth-as-noperspective").before(g);
  EXPECT_EQ(g.varyings[0].interpolation, Interpolation::noperspective);
  EXPECT_EQ(g.varyings[1].interpolation, Interpolation::flat);
  g = c;
  fault("positions-shifted-half-pixel").before(g);
  EXPECT_EQ(g.vertices[0].clip[0], 0.5f + 2.0f / 64);  // w_c / width: half a pixel
  g = c;
  fault("depth-range-nudged").before(g);
  EXPECT_EQ(g.depth_near, 1e-4f);
  EXPECT_EQ(g.depth_far, 1.0f - 1e-4f);
  g = c;
  fault("provoking-vertex-flipped").before(g);
  EXPECT_EQ(g.provoking, ProvokingVertex::first);
}

TEST(Faults, FrameFaultsChangeTheFrame) {
  Case c;
  c.varyings = {{"v", 2, Interpolation::smooth}};
  Frame f(2, 1, 2);
  f.primitive = {0, 1};
  f.fragments = {1, 1};
  f.components = {{0.5f, 2.0f}, {1.0f / 3, 7.0f}};
  Expectation e{f, {0, edge::shared}, Frame()};

  Frame g = f;
  EXPECT_TRUE(fault("one-value-off-1e-3").after(c, e, g));
  EXPECT_FLOAT_EQ(g.components[0][1], 2.002f);  // the largest |value| of the first component
  EXPECT_EQ(g.components[0][0], 0.5f);
  g = f;
  EXPECT_TRUE(fault("components-swapped").after(c, e, g));
  EXPECT_EQ(g.components[0], f.components[1]);
  g = f;
  EXPECT_TRUE(fault("varyings-11-mantissa-bits").after(c, e, g));
  EXPECT_NE(g.components[1][0], f.components[1][0]);
  g = f;
  EXPECT_TRUE(fault("shared-edge-pixel-dropped").after(c, e, g));
  EXPECT_EQ(g.primitive[1], Frame::kNoPrimitive);
  EXPECT_EQ(g.fragments[1], 0);
  EXPECT_EQ(g.primitive[0], 0);
}

// Two triangles sharing the edge (0.5, 3.5)-(7.5, 3.5) of an 8x8 viewport, on the row of centres
// y = 3.5; one end at w_c = 2, so the edge is horizontal only in window coordinates.
Case shared_horizontal_edge() {
  Case c;
  c.viewport = {0, 0, 8, 8};
  c.fb_width = c.fb_height = 8;
  c.vertices = {{{-0.875f, -0.125f, 0, 1}, {}},
                {{1.75f, -0.25f, 0, 2}, {}},
                {{0, 0.875f, 0, 1}, {}},
                {{0, -0.875f, 0, 1}, {}}};
  c.triangles = {{0, 1, 2}, {1, 0, 3}};  // above, below; both counter-clockwise
  return c;
}

TEST(Faults, SharedHorizontalEdgeDrawnTwice) {
  const Case c = shared_horizontal_edge();
  Frame f(8, 8, 0);
  f.fragments.assign(f.pixel_count(), 0);
  for (int x = 0; x < 8; ++x)
    f.primitive[f.index(x, 3)] = 0, f.fragments[f.index(x, 3)] = 1;
  Expectation e{f, std::vector<uint8_t>(f.pixel_count(), 0), Frame()};
  for (int x = 1; x < 7; ++x)
    e.edges[f.index(x, 3)] = edge::shared | edge::tie;
  e.edges[f.index(1, 3)] |= edge::snapping;  // near an outer edge: fragments are not counted
  e.edges[f.index(3, 4)] = edge::shared;     // near the edge but not on it

  Frame g = f;
  EXPECT_TRUE(fault("shared-horizontal-edge-drawn-twice").after(c, e, g));
  for (int x = 0; x < 8; ++x)
    EXPECT_EQ(g.fragments[f.index(x, 3)], x >= 2 && x <= 6 ? 2 : 1) << x;
  EXPECT_EQ(g.fragments[f.index(3, 4)], 0);
  EXPECT_EQ(g.primitive, f.primitive);

  // The lower triangle culled: the edge is no longer shared, and nothing changes.
  Case culled = c;
  culled.triangles[1] = {0, 1, 3};  // clockwise
  culled.cull = CullFace::back;
  g = f;
  EXPECT_FALSE(fault("shared-horizontal-edge-drawn-twice").after(culled, e, g));
  EXPECT_EQ(g.fragments, f.fragments);

  // Without fragment counts there is nothing to double.
  g = f;
  g.fragments.clear();
  EXPECT_FALSE(fault("shared-horizontal-edge-drawn-twice").after(c, e, g));
}

}  // namespace
}  // namespace glrc::selftest
