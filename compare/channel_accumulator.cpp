#include "compare/channel_accumulator.hpp"

namespace glrc::compare {

inline bool ChannelAccumulator::run_errors(const float* reference, const float* gl, double ulp,
                                           double inverse_ulp, double* abs_error, double* ulps_of) {
  constexpr int n = kRun;
  constexpr uint32_t kExponent = 0x7f800000u;
  uint32_t non_finite = 0;
  for (int j = 0; j < n; ++j)
    non_finite |= uint32_t((std::bit_cast<uint32_t>(reference[j]) & kExponent) == kExponent) |
                  uint32_t((std::bit_cast<uint32_t>(gl[j]) & kExponent) == kExponent);
  if (non_finite) return false;
  for (int j = 0; j < n; ++j)
    abs_error[j] = std::fabs(double(gl[j]) - double(reference[j]));
  if (inverse_ulp > 0)
    for (int j = 0; j < n; ++j)
      ulps_of[j] = abs_error[j] * inverse_ulp;
  else
    for (int j = 0; j < n; ++j)
      ulps_of[j] = abs_error[j] / ulp;
  return true;
}

inline void ChannelAccumulator::tally_errors(Tally& t, uint64_t differing, const double* abs_error,
                                             const double* ulps_of, double ulp,
                                             double inverse_ulp) {
  constexpr int n = kRun;
  int64_t max_abs = 0;
  for (int j = 0; j < n; ++j) {
    const int64_t e = std::bit_cast<int64_t>(abs_error[j]);
    max_abs = max_abs < e ? e : max_abs;
  }
  uint32_t keys[kRun], may_keep_ulps[kRun];
  const uint32_t ulps_floor = ulps.floor_key();
  for (int j = 0; j < n; ++j) {
    // order_key of a float that is +0 or above: never 0, so above a floor_key of 0.
    keys[j] = std::bit_cast<uint32_t>(float(ulps_of[j])) | 0x80000000u;
    may_keep_ulps[j] = keys[j] > ulps_floor;
  }
  uint32_t ulps_taken = 0;
  for (int j = 0; j < n; ++j)
    ulps_taken += may_keep_ulps[j];
  t.compared += uint64_t(n);
  t.differing += differing;
  t.finite += uint64_t(n);
  t.max_abs = std::max(t.max_abs, std::bit_cast<double>(max_abs));
  // The largest ulps is the largest error's: ·(1/ulp) and /ulp, rounded, are monotone.
  const double largest_error = std::bit_cast<double>(max_abs);
  t.max_ulps =
      std::max(t.max_ulps, inverse_ulp > 0 ? largest_error * inverse_ulp : largest_error / ulp);
  for (int j = 0; j < n; ++j) {
    t.sum += ulps_of[j];
    t.sum_sq += ulps_of[j] * ulps_of[j];
  }
  // In pixel order, as add() of each pixel offers them.
  ulps.count_dropped(size_t(n));
  if (ulps_taken > 0)
    for (int j = 0; j < n; ++j)
      if (may_keep_ulps[j]) ulps.offer(keys[j]);
}

GLRC_VECTOR_CLONES bool ChannelAccumulator::add_run(Tally& t, int x, int y, const float* reference,
                                                    const float* gl, const float* allowed,
                                                    double fixed_allowed, double ulp,
                                                    double inverse_ulp) {
  constexpr int n = kRun;
  double abs_error[kRun], ulps_of[kRun], allowed_of[kRun];
  if (!run_errors(reference, gl, ulp, inverse_ulp, abs_error, ulps_of)) return false;
  if (allowed)
    for (int j = 0; j < n; ++j)
      allowed_of[j] = double(allowed[j]);
  else
    std::fill(allowed_of, allowed_of + n, fixed_allowed);
  // One figure a loop, none with a branch: GCC vectorizes no other. Counts of double
  // comparisons in 64 bits (the comparisons' masks are 64-bit lanes); the maxima of doubles
  // that are +0 or above (or skipped, as std::max(m, x) skips a NaN, a negative and -0 when m
  // starts at +0) as the maxima of their bits as integers, which order them the same (a
  // maximum of doubles is vectorized only under -ffast-math).
  const uint64_t exact_mask = exact ? ~uint64_t(0) : 0;
  uint64_t differing = 0, over = 0;
  int64_t largest_allowance = 0;
  for (int j = 0; j < n; ++j)
    differing += std::bit_cast<uint32_t>(reference[j]) != std::bit_cast<uint32_t>(gl[j]);
  for (int j = 0; j < n; ++j)
    over += !(abs_error[j] <= allowed_of[j]);
  over = (differing & exact_mask) | (over & ~exact_mask);
  for (int j = 0; j < n; ++j) {
    const double allowance_ulps = allowed_of[j] * inverse_ulp;
    const int64_t a = allowance_ulps > 0 ? std::bit_cast<int64_t>(allowance_ulps) : 0;
    largest_allowance = largest_allowance < a ? a : largest_allowance;
  }
  // LargestValues' work is in the lanes whose values it may keep: at the 99th percentile a
  // run of 64 has one in about half the runs. Which lanes those are is found for every lane
  // at once, against the floors as they are now; a floor only rises (a value kept may
  // compact the kept ones), so a lane left out would be dropped later in the run too, and a
  // lane taken is tested again against the floor as it is when its turn comes.
  const bool ratios_droppable = ratios.may_drop();
  const double ratio_floor = ratios.floor_value();
  int64_t may_keep_ratio[kRun];
  const int64_t keeps_every_ratio = !ratios_droppable;
  for (int j = 0; j < n; ++j)
    may_keep_ratio[j] =
        int64_t(!LargestValues::below_drop_bound(abs_error[j], allowed_of[j], ratio_floor)) |
        keeps_every_ratio;
  uint64_t ratios_taken = 0;
  for (int j = 0; j < n; ++j)
    ratios_taken += uint64_t(may_keep_ratio[j]);
  t.largest_allowance_ulps =
      std::max(t.largest_allowance_ulps, std::bit_cast<double>(largest_allowance));
  t.over_tolerance += over;
  tally_errors(t, differing, abs_error, ulps_of, ulp, inverse_ulp);
  ratios.count_dropped(size_t(n) - ratios_taken);
  if (ratios_taken > 0)
    for (int j = 0; j < n; ++j) {
      if (!may_keep_ratio[j]) continue;
      if (ratios.certainly_dropped(abs_error[j], allowed_of[j])) {
        ratios.count_dropped();
        continue;
      }
      const PixelError pe{abs_error[j], ulps_of[j], false};
      t.max_ratio =
          std::max(t.max_ratio, keep_ratio(x + j, y, reference[j], gl[j], pe, allowed_of[j]));
    }
  return true;
}

GLRC_VECTOR_CLONES uint64_t ChannelAccumulator::add_run_within(Tally& t, const float* reference,
                                                               const float* gl, double lo,
                                                               bool largest_known, double ulp,
                                                               double inverse_ulp) {
  constexpr int n = kRun;
  static_assert(n == 64);
  if (exact || !largest_known || !ratios.may_drop()) return kEveryLane;
  double abs_error[kRun], ulps_of[kRun];
  if (!run_errors(reference, gl, ulp, inverse_ulp, abs_error, ulps_of)) return kEveryLane;
  const double ratio_floor = ratios.floor_value();
  int64_t needed[kRun];
  int64_t any = 0;
  for (int j = 0; j < n; ++j) {
    needed[j] = int64_t(!(abs_error[j] <= lo)) |
                int64_t(!LargestValues::below_drop_bound(abs_error[j], lo, ratio_floor));
    any |= needed[j];
  }
  uint64_t lanes = 0;
  if (any)
    for (int j = 0; j < n; ++j)
      lanes |= uint64_t(needed[j]) << j;
  // Every lane needed is kEveryLane's bits: that run is left to add_run() whole.
  if (lanes == kEveryLane) return kEveryLane;
  uint64_t differing = 0;
  for (int j = 0; j < n; ++j)
    differing += std::bit_cast<uint32_t>(reference[j]) != std::bit_cast<uint32_t>(gl[j]);
  tally_errors(t, differing, abs_error, ulps_of, ulp, inverse_ulp);
  ratios.count_dropped(size_t(n - std::popcount(lanes)));
  return lanes;
}

ChannelStats ChannelAccumulator::finish() {
  const Tally& t = tally;
  stats.compared = t.compared;
  stats.differing = t.differing;
  stats.over_tolerance = t.over_tolerance;
  stats.non_finite = t.non_finite;
  stats.max_abs = t.max_abs;
  stats.max_ulps = t.max_ulps;
  stats.max_ratio = t.max_ratio;
  // Mean and RMS over the finite errors; non-finite ones are counted in non_finite and make
  // max_ulps infinite, so they cannot hide.
  if (t.finite > 0) {
    stats.mean_ulps = t.sum / double(t.finite);
    stats.rms_ulps = std::sqrt(t.sum_sq / double(t.finite));
  }
  stats.p99_ulps = ulps.p99();
  stats.p99_ratio = ratios.p99();
  std::sort_heap(worst.begin(), worst.end(), larger);
  stats.worst = std::move(worst);
  return std::move(stats);
}

}  // namespace glrc::compare
