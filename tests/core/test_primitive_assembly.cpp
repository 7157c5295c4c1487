// Primitive assembly (core/primitive_assembly.hpp): table 13.2's provoking vertices, the
// strip's alternating winding, restarts and gl_PrimitiveID numbering, against hand-written
// expectations.
#include <gtest/gtest.h>

#include "core/primitive_assembly.hpp"

namespace glrc {
namespace {

using Triangles = std::vector<std::array<uint32_t, 3>>;

Draw arrays(PrimitiveMode mode, uint32_t first, uint32_t count) {
  Draw d;
  d.mode = mode, d.first = first, d.count = count;
  return d;
}
Draw elements(PrimitiveMode mode, IndexType type, std::vector<uint32_t> indices,
              Restart restart = Restart::off, uint32_t restart_index = 0) {
  Draw d;
  d.mode = mode, d.index_type = type, d.indices = std::move(indices);
  d.restart = restart, d.restart_index = restart_index;
  return d;
}

TEST(PrimitiveAssembly, StripsUnderBothConventions) {
  const std::vector<Draw> strip{arrays(PrimitiveMode::triangle_strip, 10, 5)};
  // Last: odd triangles (v_i+1, v_i, v_i+2), the provoking v_i+2 last.
  EXPECT_EQ(assemble(strip, ProvokingVertex::last).triangles,
            (Triangles{{10, 11, 12}, {12, 11, 13}, {12, 13, 14}}));
  // First: odd triangles (v_i, v_i+2, v_i+1), the provoking v_i first.
  EXPECT_EQ(assemble(strip, ProvokingVertex::first).triangles,
            (Triangles{{10, 11, 12}, {11, 13, 12}, {12, 13, 14}}));
  EXPECT_EQ(assemble(strip, ProvokingVertex::first).kind, (std::vector<uint8_t>{1, 2, 1}));
}

TEST(PrimitiveAssembly, FansProvokeByTheRimNeverTheHub) {
  const std::vector<Draw> fan{arrays(PrimitiveMode::triangle_fan, 0, 5)};
  EXPECT_EQ(assemble(fan, ProvokingVertex::last).triangles,
            (Triangles{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
  // First: v_i+1 provokes (table 13.2), so it comes first and the hub last.
  EXPECT_EQ(assemble(fan, ProvokingVertex::first).triangles,
            (Triangles{{1, 2, 0}, {2, 3, 0}, {3, 4, 0}}));
}

TEST(PrimitiveAssembly, RestartStartsANewPrimitiveAndKeepsCounting) {
  // A fan, restart, another fan: the second's hub is 5, not 0; leftovers make nothing.
  const std::vector<Draw> d{elements(PrimitiveMode::triangle_fan, IndexType::unsigned_short,
                                     {0, 1, 2, 3, 65535, 5, 6, 7, 65535, 8, 9},
                                     Restart::fixed_index)};
  const AssembledTriangles a = assemble(d, ProvokingVertex::last);
  EXPECT_EQ(a.triangles, (Triangles{{0, 1, 2}, {0, 2, 3}, {5, 6, 7}}));
  EXPECT_EQ(a.first_triangle, (std::vector<uint32_t>{0, 3}));
  // glPrimitiveRestartIndex: 7 restarts, 65535 is an ordinary index then.
  const std::vector<Draw> e{elements(PrimitiveMode::triangles, IndexType::unsigned_int,
                                     {0, 1, 2, 3, 7, 4, 5, 6}, Restart::index, 7)};
  EXPECT_EQ(assemble(e, ProvokingVertex::last).triangles, (Triangles{{0, 1, 2}, {4, 5, 6}}));
}

TEST(PrimitiveAssembly, EveryDrawCountsFromZeroAndDegenerateTrianglesCount) {
  const std::vector<Draw> d{
      arrays(PrimitiveMode::triangle_strip, 0, 4),
      elements(PrimitiveMode::triangle_strip, IndexType::unsigned_byte, {0, 1, 1, 2}),
      arrays(PrimitiveMode::triangles, 0, 2)};
  const AssembledTriangles a = assemble(d, ProvokingVertex::last);
  EXPECT_EQ(a.triangles.size(), 4u);  // the repeated index's two degenerate triangles count
  EXPECT_EQ(a.first_triangle, (std::vector<uint32_t>{0, 2, 4, 4}));
}

TEST(PrimitiveAssembly, ACaseWithoutDrawsIsOneListOfItsTriangles) {
  Case c;
  c.triangles = {{0, 1, 2}, {2, 1, 3}};
  const std::vector<Draw> d = draws_of(c);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].index_type, IndexType::unsigned_int);
  EXPECT_EQ(d[0].indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
  EXPECT_EQ(assemble(d, ProvokingVertex::first).triangles, c.triangles);
  EXPECT_FALSE(several_draws(c));
}

TEST(PrimitiveAssembly, OnlyTheSameKindOfPrimitiveIsAnIdenticalCopy) {
  Case c;
  for (const std::array<float, 4>& p :
       {std::array<float, 4>{-1, -1, 0, 1}, {1, -1, 0, 1}, {-1, 1, 0, 1}, {1, 1, 0, 1}})
    c.vertices.push_back({p, {}});
  // A strip's odd triangle (1, 0, 2) and a list triangle with the same order.
  c.draws = {arrays(PrimitiveMode::triangle_strip, 0, 4),
             elements(PrimitiveMode::triangles, IndexType::unsigned_int, {2, 1, 3, 0, 1, 2})};
  assemble_triangles(c);
  ASSERT_EQ(c.triangles.size(), 4u);
  ASSERT_EQ(c.triangles[1], (std::array<uint32_t, 3>{2, 1, 3}));
  ASSERT_EQ(c.triangles[2], (std::array<uint32_t, 3>{2, 1, 3}));
  const std::vector<int32_t> first = identical_triangles(c);
  EXPECT_EQ(first[2], 2);  // not a copy of the odd strip triangle 1
  EXPECT_EQ(first[3], 3);  // nor of the even strip triangle 0: another kind of primitive
  // Two list triangles with the same order are.
  c.draws.push_back(elements(PrimitiveMode::triangles, IndexType::unsigned_byte, {0, 1, 2}));
  assemble_triangles(c);
  EXPECT_EQ(identical_triangles(c)[4], 3);
}

}  // namespace
}  // namespace glrc
