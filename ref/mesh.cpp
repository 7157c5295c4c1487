#include "ref/mesh.hpp"

#include <algorithm>
#include <utility>

#include "core/parallel.hpp"

namespace glrc::ref {

namespace {

// A vertex's exact window position (x_h/w_c, y_h/w_c), with double copies that order like it:
// get_d truncates, so it never reverses an order, and two points whose copies differ are
// ordered by the copies alone. Equal copies fall back to the exact values, compared as
// x_h·w_c' against x_h'·w_c (w_c, w_c' > 0): no division, no canonical form.
struct WindowPoint {
  const WindowVertex* v = nullptr;
  double dx = 0, dy = 0;
};

int compare(const WindowPoint& p, const WindowPoint& q) {
  if (&p == &q) return 0;  // one case vertex: a triangle's edges share their ends
  if (p.dx != q.dx) return p.dx < q.dx ? -1 : 1;
  // Vertices given apart with the same clip coordinates (a fan written triangle by triangle
  // repeats its centre in each) are equal without a product: comparing rationals for equality
  // allocates nothing.
  const bool same_w = p.v->w_c == q.v->w_c;
  if (!(same_w && p.v->x_h == q.v->x_h))
    if (const int c = cmp(mpq_class(p.v->x_h * q.v->w_c), mpq_class(q.v->x_h * p.v->w_c)); c != 0)
      return c;
  if (p.dy != q.dy) return p.dy < q.dy ? -1 : 1;
  if (same_w && p.v->y_h == q.v->y_h) return 0;
  return cmp(mpq_class(p.v->y_h * q.v->w_c), mpq_class(q.v->y_h * p.v->w_c));
}

// Whether two window points come from the same clip coordinates (x_h, y_h and w_c fix x_c and
// y_c).
bool same_clip(const WindowPoint& p, const WindowPoint& q) {
  return &p == &q || (p.v->w_c == q.v->w_c && p.v->x_h == q.v->x_h && p.v->y_h == q.v->y_h &&
                      p.v->z_c == q.v->z_c);
}

// One drawn triangle's edge: its ends, the smaller first, so that triangles naming the same two
// window points in either order have the same ends.
struct EdgeUse {
  const WindowPoint *a, *b;
  size_t triangle;
  int edge;
};

int compare(const EdgeUse& u, const EdgeUse& k) {
  if (const int c = compare(*u.a, *k.a); c != 0) return c;
  return compare(*u.b, *k.b);
}

// Sign of the homogeneous edge form of triangle t's edge i at vertex v (w_c > 0): > 0 on the
// triangle's side.
int side(const TriangleSetup& t, int i, const WindowVertex& v) {
  const LinearForm& e = t.homogeneous_edges[size_t(i)];
  // e(px, py) at the window position (x_h/w_c, y_h/w_c), px = x_w - 1/2, times w_c > 0.
  const mpq_class half(1, 2);
  return sgn(e.a * (v.x_h - half * v.w_c) + e.b * (v.y_h - half * v.w_c) + e.c * v.w_c);
}

// shared_edge_groups over n triangles, triangle(t) the t-th.
template <class Triangle>
SharedEdges shared_edges_of(size_t n, const Triangle& triangle, int threads) {
  SharedEdges shared(n);
  // Each vertex's window point, computed once for all the drawn triangles that use it (a mesh
  // shares its vertices; an edge names two of them), by the vertex's index in the case.
  // Sized once, before any point is taken: EdgeUse keeps pointers into it.
  size_t vertices = 0;
  for (size_t t = 0; t < n; ++t)
    for (uint32_t index : triangle(t).index)
      vertices = std::max(vertices, size_t(index) + 1);
  std::vector<std::optional<WindowPoint>> points(vertices);
  std::vector<EdgeUse> uses;
  for (size_t t = 0; t < n; ++t) {
    const TriangleSetup& s = triangle(t);
    if (!s.drawn) continue;
    if (!std::all_of(s.v.begin(), s.v.end(), [](const WindowVertex& v) { return sgn(v.w_c) > 0; }))
      continue;
    const WindowPoint* corner[3];
    for (size_t j = 0; j < 3; ++j) {
      std::optional<WindowPoint>& p = points[s.index[j]];
      if (!p)
        p = WindowPoint{&s.v[j], truncated_quotient(s.v[j].x_h, s.v[j].w_c),
                        truncated_quotient(s.v[j].y_h, s.v[j].w_c)};
      corner[j] = &*p;
    }
    for (int i = 0; i < 3; ++i) {
      const WindowPoint* a = corner[(i + 1) % 3];
      const WindowPoint* b = corner[(i + 2) % 3];
      if (compare(*b, *a) < 0) std::swap(a, b);
      uses.push_back({a, b, t, i});
    }
  }
  // Grouped by their ends: sorted, in primitive order within a group. O(n log n) comparisons,
  // nearly all of doubles.
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& u, const EdgeUse& k) {
    const int c = compare(u, k);
    return c != 0 ? c < 0 : std::pair(u.triangle, u.edge) < std::pair(k.triangle, k.edge);
  });
  // Within one edge's users, side(t, i, p) is the sign of the exact edge function of t through
  // the edge's two ends (the same two window points for every user), oriented so that t's own
  // third vertex is positive: sign(orient(P, Q, p)) times t's orientation sign. So for two users
  // u, k: side(u, v_k) = o_u·o_k = side(k, v_u), and the two lie on opposite sides exactly when
  // side(r, v_u) and side(r, v_k) differ, r being any one user. One exact evaluation per user
  // decides every pair: linear in the users, where comparing all pairs was quadratic (10,000
  // copies of one triangle took minutes).
  std::vector<std::pair<size_t, size_t>> groups;  // [first, end) of uses with the same ends
  for (size_t first = 0, end = 0; first < uses.size(); first = end) {
    end = first + 1;
    while (end < uses.size() && compare(uses[first], uses[end]) == 0)
      ++end;
    if (end - first >= 2) groups.emplace_back(first, end);
  }
  // The groups on every thread: each side() is exact rational arithmetic (a fan of 4,400
  // triangles has 4,400 shared edges), and each (triangle, edge) is in one group, so each
  // writes its own elements of `shared` and of `rel` (each use's side) only. A shared edge is
  // named by its group's index.
  std::vector<int> rel(uses.size(), 0);
  parallel_for(int(groups.size()), threads, [&](int g) {
    const auto [first, end] = groups[size_t(g)];
    const EdgeUse& r = uses[first];
    size_t positive = 0, negative = 0;
    for (size_t u = first; u < end; ++u) {
      const EdgeUse& k = uses[u];
      // The same window points from other clip coordinates (another z_c, or every coordinate
      // scaled): the clipper may cut the two triangles' edges apart (near and far by z_c, the
      // new vertex's rounding by its inputs), and then their polygons' edges are not one line.
      if (!same_clip(*k.a, *r.a) || !same_clip(*k.b, *r.b)) return;
      rel[u] = u == first
                   ? 1
                   : side(triangle(r.triangle), r.edge, triangle(k.triangle).v[size_t(k.edge)]);
      positive += rel[u] > 0;
      negative += rel[u] < 0;
    }
    // A centre near the edge goes to the same side for every user (they rasterize one snapped
    // edge alike), so the users' fragments there number those of one side: decided only where
    // both sides have as many (a copy of one user on one side makes it 1 or 2).
    if (positive == 0 || positive != negative) return;
    for (size_t u = first; u < end; ++u)
      if (rel[u] != 0) shared[uses[u].triangle][size_t(uses[u].edge)] = {g, rel[u] > 0};
  });
  return shared;
}

}  // namespace

