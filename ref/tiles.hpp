// Tiles: the frame split into bands of rows that threads draw at once. Every pixel belongs to
// one band, and each band draws every triangle in primitive order, so a pixel sees the same
// triangles in the same order on any number of threads: the output is bit-identical for all of
// them (tests/ref/test_tiles.cpp checks 1, 2 and 5 threads against the digests).
#pragma once

#include <functional>
#include <vector>

namespace glrc::ref {

// The threads `requested` means: itself when >= 1, else every core the process may use.
int thread_count(int requested);

// Rows [y0, y1] of one band.
struct Band {
  int y0 = 0, y1 = -1;
};

// Rows [y0, y1] cut into bands of about equal height, several per thread (a scene is rarely
// even: a fan's centre holds most of its work), in order; none for y1 < y0.
std::vector<Band> bands(int y0, int y1, int threads);

// Calls fn(k) for k in [0, n) on up to `threads` threads (the calling one among them), each
// taking the next k when it is done with one; returns when all are done. An exception from fn
// is rethrown here (the first one), after every thread stopped.
void parallel_for(int n, int threads, const std::function<void(int)>& fn);

}  // namespace glrc::ref
