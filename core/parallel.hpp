// Work on several threads: the reference draws tiles of rows at once (ref/tiles.hpp), the
// comparator judges channels at once (compare/). Whatever runs in parallel here writes only its
// own outputs, so results are the same bits for any number of threads.
#pragma once

#include <functional>
#include <memory>

namespace glrc {

// The threads `requested` means: itself when >= 1, else every core the process may use (its
// CPU affinity: taskset, cgroups' cpusets), not every core the machine has.
int thread_count(int requested);

// Calls fn(k) for k in [0, n) on up to `threads` threads (the calling one among them), each
// taking the next k when it is done with one; returns when all are done. An exception from fn
// is rethrown here (the first one), after every thread stopped.
void parallel_for(int n, int threads, const std::function<void(int)>& fn);

// Threads kept for a run of parallel_for calls: each call hands its items to the same threads,
// which wait between calls, where the function above starts and joins threads per call (a
// thread's start, its allocator's cache and its thread-local scratch made anew each time: the
// reference's two dozen calls per frame scaled poorly for it). Owned by the caller for the
// run: no pool outlives it, and no state is shared between pools.
class ThreadPool {
 public:
  // thread_count(threads) threads in all, the calling one among them.
  explicit ThreadPool(int threads);
  ~ThreadPool();  // stops the threads and joins them
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int threads() const { return threads_; }
  // As parallel_for(n, threads(), fn), on the pool's threads. Not from within fn (one call at a
  // time, from the thread that made the pool).
  void parallel_for(int n, const std::function<void(int)>& fn);

 private:
  struct State;
  int threads_ = 1;
  std::unique_ptr<State> state_;
};

}  // namespace glrc
