#include "compare/run_bounds.hpp"

#include <algorithm>

namespace glrc::compare {

GLRC_VECTOR_CLONES bool run_range(const float* v, float& lo, float& hi) {
  return value_range(v, RunGrid::kRun, lo, hi);
}

void find_run_bounds(const DeferredAllowance& deferred, const Frame& reference, Channel ch,
                     int32_t p, int x, int row, Comparator::RunBounds& b) {
  constexpr int kRun = RunGrid::kRun;
  b.computed = true;
  float lo, hi;
  if (!run_range(reference.values(ch).data() + reference.index(x, row), lo, hi)) return;
  const auto range = deferred.range(ch, p, x, x + kRun - 1, row, lo, hi);
  b.lo = range[0], b.hi = range[1];
}

Comparator::ChannelBounds run_bounds(const DeferredAllowance& deferred,
                                     const std::vector<int32_t>& plain_runs, const UlpTable& table,
                                     const Frame& reference, Channel ch) {
  constexpr int kRun = RunGrid::kRun;
  constexpr int kSampledRuns = 4;
  const RunGrid grid{reference.width, reference.height};
  Comparator::ChannelBounds out;
  out.runs.resize(plain_runs.size());
  size_t plain = 0;
  struct Sampled {
    size_t run;
    int x, row;
  };
  std::vector<Sampled> sampled;
  for (int row = 0; row < reference.height; ++row)
    for (int r = 0; r < grid.whole_runs_per_row(); ++r) {
      const size_t run = grid.index(row, r);
      if (plain_runs[run] >= 0 && plain++ % kSampledRuns == 0)
        sampled.push_back({run, r * kRun, row});
    }
  const float* values = reference.values(ch).data();
  for (size_t s = 0; s < sampled.size(); ++s) {
    // The runs sampled are four apart: their values are in no cache line the processor
    // fetches ahead by itself (assume_floors' samples too).
    const Sampled& ahead = sampled[std::min(s + kPrefetchAhead, sampled.size() - 1)];
    for (int line = 0; line < kRun; line += 16)
      __builtin_prefetch(values + reference.index(ahead.x + line, ahead.row));
    const auto [run, x, row] = sampled[s];
    const int32_t p = plain_runs[run];
    Comparator::RunBounds& b = out.runs[run];
    find_run_bounds(deferred, reference, ch, p, x, row, b);
    if (b.hi < std::numeric_limits<double>::infinity())
      out.largest_lo = std::max(out.largest_lo, b.lo * table.inverse_ulp(p, ch));
  }
  return out;
}

}  // namespace glrc::compare
