// shared_edges: one exact side test per triangle on an edge, where every pair was compared
// before (issue 11: 10,000 copies of one triangle took 334 s). The results must be the pairwise
// comparison's, bit for bit: the rule written pairwise is kept here as the oracle.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "ref/mesh.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {
namespace {

// The rule written the slow way: users grouped by their ends' window points (either order),
// none shared unless every user's ends have the same clip coordinates, each user's side of the
// edge taken against the first user both ways, and an edge shared where as many users lie on each
// side.
int side_of(const TriangleSetup& t, int i, const WindowVertex& v) {
  const LinearForm& e = t.homogeneous_edges[size_t(i)];
  const mpq_class half(1, 2);
  return sgn(e.a * (v.x_h - half * v.w_c) + e.b * (v.y_h - half * v.w_c) + e.c * v.w_c);
}

std::vector<std::array<bool, 3>> pairwise_shared_edges(const std::vector<TriangleSetup>& tris) {
  using Clip = std::array<mpq_class, 4>;  // x_h, y_h, z_c, w_c: the clip coordinates
  struct Use {
    size_t triangle;
    int edge;
    std::pair<Clip, Clip> ends;
  };
  std::vector<std::array<bool, 3>> shared(tris.size(), {false, false, false});
  std::map<std::pair<std::array<mpq_class, 2>, std::array<mpq_class, 2>>, std::vector<Use>> by_edge;
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
      Clip ca{a.x_h, a.y_h, a.z_c, a.w_c}, cb{b.x_h, b.y_h, b.z_c, b.w_c};
      if (wb < wa) std::swap(wa, wb), std::swap(ca, cb);
      by_edge[{wa, wb}].push_back({t, i, {ca, cb}});
    }
  }
  for (const auto& [key, users] : by_edge) {
    bool same_clip = true;
    for (const Use& u : users)
      same_clip = same_clip && u.ends == users[0].ends;
    if (!same_clip) continue;
    std::vector<int> rel(users.size(), 0);
    size_t same = 0, other = 0;
    const Use& r = users[0];
    for (size_t u = 0; u < users.size(); ++u) {
      const Use& k = users[u];
      if (u == 0 || side_of(tris[r.triangle], r.edge, tris[k.triangle].v[size_t(k.edge)]) > 0)
        rel[u] = 1;
      else if (side_of(tris[r.triangle], r.edge, tris[k.triangle].v[size_t(k.edge)]) < 0 &&
               side_of(tris[k.triangle], k.edge, tris[r.triangle].v[size_t(r.edge)]) < 0)
        rel[u] = -1;
      same += rel[u] > 0, other += rel[u] < 0;
    }
    if (other == 0 || same != other) continue;
    for (size_t u = 0; u < users.size(); ++u)
      if (rel[u] != 0) shared[users[u].triangle][size_t(users[u].edge)] = true;
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
// w = 0.5 (the same window point from other clip coordinates) in a quarter of the triangles, and
// each point three times (the same clip coordinates), some triangles repeated, both windings,
// some culled: edges with users on both sides, as many or not, from the same clip coordinates
// or not. On one thread and on three.
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
    // Vertex 3·p + k (k = 0: w = 1, 1: w = 2, 2: w = 0.5) of the 16 points, in one of the three
    // copies of them; mostly w = 1, so that many edges have one user on each side.
    auto vertex = [&] {
      const uint32_t point = rng() % 16, variant = rng() % 4 == 0 ? 1 + rng() % 2 : 0;
      return uint32_t((rng() % 3) * given + 3 * point + variant);
    };
    // A 3x3 grid of quads (w = 1, first copy) with alternating diagonals: 33 edges with one
    // user on each side, until the random triangles cross them.
    for (uint32_t y = 0; y < 3; ++y)
      for (uint32_t x = 0; x < 3; ++x) {
        const uint32_t a = 3 * (4 * y + x), b = a + 3, d = a + 12, e = a + 15;
        if ((x + y) % 2 == 0)
          c.triangles.insert(c.triangles.end(), {{a, b, e}, {a, e, d}});
        else
          c.triangles.insert(c.triangles.end(), {{a, b, d}, {b, e, d}});
      }
    for (int t = 0; t < 20; ++t)
      c.triangles.push_back({vertex(), vertex(), vertex()});
    for (int t = 0; t < 5; ++t)
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
    EXPECT_GT(n_shared, 10u) << "seed " << seed;  // the meshes do share edges
    EXPECT_EQ(got, want) << "seed " << seed;
    EXPECT_EQ(shared_edges(s, 3), want) << "seed " << seed << ", 3 threads";
  }
}

// 10,000 copies of one triangle: no edge has a neighbour on its other side. One more triangle
// across the first edge leaves it outer (a centre near it gets 10,000 fragments or 1, whichever
// side takes it); 10,000 copies of that one make it shared for all 20,000.
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
  for (const auto& e : shared)
    ASSERT_EQ(e, (std::array<bool, 3>{false, false, false}));

  for (int t = 1; t < 10000; ++t) {
    c.triangles.push_back({1, 3, 2});
    s.push_back(setup_triangle(c, Model{}, int(c.triangles.size()) - 1));
  }
  shared = shared_edges(s);
  for (size_t t = 0; t < 10000; ++t)
    ASSERT_EQ(shared[t], (std::array<bool, 3>{true, false, false})) << t;
  for (size_t t = 10000; t < 20000; ++t)
    ASSERT_EQ(shared[t], (std::array<bool, 3>{false, true, false})) << t;  // 2-1 is opposite 3
}

// The same window points from other clip coordinates: another z_c at one end (the near plane may
// cut one user's edge and not the other's), or every coordinate scaled. Not shared.
TEST(SharedEdges, OnlyIdenticalClipCoordinatesShareAnEdge) {
  Case c = grid_case();
  c.vertices = {{{-0.9f, -0.8f, 0, 1}, {}},    {{0.7f, -0.6f, 0, 1}, {}},
                {{0.1f, 0.9f, 0, 1}, {}},      {{0.6f, 0.8f, 0, 1}, {}},
                {{0.7f, -0.6f, -0.5f, 1}, {}}, {{1.4f, -1.2f, 0, 2}, {}}};
  c.triangles = {{0, 1, 2}, {1, 3, 2}};
  EXPECT_EQ(shared_edges(setups(c, Model{}))[0], (std::array<bool, 3>{true, false, false}));
  c.triangles = {{0, 1, 2}, {4, 3, 2}};  // vertex 1 with another z_c
  EXPECT_EQ(shared_edges(setups(c, Model{}))[0], (std::array<bool, 3>{false, false, false}));
  c.triangles = {{0, 1, 2}, {5, 3, 2}};  // vertex 1 scaled by 2
  EXPECT_EQ(shared_edges(setups(c, Model{}))[0], (std::array<bool, 3>{false, false, false}));
}

}  // namespace
}  // namespace glrc::ref
