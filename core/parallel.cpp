#include "core/parallel.hpp"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
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

struct ThreadPool::State {
  std::mutex lock;
  std::condition_variable wake, done;
  // The current call: its items, the next one to take, and the helpers still in it.
  const std::function<void(int)>* fn = nullptr;
  int n = 0;
  std::atomic<int> next{0};
  int busy = 0;
  uint64_t call = 0;  // counts the calls, so that a helper joins each one once
  bool stop = false;
  std::exception_ptr error;
  std::vector<std::jthread> helpers;

  // Takes items of the current call until none is left.
  void work() {
    for (int k; (k = next.fetch_add(1)) < n;) {
      try {
        (*fn)(k);
      } catch (...) {
        const std::lock_guard hold(lock);
        if (!error) error = std::current_exception();
        next = n;  // the others stop after their current item
      }
    }
  }

  void helper() {
    uint64_t seen = 0;
    for (;;) {
      {
        std::unique_lock hold(lock);
        wake.wait(hold, [&] { return stop || call != seen; });
        if (stop) return;
        seen = call;
      }
      work();
      const std::lock_guard hold(lock);
      if (--busy == 0) done.notify_one();
    }
  }
};

ThreadPool::ThreadPool(int threads)
    : threads_(thread_count(threads)), state_(std::make_unique<State>()) {
  for (int t = 1; t < threads_; ++t)
    state_->helpers.emplace_back([s = state_.get()] { s->helper(); });
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard hold(state_->lock);
    state_->stop = true;
  }
  state_->wake.notify_all();
  state_->helpers.clear();  // joined
}

void ThreadPool::parallel_for(int n, const std::function<void(int)>& fn) {
  if (n <= 0) return;
  State& s = *state_;
  if (threads_ <= 1 || n == 1) {
    for (int k = 0; k < n; ++k)
      fn(k);
    return;
  }
  {
    const std::lock_guard hold(s.lock);
    s.fn = &fn, s.n = n, s.next = 0, s.error = nullptr;
    s.busy = int(s.helpers.size());
    ++s.call;
  }
  s.wake.notify_all();
  s.work();
  std::unique_lock hold(s.lock);
  s.done.wait(hold, [&] { return s.busy == 0; });
  s.fn = nullptr;
  if (s.error) std::rethrow_exception(std::exchange(s.error, nullptr));
}

}  // namespace glrc
