// A JSON document whose memory is released all at once: ArenaJson, for a reader of large files.
// A large case is millions of small containers, and allocating and freeing each one on the heap
// cost about a tenth of its loading.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace glrc::typed_json {

// Memory handed out in blocks of 4 MiB (or one block of a larger request), freed together.
class Arena {
 public:
  void* take(size_t n, size_t align) {
    size_t at = (used_ + align - 1) & ~(align - 1);
    if (blocks_.empty() || at + n > size_) {
      size_ = std::max<size_t>(n, size_t(1) << 22);
      // Not make_unique, which zeroes the block: 4 MiB written for a case of a few hundred
      // bytes cost `list` and `digest` of one small case ~6 ms, a quarter of their start-up.
      // Untouched, the pages are never even mapped.
      blocks_.push_back(std::unique_ptr<std::byte[]>(new std::byte[size_]));
      at = 0;
    }
    used_ = at + n;
    return blocks_.back().get() + at;
  }

 private:
  std::vector<std::unique_ptr<std::byte[]>> blocks_;
  size_t size_ = 0, used_ = 0;
};

// The arena ArenaAllocator takes from on this thread, while an ArenaScope is open.
inline constinit thread_local Arena* open_arena = nullptr;

// nlohmann-json makes its allocators by default construction, so the arena is found through a
// thread-local: while one is open (ArenaScope), containers come from it and freeing them is a
// no-op; otherwise from the heap.
template <typename T>
struct ArenaAllocator {
  using value_type = T;
  ArenaAllocator() = default;
  template <typename U>
  ArenaAllocator(const ArenaAllocator<U>& /*other*/) {}
  T* allocate(size_t n) {
    return open_arena ? static_cast<T*>(open_arena->take(n * sizeof(T), alignof(T)))
                      : std::allocator<T>().allocate(n);
  }
  void deallocate(T* p, size_t n) {
    if (!open_arena) std::allocator<T>().deallocate(p, n);
  }
  template <typename U>
  bool operator==(const ArenaAllocator<U>& /*other*/) const {
    return true;
  }
};

// Opens an arena for this thread until the end of the scope. Every ArenaJson made inside must
// die inside it (declare the scope before the document); scopes do not nest.
class ArenaScope {
 public:
  ArenaScope() { open_arena = &arena_; }
  ~ArenaScope() { open_arena = nullptr; }
  ArenaScope(const ArenaScope&) = delete;
  ArenaScope& operator=(const ArenaScope&) = delete;

 private:
  Arena arena_;
};

using ArenaJson = nlohmann::basic_json<std::map, std::vector, std::string, bool, std::int64_t,
                                       std::uint64_t, double, ArenaAllocator>;

}  // namespace glrc::typed_json
