// The grid of runs the comparator judges a slice of rows by: runs of kRun pixels of one row, a
// row's last run shorter where the width is not a multiple of kRun. The run kernels
// (channel_accumulator.hpp) take whole runs only; the per-run tables of a slice (which runs are
// plain, their allowance bounds) are indexed by it.
#pragma once

#include <cstddef>

namespace glrc::compare {

struct RunGrid {
  // 64: GCC's -O2 vectorizes only loops of a fixed count, and a run's lanes fit one uint64_t.
  static constexpr int kRun = 64;
  int width = 0, height = 0;  // the slice's, in pixels

  // Runs of a row, its last one shorter included.
  int runs_per_row() const { return (width + kRun - 1) / kRun; }
  // Runs of a row that are kRun pixels long.
  int whole_runs_per_row() const { return width / kRun; }
  // Runs of the slice.
  size_t count() const { return size_t(runs_per_row()) * size_t(height > 0 ? height : 0); }
  // Run r of `row` (from pixel (r·kRun, row)).
  size_t index(int row, int r) const { return size_t(row) * size_t(runs_per_row()) + size_t(r); }
};

}  // namespace glrc::compare
