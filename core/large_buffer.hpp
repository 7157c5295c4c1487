// Per-pixel buffers of large frames, filled without a page fault per 4 KiB: a 4096x4096 frame
// with 28 channels is 1.9 GB, and on a kernel that gives transparent huge pages only to memory
// that asks for them (/sys/kernel/mm/transparent_hugepage/enabled = madvise, common on VMs), the
// first touch of every 4 KiB page of it costs a fault. Measured on a 2-core VM: a 1000x1000
// case spent a fifth of its `run` in page faults. Only memory is affected, never a value.
#pragma once

#include <cstddef>
#include <vector>

namespace glrc {

// Asks the kernel to back [p, p + bytes) with huge pages where it can (madvise MADV_HUGEPAGE on
// the whole 2 MiB pages inside the range). Advice only: does nothing on a system without it, or
// for a range under 2 MiB, and never fails.
void advise_huge_pages(void* p, size_t bytes);

// v = n copies of `value`, the storage advised as above before it is first written. Existing
// capacity is reused as it is.
template <class T>
void assign_large(std::vector<T>& v, size_t n, const T& value) {
  if (v.capacity() < n) {
    std::vector<T>().swap(v);
    v.reserve(n);
    advise_huge_pages(v.data(), n * sizeof(T));
  }
  v.assign(n, value);
}

}  // namespace glrc
