#include "core/parallel.hpp"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace glrc {

int thread_count(int requested) {
  if (requested >= 1) return requested;
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

void parallel_for(int n, int threads, const std::function<void(int)>& fn) {
  if (n <= 0) return;
  if (threads <= 1 || n == 1) {
    for (int k = 0; k < n; ++k)
      fn(k);
    return;
  }
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_lock;
  auto work = [&] {
    for (int k; (k = next.fetch_add(1)) < n;) {
      try {
        fn(k);
      } catch (...) {
        const std::lock_guard hold(error_lock);
        if (!error) error = std::current_exception();
        next = n;  // the others stop after their current item
      }
    }
  };
  {
    std::vector<std::jthread> helpers;
    for (int t = 1; t < std::min(threads, n); ++t)
      helpers.emplace_back(work);
    work();
  }  // joined
  if (error) std::rethrow_exception(error);
}

}  // namespace glrc