std::vector<std::array<bool, 3>> shared_flags(const SharedEdges& edges) {
  std::vector<std::array<bool, 3>> out(edges.size());
  for (size_t t = 0; t < edges.size(); ++t)
    for (size_t i = 0; i < 3; ++i)
      out[t][i] = edges[t][i].shared();
  return out;
}

SharedEdges shared_edge_groups(const std::vector<std::optional<TriangleSetup>>& triangles,
                               int threads) {
  return shared_edges_of(
      triangles.size(), [&](size_t t) -> const TriangleSetup& { return *triangles[t]; }, threads);
}

std::vector<std::array<bool, 3>> shared_edges(const std::vector<TriangleSetup>& triangles,
                                              int threads) {
  return shared_flags(shared_edges_of(
      triangles.size(), [&](size_t t) -> const TriangleSetup& { return triangles[t]; }, threads));
}

std::vector<std::array<bool, 3>> shared_edges(
    const std::vector<std::optional<TriangleSetup>>& triangles, int threads) {
  return shared_flags(shared_edge_groups(triangles, threads));
}

CaseSetup::~CaseSetup() {
  ThreadPool pool(thread_count(threads));
  pool.parallel_for(int(triangles.size()), [&](int k) { triangles[size_t(k)].reset(); });
}

}  // namespace glrc::ref
