// One channel's errors as the comparator gathers them (internal to compare/): its running
// figures (Tally), the largest values for the percentiles, the worst pixels, and the 64-pixel
// run kernels that add a run of a row at once, vectorized, with the same figures bit for bit
// as adding its pixels one by one.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "compare/largest_values.hpp"
#include "compare/rules.hpp"
#include "compare/run_grid.hpp"
#include "core/result.hpp"
#include "core/vector_clones.hpp"

namespace glrc::compare {

inline constexpr size_t kWorstPerChannel = 10;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The running figures of one channel: plain numbers, which a channel's loop keeps in a local
// copy (registers, where the accumulator's members would be stored and reloaded per pixel)
// and hands back after each slice. Every sum still runs in pixel order.
struct Tally {
  uint64_t compared = 0, differing = 0, over_tolerance = 0, non_finite = 0, finite = 0;
  double sum = 0, sum_sq = 0, max_abs = 0, max_ulps = 0, max_ratio = 0;
  double largest_allowance_ulps = 0;  // the largest allowance applied, ULPs
};

// One channel's errors, gathered over the pixels both frames cover with the same primitive.
struct ChannelAccumulator {
  ChannelStats stats;
  Tally tally;
  // The largest errors and shares of the allowance, enough of them for the percentiles; float
  // is ample for a statistic.
  explicit ChannelAccumulator(size_t most_compared) : ulps(most_compared), ratios(most_compared) {}
  LargestValues ulps, ratios;
  bool exact = false;  // exact mode: any differing bit is over
  // The kWorstPerChannel largest errors as a min-heap: memory does not grow with the frame.
  std::vector<WorstPixel> worst;

  static bool larger(const WorstPixel& a, const WorstPixel& b) {
    if (a.ratio != b.ratio) return a.ratio > b.ratio;
    if (a.ulps != b.ulps) return a.ulps > b.ulps;
    return a.y != b.y ? a.y < b.y : a.x < b.x;
  }

  // Where the expectation is NaN or Inf (spec and ulps modes) no value is wrong: not judged
  // (value_determined). The first such pixel where GL also gave NaN or Inf is kept: it makes a
  // case that otherwise passes outside what GL specifies, never a pass.
  std::optional<WorstPixel> undetermined_non_finite;

  // A pixel where the specification determines no value (value_determined): counted only.
  void add_undetermined(int x, int y, float reference, float gl, double allowed) {
    ++stats.undetermined;
    if (!std::isfinite(gl) && !undetermined_non_finite)
      undetermined_non_finite = WorstPixel{x, y, reference, gl, kInf, kInf, allowed, kInf};
  }

  // One compared pixel; `t` is the channel loop's local copy of `tally`. Always inlined: once
  // per pixel of the loop, whose two forms (with a deferred allowance and without) made GCC call
  // it instead (measured: the fan's comparison 20% slower).
  [[gnu::always_inline]] void add(Tally& t, int x, int y, float reference, float gl, double ulp,
                                  double inverse_ulp, double allowed) {
    const PixelError e = pixel_error(reference, gl, ulp, inverse_ulp);
    ++t.compared;
    const bool differs = std::bit_cast<uint32_t>(reference) != std::bit_cast<uint32_t>(gl);
    t.differing += differs;
    // NaN and Inf are over any tolerance, an infinite one included; in exact mode every bit
    // counts (-0 against +0 too).
    const bool over = exact ? differs : e.non_finite || !(e.abs_error <= allowed);
    t.over_tolerance += over;
    // GL's NaN never passes, even where the reference (a driver model) has the same NaN.
    t.non_finite += !std::isfinite(gl);
    if (std::isfinite(e.ulps)) {
      t.sum += e.ulps;
      t.sum_sq += e.ulps * e.ulps;
      ++t.finite;
    }
    t.max_abs = std::max(t.max_abs, e.abs_error);
    t.max_ulps = std::max(t.max_ulps, e.ulps);
    ulps.add(float(e.ulps));
    // The share of the allowance is divided out only where it can matter: a ratio LargestValues
    // certainly drops is below every ratio it keeps, and so below the largest and the worst
    // pixels' (LargestValues::certainly_dropped); it is only counted.
    if (ratios.certainly_dropped(e.abs_error, allowed)) {
      ratios.count_dropped();
      return;
    }
    t.max_ratio = std::max(t.max_ratio, keep_ratio(x, y, reference, gl, e, allowed));
  }

  // add() of a run of kRun pixels (x, y) ... (x + kRun - 1, y) of one primitive:
  // reference[j], gl[j], allowed[j] (`allowed` null: the fixed `fixed_allowed` for every pixel).
  // False, having changed nothing, when a value of the run is NaN or Inf: the caller adds it
  // pixel by pixel. The same figures, bit for bit, as add() of each pixel in turn: what does
  // not depend on the order (counts, maxima) over the whole run in loops without a branch, which
  // the vectorizer takes; the sums in pixel order; LargestValues fed pixel by pixel only where
  // one value of the run may be kept. A fixed count: GCC's -O2 vectorizes only loops that need
  // no remainder; and an AVX2 copy, which vectorizes the counts of double comparisons and the
  // maxima of 64-bit keys.
  static constexpr int kRun = RunGrid::kRun;
  GLRC_VECTOR_CLONES bool add_run(Tally& t, int x, int y, const float* reference, const float* gl,
                                  const float* allowed, double fixed_allowed, double ulp,
                                  double inverse_ulp);

