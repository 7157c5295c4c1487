// Tiles: the frame split into tiles, runs of whole rows that threads draw at once. Every pixel
// belongs to one tile, and each tile draws every triangle in primitive order, so a pixel sees the
// same triangles in the same order on any number of threads: the output is bit-identical for all of
// them (tests/ref/test_tiles.cpp checks 1, 2 and 5 threads against the digests).
#pragma once

#include <vector>

#include "core/parallel.hpp"

namespace glrc::ref {

// thread_count and parallel_for (core/parallel.hpp), under the names the reference has used.
using glrc::parallel_for;
using glrc::thread_count;

// Rows [y0, y1] of one tile: a thread's share of a draw. (Not a "band": that is the margin
// around an edge within which the freedom may move it, ref/coverage.hpp.)
struct Tile {
  int y0 = 0, y1 = -1;
};

// Rows [y0, y1] cut into tiles of about equal height, several per thread (a scene is rarely
// even: a fan's centre holds most of its work), in order; none for y1 < y0.
std::vector<Tile> tiles(int y0, int y1, int threads);

}  // namespace glrc::ref
