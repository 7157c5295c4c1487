// Work on several threads: the reference draws bands of rows at once (ref/tiles.hpp), the
// comparator judges channels at once (compare/). Whatever runs in parallel here writes only its
// own outputs, so results are the same bits for any number of threads.
#pragma once

#include <functional>

namespace glrc {

// The threads `requested` means: itself when >= 1, else every core the process may use (its
// CPU affinity: taskset, cgroups' cpusets), not every core the machine has.
int thread_count(int requested);

// Calls fn(k) for k in [0, n) on up to `threads` threads (the calling one among them), each
// taking the next k when it is done with one; returns when all are done. An exception from fn
// is rethrown here (the first one), after every thread stopped.
void parallel_for(int n, int threads, const std::function<void(int)>& fn);

}  // namespace glrc