  // add_run() of a run whose allowances are not known, only a bound `lo` below each of them
  // (DeferredAllowance::range; spec mode), as far as they change no figure: 0, with the figures
  // add_run() would give, when no error is above lo (so none is over); `largest_known`: no
  // allowance is above the largest the channel has, which the caller knows; and every share of
  // the allowance is one LargestValues certainly drops, since it does for the larger share
  // error/lo (below_drop_bound is monotone in the allowance). Else the lanes whose allowances
  // are needed, as bits: the others' decisions are the same for any allowance from lo up. Then
  // everything that does not depend on the allowance is added, and the other lanes' shares
  // counted as dropped: add_lanes() adds the rest once the caller has the lanes' allowances.
  // kEveryLane, having changed nothing, where that does not hold, for a run with NaN or Inf, and
  // where every lane is needed: add_run() then, given any allowance from lo up for the lanes
  // not needed.
  static constexpr uint64_t kEveryLane = ~uint64_t(0);
  GLRC_VECTOR_CLONES uint64_t add_run_within(Tally& t, const float* reference, const float* gl,
                                             double lo, bool largest_known, double ulp,
                                             double inverse_ulp);

  // The rest of add_run() of a run add_run_within() returned `lanes` for (neither 0 nor
  // kEveryLane), with allowed[j] each lane's allowance and `substitute` (a float from lo up)
  // the others': what depends on the allowance, as add_run() takes it (the largest allowance
  // over every lane, the lanes over it, their shares, these in add_run's order). Few lanes: one
  // by one.
  void add_lanes(Tally& t, int x, int y, const float* reference, const float* gl, uint64_t lanes,
                 const float* allowed, float substitute, double ulp, double inverse_ulp) {
    // add_run's maxima of allowance·(1/ulp) above 0: the substitute's where a lane holds it.
    const auto largest = [&](double allowance) {
      const double a = allowance * inverse_ulp;
      if (a > 0) t.largest_allowance_ulps = std::max(t.largest_allowance_ulps, a);
    };
    if (~lanes != 0) largest(double(substitute));
    for (uint64_t rest = lanes; rest != 0; rest &= rest - 1) {
      const int j = std::countr_zero(rest);
      const double allowance = double(allowed[j]);
      largest(allowance);
      const double abs_error = std::fabs(double(gl[j]) - double(reference[j]));
      t.over_tolerance += !(abs_error <= allowance);
      if (ratios.certainly_dropped(abs_error, allowance)) {
        ratios.count_dropped();
        continue;
      }
      const PixelError e{abs_error, inverse_ulp > 0 ? abs_error * inverse_ulp : abs_error / ulp,
                         false};
      t.max_ratio = std::max(t.max_ratio, keep_ratio(x + j, y, reference[j], gl[j], e, allowance));
    }
  }

  // A run's errors, as pixel_error's finite branch gives them (both values finite floats, so
  // their difference is exact in double, and the ulps finite): false when a value is NaN or
  // Inf. Inlined into each caller's copies.
  [[gnu::always_inline]] static bool run_errors(const float* reference, const float* gl, double ulp,
                                                double inverse_ulp, double* abs_error,
                                                double* ulps_of);

  // The figures of a run's errors that do not depend on the allowance: counts, maxima, sums in
  // pixel order, and the ulps' LargestValues (as add_run() feeds the ratios'). Inlined into
  // each caller's copies.
  [[gnu::always_inline]] void tally_errors(Tally& t, uint64_t differing, const double* abs_error,
                                           const double* ulps_of, double ulp, double inverse_ulp);

  // The share of the allowance of a pixel whose ratio LargestValues may keep, kept, and the
  // pixel among the worst if it is one of them. Out of line: after the first compaction few
  // pixels get here, and inlined into the channel's loop its registers would crowd out the
  // tally's.
  [[gnu::noinline]] double keep_ratio(int x, int y, float reference, float gl, const PixelError& e,
                                      double allowed) {
    const double ratio = e.abs_error == 0 ? 0.0 : allowed > 0 ? e.abs_error / allowed : kInf;
    ratios.add(float(ratio));
    if (e.ulps == 0) return ratio;
    const WorstPixel p{x, y, reference, gl, e.abs_error, e.ulps, allowed, ratio};
    if (worst.size() < kWorstPerChannel) {
      worst.push_back(p);
      std::push_heap(worst.begin(), worst.end(), larger);
    } else if (larger(p, worst.front())) {
      std::pop_heap(worst.begin(), worst.end(), larger);
      worst.back() = p;
      std::push_heap(worst.begin(), worst.end(), larger);
    }
    return ratio;
  }

  ChannelStats finish();
};

}  // namespace glrc::compare
