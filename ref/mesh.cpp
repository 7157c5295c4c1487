#include "ref/mesh.hpp"

#include <map>
#include <utility>

namespace glrc::ref {

namespace {

// An edge's ends, by their exact homogeneous window positions, smaller first: triangles share
// an edge when they name the same two points, whichever vertices (or indices) carry them.
using Point = std::array<mpq_class, 3>;
using EdgeKey = std::pair<Point, Point>;

Point point_of(const WindowVertex& v) {
  return {v.x_h, v.y_h, v.w_c};
}

// Sign of the homogeneous edge form of triangle t's edge i at vertex v (w_c > 0): > 0 on the
// triangle's side.
int side(const TriangleSetup& t, int i, const WindowVertex& v) {
  const LinearForm& e = t.homogeneous_edges[size_t(i)];
  // e(px, py) at the window position (x_h/w_c, y_h/w_c), px = x_w - 1/2, times w_c > 0.
  const mpq_class half(1, 2);
  return sgn(e.a * (v.x_h - half * v.w_c) + e.b * (v.y_h - half * v.w_c) + e.c * v.w_c);
}

}  // namespace

std::vector<std::array<bool, 3>> shared_edges(const std::vector<TriangleSetup>& triangles) {
  std::vector<std::array<bool, 3>> shared(triangles.size(), {false, false, false});
  std::map<EdgeKey, std::vector<std::pair<size_t, int>>> by_edge;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const TriangleSetup& s = triangles[t];
    if (!s.drawn) continue;
    bool w_positive = true;
    for (const auto& v : s.v)
      w_positive = w_positive && sgn(v.w_c) > 0;
    if (!w_positive) continue;
    for (int i = 0; i < 3; ++i) {
      Point a = point_of(s.v[size_t((i + 1) % 3)]), b = point_of(s.v[size_t((i + 2) % 3)]);
      // Homogeneous points are equal when their window positions are: compare x/w and y/w.
      auto window = [](const Point& p) {
        return std::array<mpq_class, 2>{p[0] / p[2], p[1] / p[2]};
      };
      auto wa = window(a), wb = window(b);
      if (wb < wa) std::swap(wa, wb);
      by_edge[{{wa[0], wa[1], 1}, {wb[0], wb[1], 1}}].push_back({t, i});
    }
  }
  // Within one edge's users, side(t, i, p) is the sign of the exact edge function of t through
  // the edge's two ends (the same two window points for every user), oriented so that t's own
  // third vertex is positive: sign(orient(P, Q, p)) times t's orientation sign. So for two users
  // u, k: side(u, v_k) = o_u·o_k = side(k, v_u), and the two lie on opposite sides exactly when
  // side(r, v_u) and side(r, v_k) differ, r being any one user. One exact evaluation per user
  // decides every pair: linear in the users, where comparing all pairs was quadratic (10,000
  // copies of one triangle took minutes).
  for (const auto& [key, users] : by_edge) {
    if (users.size() < 2) continue;
    const auto [tr, ir] = users.front();
    std::vector<int> rel(users.size());
    bool positive = false, negative = false;
    for (size_t u = 0; u < users.size(); ++u) {
      const auto [t, i] = users[u];
      rel[u] = u == 0 ? 1 : side(triangles[tr], ir, triangles[t].v[size_t(i)]);
      positive = positive || rel[u] > 0;
      negative = negative || rel[u] < 0;
    }
    if (!positive || !negative) continue;
    for (size_t u = 0; u < users.size(); ++u)
      if (rel[u] != 0) shared[users[u].first][size_t(users[u].second)] = true;
  }
  return shared;
}

}  // namespace glrc::ref
