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

// Makes the kernel back [p, p + bytes) with memory now, in one call (madvise
// MADV_POPULATE_WRITE, Linux 5.14 and later), for memory about to be written whole: a buffer is
// not huge-page aligned (malloc places it), so the part of it outside whole huge pages is 4 KiB
// pages, and on a VM the fault taken at the first write of each costs more than the write
// (measured on a 2-core VM: 36 buffers of 4 MiB filled in 450-620 ms, 210-310 ms populated
// first). Advice only: nothing where the kernel cannot, never a change to any value.
void populate(void* p, size_t bytes);

// Keeps per-pixel buffers of a few MiB in the process's heap when they are freed, for the next
// slice or case to reuse: glibc's malloc maps each with mmap and unmaps it when freed (or trims
// it from the heap's top), so every page of the next one faults in again and is zeroed by the
// kernel (measured: two fifths of a streamed 2048x2048 case). With this, below 32 MiB they come
// from the heap, and up to 512 MiB freed at its top is kept. glibc's settings only: where the
// programs link jemalloc (GLRC_MALLOC, CMakeLists.txt), which keeps freed extents for reuse by
// itself, it does nothing. Call once, at the start of a process that checks cases (glrefcheck's
// main, so its workers too; the benchmarks, which time a case as a worker runs it).
void keep_freed_buffers();

// Makes v's storage ready for n elements, as assign_large and resize_large below need it:
// existing capacity is kept (a frame made again in a buffer a previous case used: its pages are
// in memory already), unless it is over twice n and over 1 MiB more: then it is given back
// first, so that a buffer kept for reuse holds at most about twice what it is used for. New
// storage is advised and populated as above before it is first written.
template <class T>
void reserve_large(std::vector<T>& v, size_t n) {
  if (v.capacity() / 2 > n && (v.capacity() - n) * sizeof(T) > (size_t(1) << 20))
    std::vector<T>().swap(v);
  if (v.capacity() < n) {
    std::vector<T>().swap(v);
    v.reserve(n);
    advise_huge_pages(v.data(), n * sizeof(T));
    populate(v.data(), n * sizeof(T));
  }
}

// v = n copies of `value`, in storage made ready by reserve_large.
template <class T>
void assign_large(std::vector<T>& v, size_t n, const T& value) {
  reserve_large(v, n);
  v.assign(n, value);
}

// v.resize(n), in storage made ready by reserve_large: the first elements keep whatever values
// they had (a shorter vector's new elements are value-initialized), so that a buffer its user
// writes whole anyway is not filled first.
template <class T>
void resize_large(std::vector<T>& v, size_t n) {
  reserve_large(v, n);
  v.resize(n);
}

}  // namespace glrc
