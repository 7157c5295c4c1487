// Meshes: which edges two drawn triangles share. GL requires a pixel centre on a shared edge
// to be covered by exactly one of the two, so near such an edge coverage may move from one
// triangle to the other but never leave a gap or be drawn twice (watertightness).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/case.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

// shared[t][i]: edge i of triangle t (the edge opposite vertex i) is also an edge of another
// drawn triangle lying on its other side, and as many of the edge's users lie on each side (so
// that the fragments near it number the same whichever side a centre goes to). Every user's
// ends must have identical clip coordinates and w_c > 0; a culled or zero-area neighbour leaves
// the edge outer. `threads`: how many threads
// decide the shared ends' sides (parallel_for's count); the result is the same for any.
std::vector<std::array<bool, 3>> shared_edges(const std::vector<TriangleSetup>& triangles,
                                              int threads = 1);
// The same for triangles set up in place (render.cpp); every element must hold one.
std::vector<std::array<bool, 3>> shared_edges(
    const std::vector<std::optional<TriangleSetup>>& triangles, int threads = 1);

// Which shared edge a triangle's edge is, where shared_edges says it is one: the edge's name
// (the same for every user of it, different for every other shared edge), and the side of it the
// triangle lies on (first: the side of the edge's first user, in primitive order).
struct SharedEdge {
  int32_t group = -1;  // -1: not shared
  bool first_side = false;
  bool shared() const { return group >= 0; }
};
using SharedEdges = std::vector<std::array<SharedEdge, 3>>;
// shared_edges(), naming each shared edge and side (ref/fragment_choices.cpp).
SharedEdges shared_edge_groups(const std::vector<std::optional<TriangleSetup>>& triangles,
                               int threads = 1);
// shared_edges()'s flags of named edges: shared[t][i] = edges[t][i].shared().
std::vector<std::array<bool, 3>> shared_flags(const SharedEdges& edges);

// A case's triangles set up under one model (setup_triangles: every element holds one), each
// edge's sharing named (shared_edge_groups): render()'s set-up, kept for fragment_choices()
// to reuse instead of setting every triangle up again (reference.hpp). Freed on `threads`
// threads: its triangles hold many GMP numbers each.
struct CaseSetup {
  std::vector<std::optional<TriangleSetup>> triangles;
  SharedEdges shared;
  int threads = 1;

  CaseSetup() = default;
  CaseSetup(const CaseSetup&) = delete;
  CaseSetup& operator=(const CaseSetup&) = delete;
  ~CaseSetup();
};

}  // namespace glrc::ref
