// shared_edges: one exact side test per triangle on an edge, where every pair was compared
// before (issue 11: 10,000 copies of one triangle took 334 s). The results must be the pairwise
// comparison's, bit for bit: the old algorithm is kept here as the oracle.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "ref/mesh.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {
namespace {

// The algorithm before issue 11, verbatim but for names: every pair of users of an edge.
int side_of(const TriangleSetup& t, int i, const WindowVertex& v) {
  const LinearForm& e = t.homogeneous_edges[size_t(i)];
  const mpq_class half(1, 2);
  return sgn(e.a * (v.x_h - half * v.w_c) + e.b * (v.y_h - half * v.w_c) + e.c * v.w_c);
}

std::vector<std::array<bool, 3>> pairwise_shared_edges(const std::vector<TriangleSetup>& tris) {
  using Point = std::array<mpq_class, 3>;
  std::vector<std::array<bool, 3>> shared(tris.size(), {false, false, false});
  std::map<std::pair<Point, Point>, std::vector<std::pair<size_t, int>>> by_edge;
  for (size_t t = 0; t < tris.size(); ++t) {
    const TriangleSetup& s = tris[t];
    if (!s.drawn) continue;
    bool w_positive = true;
    for (const auto& v : s.v)
      w_positive = w_positive && sgn(v.w_c) > 0;
    if (!w_positive) continue;
    for (int i = 0; i < 3; ++i) {
      const WindowVertex& a = s.v[size_t((i + 1) % 3)];
      const WindowVertex& b = s.v[size_t((i + 2) % 3)];
      std::array<mpq_class, 2> wa{a.x_h / a.w_c, a.y_h / a.w_c}, wb{b.x_h / b.w_c, b.y_h / b.w_c};
      if (wb < wa) std::swap(wa, wb);
      by_edge[{{wa[0], wa[1], 1}, {wb[0], wb[1], 1}}].push_back({t, i});
    }
  }
  for (const auto& [key, users] : by_edge)
    for (size_t u = 0; u < users.size(); ++u)
      for (size_t k = u + 1; k < users.size(); ++k) {
        const auto [t1, i1] = users[u];
        const auto [t2, i2] = users[k];
        if (side_of(tris[t1], i1, tris[t2].v[size_t(i2)]) < 0 &&
            side_of(tris[t2], i2, tris[t1].v[size_t(i1)]) < 0)
          shared[t1][size_t(i1)] = shared[t2][size_t(i2)] = true;
      }
  return shared;
}

Case grid_case() {
  Case c;
  c.name = "mesh";
  c.fb_width = c.fb_height = 32;
  c.viewport = {0, 0, 32, 32};
  return c;
}

std::vector<TriangleSetup> setups(const Case& c, const Model& m) {
  std::vector<TriangleSetup> out;
  for (size_t p = 0; p < c.triangles.size(); ++p)
    out.push_back(setup_triangle(c, m, int(p)));
  return out;
}

// Random triangles over a 4x4 grid of window points, each point also written with w = 2 and
// w = 0.5 (the same window point from other clip coordinates) and each of those three times
// (the same clip coordinates), some repeated, both windings, some culled: many edges with many
// users on both sides. On one thread and on three.
TEST(SharedEdges, SameAsEveryPairOnRandomMeshes) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    Case c = grid_case();
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        for (float w : {1.0f, 2.0f, 0.5f})
          c.vertices.push_back(
              {{(-0.75f + 0.5f * float(x)) * w, (-0.75f + 0.5f * float(y)) * w, 0.0f, w}, {}});
    // Every vertex written twice more, with the same clip coordinates (a mesh given triangle by
    // triangle repeats its shared vertices): equal window points under other indices.
    const size_t given = c.vertices.size();
    for (int copy = 0; copy < 2; ++copy)
      for (size_t i = 0; i < given; ++i)
        c.vertices.push_back(c.vertices[i]);
    std::uniform_int_distribution<uint32_t> vertex(0, uint32_t(c.vertices.size() - 1));
    for (int t = 0; t < 400; ++t)
      c.triangles.push_back({vertex(rng), vertex(rng), vertex(rng)});
    for (int t = 0; t < 100; ++t)
      c.triangles.push_back(c.triangles[rng() % c.triangles.size()]);  // exact copies
    c.cull = seed % 3 == 0 ? CullFace::back : CullFace::none;
    Model m;
    m.subpixel_bits = seed % 2 ? 8 : 0;  // snapped and homogeneous coverage paths
    const auto s = setups(c, m);
    const auto got = shared_edges(s);
    const auto want = pairwise_shared_edges(s);
    size_t n_shared = 0;
    for (const auto& e : want)
      n_shared += size_t(e[0]) + size_t(e[1]) + size_t(e[2]);
    EXPECT_GT(n_shared, 50u) << "seed " << seed;  // the meshes do share edges
    EXPECT_EQ(got, want) << "seed " << seed;
    EXPECT_EQ(shared_edges(s, 3), want) << "seed " << seed << ", 3 threads";
  }
}

// 10,000 copies of one triangle: no edge has a neighbour on its other side. One more triangle
// across the first edge makes that edge shared for every copy and for it.
TEST(SharedEdges, TenThousandCopiesOfOneTriangle) {
  Case c = grid_case();
  c.vertices = {{{-0.9f, -0.8f, 0, 1}, {}},
                {{0.7f, -0.6f, 0, 1}, {}},
                {{0.1f, 0.9f, 0, 1}, {}},
                {{0.6f, 0.8f, 0, 1}, {}}};
  c.triangles.assign(10000, {0, 1, 2});
  auto s = setups(c, Model{});
  auto shared = shared_edges(s);
  ASSERT_EQ(shared.size(), 10000u);
  for (const auto& e : shared)
    ASSERT_EQ(e, (std::array<bool, 3>{false, false, false}));

  c.triangles.push_back({1, 3, 2});  // across edge 1-2, which is edge 0 of (0, 1, 2)
  s.push_back(setup_triangle(c, Model{}, 10000));
  shared = shared_edges(s);
  for (size_t t = 0; t < 10000; ++t)
    ASSERT_EQ(shared[t], (std::array<bool, 3>{true, false, false})) << t;
  EXPECT_EQ(shared[10000], (std::array<bool, 3>{false, true, false}));  // 2-1 is opposite 3
}

}  // namespace
}  // namespace glrc::ref
