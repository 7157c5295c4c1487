// Bounds of a deferred allowance over a run of pixels (internal to compare/): most of a run's
// pixels need no allowance of their own, only the certainty that it lies between two bounds
// (compare/README.md, "A deferred allowance"), found once per plain run of a channel.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "compare/compare.hpp"
#include "compare/run_grid.hpp"
#include "core/vector_clones.hpp"

namespace glrc::compare {

// How many samples ahead assume_floors and run_bounds ask for a sample's values to be fetched
// into the cache (__builtin_prefetch): far enough that they arrive before they are read.
inline constexpr size_t kPrefetchAhead = 8;

// The least and the largest of n finite floats, in loops the compiler vectorizes (eight
// partial extremes, each a selection that is one minps or maxps: a single running one is a
// chain of dependent instructions). false when a value is NaN or Inf. Inlined into each caller
// (run_range's copies).
[[gnu::always_inline]] inline bool value_range(const float* v, int n, float& lo, float& hi) {
  constexpr uint32_t kExponent = 0x7f800000u;
  uint32_t non_finite = 0;
  for (int j = 0; j < n; ++j)
    non_finite |= uint32_t((std::bit_cast<uint32_t>(v[j]) & kExponent) == kExponent);
  if (non_finite || n <= 0) return false;
  constexpr int kLanes = 8;
  float low[kLanes], high[kLanes];
  for (int l = 0; l < kLanes; ++l)
    low[l] = high[l] = v[0];
  int j = 0;
  for (; j + kLanes <= n; j += kLanes)
    for (int l = 0; l < kLanes; ++l) {
      low[l] = v[j + l] < low[l] ? v[j + l] : low[l];
      high[l] = high[l] < v[j + l] ? v[j + l] : high[l];
    }
  for (; j < n; ++j)
    low[0] = v[j] < low[0] ? v[j] : low[0], high[0] = high[0] < v[j] ? v[j] : high[0];
  lo = low[0], hi = high[0];
  for (int l = 1; l < kLanes; ++l)
    lo = low[l] < lo ? low[l] : lo, hi = hi < high[l] ? high[l] : hi;
  return true;
}

// value_range of a whole run: a count the compiler sees, and an AVX2 copy.
GLRC_VECTOR_CLONES bool run_range(const float* v, float& lo, float& hi);

// One plain run's bounds (ChannelBounds), for channel ch's values there: none where one is
// NaN or Inf.
void find_run_bounds(const DeferredAllowance& deferred, const Frame& reference, Channel ch,
                     int32_t p, int x, int row, Comparator::RunBounds& b);

// The ChannelBounds of a frame compared whole, for channel ch's deferred allowance: the bounds
// of one plain run in four (the others are found as they are compared, their values then in
// cache), and from them the largest allowance certainly in the channel: every plain run with
// finite bounds has its allowances counted in the channel's largest (all finite: every pixel's
// value is judged), so that is at least the largest lo of those.
Comparator::ChannelBounds run_bounds(const DeferredAllowance& deferred,
                                     const std::vector<int32_t>& plain_runs, const UlpTable& table,
                                     const Frame& reference, Channel ch);

// The least float not below a bound lo >= 0: an allowance that is a float at least lo is at
// least this one too.
inline float float_up(double lo) {
  float f = float(lo);
  if (double(f) < lo) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace glrc::compare
