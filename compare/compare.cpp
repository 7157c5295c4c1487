// The comparator. Coverage first (which primitive covers each pixel), then, where both frames
// agree on the primitive, every varying component and depth, in ULPs of the attribute's scale.
#include "compare/compare.hpp"

#include "core/parallel.hpp"
#include "core/vector_clones.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>

namespace glrc::compare {
namespace {

constexpr size_t kWorstPerChannel = 10;
// Comparator::State::judgement's values.
constexpr uint8_t kNotCompared = 0, kOwn = 1, kCandidate = 2;
constexpr size_t kMismatchesKept = 64;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The running figures of one channel: plain numbers, which a channel's loop keeps in a local
// copy (registers, where the accumulator's members would be stored and reloaded per pixel)
// and hands back after each band. Every sum still runs in pixel order.
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
  static constexpr int kRun = 64;
  GLRC_VECTOR_CLONES bool add_run(Tally& t, int x, int y, const float* reference, const float* gl,
                                  const float* allowed, double fixed_allowed, double ulp,
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
                                                double* ulps_of) {
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

  // The figures of a run's errors that do not depend on the allowance: counts, maxima, sums in
  // pixel order, and the ulps' LargestValues (as add_run() feeds the ratios'). Inlined into
  // each caller's copies.
  [[gnu::always_inline]] void tally_errors(Tally& t, uint64_t differing, const double* abs_error,
                                           const double* ulps_of, double ulp, double inverse_ulp) {
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

  ChannelStats finish() {
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
};

std::string format_ulps(double u) {
  if (std::isinf(u)) return "inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", u);
  return buf;
}

// Why a case failed, in one line: the first failing channels and the coverage failures.
std::string failure_message(const CaseResult& r) {
  std::string msg;
  auto append = [&](const std::string& part) { msg += (msg.empty() ? "" : "; ") + part; };
  int listed = 0, more = 0;
  for (const auto& ch : r.channels) {
    if (ch.pass()) continue;
    if (listed == 3) {
      ++more;
      continue;
    }
    ++listed;
    std::string part = ch.name + ": ";
    if (ch.non_finite > 0) part += std::to_string(ch.non_finite) + " px NaN/Inf, ";
    if (r.tolerance.mode == ToleranceMode::exact)
      part += std::to_string(ch.differing) + " px differ (max " + format_ulps(ch.max_ulps) + " ulp";
    else if (r.tolerance.mode == ToleranceMode::spec)
      part += std::to_string(ch.over_tolerance) + " px over the allowance (max " +
              format_ulps(ch.max_ratio) + "x allowed, " + format_ulps(ch.max_ulps) + " ulp";
    else
      part += std::to_string(ch.over_tolerance) + " px over " + format_ulps(ch.tolerance_ulps) +
              " ulp (max " + format_ulps(ch.max_ulps) + " ulp";
    if (!ch.worst.empty())
      part += " at " + std::to_string(ch.worst[0].x) + "," + std::to_string(ch.worst[0].y);
    append(part + ")");
  }
  if (more > 0) append(std::to_string(more) + (more == 1 ? " more channel" : " more channels"));
  const CoverageStats& cov = r.coverage;
  if (cov.failures > 0) {
    std::string part = "coverage: " + std::to_string(cov.failures) + " px fail (";
    std::string kinds;
    // "1 gap on a shared edge", "2 gaps on shared edges".
    auto kind = [&](uint64_t n, const char* one, const char* many) {
      if (n) kinds += (kinds.empty() ? "" : ", ") + std::to_string(n) + " " + (n == 1 ? one : many);
    };
    kind(cov.fill_rule, "fill-rule error", "fill-rule errors");
    kind(cov.gaps, "gap on a shared edge", "gaps on shared edges");
    kind(cov.double_hits, "double hit on a shared edge", "double hits on shared edges");
    if (!r.tolerance.allow_boundary || r.tolerance.mode == ToleranceMode::exact) {
      kind(cov.exact_tie, "exact tie", "exact ties");
      kind(cov.within_snapping, "within snapping", "within snapping");
    }
    append(part + kinds + ")");
  }
  return msg;
}

// Why a case whose only trouble is a NaN or Inf where no value is determined is skipped.
std::string undetermined_message(const std::string& channel, const WorstPixel& p) {
  auto number = [](float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", double(v));
    return std::string(buf);
  };
  std::string why;
  if (std::isfinite(p.reference))
    why.append("the triangle reaches within rounding of the eye, where the w_c of a vertex ")
        .append("clipping makes may be 0: its values are unbounded");
  else
    why.append("the exact interpolation there is ")
        .append(number(p.reference))
        .append(": the pixel lies outside the triangle its plane comes from, beyond the plane's ")
        .append("vanishing line");
  return "outside what GL specifies: " + channel + " at " + std::to_string(p.x) + "," +
         std::to_string(p.y) + " has no value the specification determines (" + why +
         "), and GL drew " + number(p.gl) + " there; nothing else fails";
}

}  // namespace

double p99(const std::vector<float>& values) {
  LargestValues largest(values.size());
  for (float v : values)
    largest.add(v);
  return largest.p99();
}

LargestValues::LargestValues(size_t most) : keep_(most / 100 + 16) {}

void LargestValues::keep(uint32_t key) {
  keys_.push_back(key);
  if (keys_.size() >= 2 * keep_) compact();
}

void LargestValues::compact() {
  // The keep_ largest keys, the smallest of them last: everything not above it may go. Above
  // an assumed floor, every key kept is above it, and so is the new floor.
  std::nth_element(keys_.begin(), keys_.begin() + ptrdiff_t(keep_ - 1), keys_.end(),
                   std::greater<>());
  keys_.resize(keep_);
  floor_ = keys_.back();
  compacted_ = true;
  assumed_ = false;
  floor_value_ = float_of_order_key(floor_);
}

void LargestValues::assume_floor(uint32_t floor) {
  if (count_ > 0 || compacted_ || floor <= order_key(0.0f) ||
      floor >= order_key(std::numeric_limits<float>::infinity()))
    throw std::logic_error("LargestValues: a floor is assumed above 0, before any value");
  floor_ = floor;
  compacted_ = assumed_ = true;
  floor_value_ = float_of_order_key(floor_);
}

double LargestValues::p99() {
  if (count_ == 0) return 0;
  const size_t rank = size_t(std::ceil(0.99 * double(count_))) - 1;
  // The (count - rank)-th largest. Every value above floor_ is kept, and at least keep_ values
  // not below it, so the kept keys' j-th largest is the stream's for any j <= keep_.
  const size_t j = count_ - rank;
  if (j > keys_.size() || !complete())
    throw std::logic_error("LargestValues: kept too few values for p99");
  std::nth_element(keys_.begin(), keys_.begin() + ptrdiff_t(j - 1), keys_.end(), std::greater<>());
  return float_of_order_key(keys_[j - 1]);
}

double attribute_scale(const Case& c, int primitive, int component) {
  if (component < 0) return 1.0;
  double scale = 0;
  for (uint32_t v : c.triangles.at(size_t(primitive)))
    scale = std::max(scale, std::fabs(double(c.vertices.at(v).values.at(size_t(component)))));
  return scale;
}

double ulp_of_scale(double scale) {
  // The spacing of float32 values at the scale's binade; below the normal range the spacing is
  // that of subnormals, 2^-149.
  if (!(scale > 0) || !std::isfinite(scale)) return std::ldexp(1.0, -149);
  return std::ldexp(1.0, std::max(std::ilogb(scale) - 23, -149));
}

UlpTable::UlpTable(const Case& c)
    : components_(c.component_count()),
      depth_ulp_(ulp_of_scale(1.0)),
      depth_inverse_(1 / depth_ulp_) {
  ulps_.reserve(c.triangles.size() * size_t(components_));
  for (size_t t = 0; t < c.triangles.size(); ++t)
    for (int k = 0; k < components_; ++k)
      ulps_.push_back(ulp_of_scale(attribute_scale(c, int(t), k)));
  inverses_.reserve(ulps_.size());
  for (double ulp : ulps_)
    inverses_.push_back(1 / ulp);
}

ChannelAllowance::ChannelAllowance(const Case& c, const Expectation& expected,
                                   const Tolerance& tolerance, int channel) {
  const bool depth = channel == kDepth;
  if (tolerance.mode == ToleranceMode::exact) return;
  // In spec mode the allowance covers every pixel (add_rows checks its shape): every channel,
  // depth included, is judged by it, also in a case without varyings, whose allowance has no
  // components (the fixed depth ULPs judged those until a campaign found it).
  // A deferred allowance gives the components' allowances, and the depth's where it says so.
  const bool deferred_depth = expected.deferred && expected.deferred->depth();
  if (tolerance.mode == ToleranceMode::spec &&
      (deferred_depth || expected.allowed.depth.size() == expected.frame.pixel_count())) {
    static_assert(kDepth == DeferredAllowance::kDepth);
    if (depth ? deferred_depth : expected.deferred && expected.allowed.components.empty()) {
      deferred_ = expected.deferred;
      frame_ = &expected.frame, channel_ = channel;
      return;
    }
    per_pixel_ = depth ? &expected.allowed.depth : &expected.allowed.components.at(size_t(channel));
    return;
  }
  const bool flat =
      !depth && c.varyings.at(size_t(component_varying(c).at(size_t(channel)))).interpolation ==
                    Interpolation::flat;
  fixed_ulps_ = depth ? tolerance.depth_ulps : flat ? 0.0 : tolerance.varying_ulps;
}

PixelError pixel_error(float reference, float gl, double ulp) {
  return pixel_error(reference, gl, ulp, 0);
}

Judged judged_against(const Case& c, const Expectation& e, const Frame& gl, size_t i,
                      const Tolerance& tolerance) {
  const int32_t pr = e.frame.primitive[i], pg = gl.primitive[i];
  if (same_primitive(c, pr, pg)) return {true, nullptr};
  if (tolerance.mode == ToleranceMode::exact || pg < 0) return {};
  const Candidate* other = e.candidate(i, pg);
  return {other != nullptr, other};
}

std::optional<CoverageStats::Label> coverage_label(const Expectation& expected, const Frame& gl,
                                                   size_t i) {
  using Label = CoverageStats::Label;
  const Frame& reference = expected.frame;
  const uint8_t edges = expected.edges[i];
  // Watertightness: away from outer edges, GL must rasterize as many fragments as the
  // reference; near a shared edge that is one, never zero or two. Both count every fragment,
  // passing the depth test or not (core/frame.hpp), so the count is decided even where the
  // depth test's order is free.
  const bool counts = reference.fragments.size() == reference.pixel_count() &&
                      gl.fragments.size() == gl.pixel_count();
  // Where either fragment may win the depth test, GL may keep any of them.
  const bool kept = reference.primitive[i] == gl.primitive[i] ||
                    ((edges & edge::depth_order) && expected.candidate(i, gl.primitive[i]));
  // Near a triangle the freedom may turn over, make vanish or make appear, any primitive and
  // any count is what some conforming implementation draws.
  if (edges & edge::unstable) {
    const bool differs = !kept || (counts && gl.fragments[i] != reference.fragments[i]);
    return differs ? std::optional(Label::within_snapping) : std::nullopt;
  }
  if (counts && !(edges & edge::snapping) && gl.fragments[i] != reference.fragments[i]) {
    if (!(edges & edge::shared)) return Label::fill_rule;
    return gl.fragments[i] < reference.fragments[i] ? Label::gap : Label::double_hit;
  }
  if (kept) return std::nullopt;
  if (edges & edge::tie) return Label::exact_tie;
  if (edges & (edge::snapping | edge::shared)) return Label::within_snapping;
  return Label::fill_rule;
}

bool count_excused(const Expectation& expected, const Frame& gl, size_t i,
                   const std::optional<CoverageStats::Label>& label) {
  const Frame& reference = expected.frame;
  if (reference.fragments.size() != reference.pixel_count() ||
      gl.fragments.size() != gl.pixel_count() ||
      !(expected.edges[i] & (edge::snapping | edge::unstable | edge::shared)))
    return false;
  // A mismatch the bands explain, or a count they leave free.
  if (label) return explained(*label);
  return gl.fragments[i] != reference.fragments[i];
}

CoverageStats::Label untraceable_label(const Expectation& expected, const Frame& gl, size_t i) {
  using Label = CoverageStats::Label;
  const uint16_t g = gl.fragments[i], r = expected.frame.fragments[i];
  if (!(expected.edges[i] & edge::shared) || g == r) return Label::fill_rule;
  return g < r ? Label::gap : Label::double_hit;
}

// What a Comparator gathers between bands.
struct Comparator::State {
  State(const Case& the_case, const Tolerance& t, int w, int h, int threads_)
      : c(the_case), ulps(the_case), width(w), height(h), threads(threads_) {
    r.name = c.name;
    r.description = c.description;
    r.tolerance = t;
    r.coverage.fragments_checked = true;  // until a band without counts says otherwise
    const std::vector<std::string> names = component_names(c);
    for (int k = kDepth; k < int(names.size()); ++k) {
      ChannelAccumulator& acc = channels.emplace_back(size_t(w) * size_t(std::max(h, 0)));
      acc.exact = t.mode == ToleranceMode::exact;
      acc.stats.name = k == kDepth ? "depth" : names[size_t(k)];
    }
    fixed_ulps.assign(channels.size(), std::nullopt);
  }

  const Case& c;
  const UlpTable ulps;
  int width, height, next_row = 0;
  int threads;  // channels judged at once
  CaseResult r;
  std::vector<ChannelAccumulator> channels;       // depth, then each component
  std::vector<std::optional<double>> fixed_ulps;  // a channel's fixed allowance, if not per pixel
  // Per pixel of the band add_rows compares: whether its values are compared, and against the
  // reference's own fragment or a candidate (judged_against), found once for every channel.
  std::vector<uint8_t> judgement;
  // Per run of ChannelAccumulator::kRun pixels of each row of the band: the primitive when every
  // pixel of it is compared against the reference's own fragment of that primitive, else -1 (a
  // row's last, shorter run always: add_run takes whole runs). The same for every channel, so
  // found once.
  std::vector<int32_t> plain_runs;
  // Per run as plain_runs: 1 when every pixel of a whole run is compared against the reference's
  // own fragment, of whichever primitive (a plain run, or one where triangles meet), else 0.
  std::vector<uint8_t> own_runs;
  // add_floor_sample's keys by channel, and how many rows and plain runs they were taken from.
  std::vector<std::vector<uint32_t>> sampled_ulps, sampled_ratios;
  size_t sampled_rows = 0, sampled_plain = 0;
  bool floors_guessed = false;  // guess_floors() has run on a sample
  // The pixels count_excused found, for finish() to trace (at most kMostTracedPixels).
  struct Excused {
    size_t pixel = 0;  // window index
    CoverageStats::Pixel at;
    std::optional<CoverageStats::Label> label;  // coverage_label's
    CoverageStats::Label untraceable = CoverageStats::Label::fill_rule;
    uint16_t gl_fragments = 0;
  };
  std::vector<Excused> excused;
  uint64_t excused_beyond = 0;  // found beyond kMostTracedPixels
};

Comparator::Comparator(const Case& c, const Tolerance& tolerance, int width, int height,
                       int threads)
    : state_(std::make_unique<State>(c, tolerance, width, height, thread_count(threads))) {}

Comparator::~Comparator() = default;

namespace {

// Whether pixel i is one of those most of a frame is: the same drawn triangle in both frames,
// no edge bit, as many fragments (where both frames have counts). judged_against gives such a
// pixel the reference's own fragment and coverage_label nothing, which is all this says
// without calling either. Inlined into add_rows' loop over every pixel.
class PlainlyOwn {
 public:
  PlainlyOwn(const Case& c, const Expectation& expected, const Frame& gl)
      : expected_(expected),
        gl_(gl),
        // coverage_label's own test: these frames both have fragment counts.
        counts_(expected.frame.fragments.size() == expected.frame.pixel_count() &&
                gl.fragments.size() == gl.pixel_count()),
        triangles_(int32_t(std::min<size_t>(c.triangles.size(), INT32_MAX))) {}
  [[gnu::always_inline]] bool operator()(size_t i) const {
    const Frame& reference = expected_.frame;
    const int32_t p = reference.primitive[i];
    return p == gl_.primitive[i] && p >= 0 && p < triangles_ && expected_.edges[i] == 0 &&
           (!counts_ || reference.fragments[i] == gl_.fragments[i]);
  }

 private:
  const Expectation& expected_;
  const Frame& gl_;
  const bool counts_;
  const int32_t triangles_;
};

}  // namespace

void Comparator::add_rows(const Expectation& expected, const Frame& gl, int y0) {
  State& st = *state_;
  const Case& c = st.c;
  const Tolerance& tolerance = st.r.tolerance;
  const Frame& reference = expected.frame;
  const bool spec = tolerance.mode == ToleranceMode::spec;
  const bool exact = tolerance.mode == ToleranceMode::exact;
  if (reference.width != st.width || reference.width != gl.width || reference.height != gl.height ||
      y0 != st.next_row || reference.height < 0 || y0 + reference.height > st.height ||
      reference.components.size() != size_t(c.component_count()) ||
      reference.components.size() != gl.components.size() ||
      expected.edges.size() != reference.pixel_count() ||
      (spec && ((expected.allowed.components.size() != reference.components.size() &&
                 !(expected.deferred && expected.allowed.components.empty())) ||
                (expected.allowed.depth.size() != reference.pixel_count() &&
                 !(expected.deferred && expected.deferred->depth())))))
    throw std::invalid_argument("compare: frames of different shape for case " + c.name);
  // A deferred allowance knows the first row of the frame it drew: it must be this band's.
  if (expected.deferred && expected.deferred->first_row() != y0)
    throw std::invalid_argument("compare: a deferred allowance drawn for rows from " +
                                std::to_string(expected.deferred->first_row()) +
                                " compared as rows from " + std::to_string(y0) + ", for case " +
                                c.name);
  st.next_row += reference.height;

  // Coverage first, then the values where both frames name the same triangle (or GL a
  // candidate of the depth test), channel by channel. Which pixels those are is kept as one
  // byte per pixel of the band (Judgement), kept between bands; a candidate is looked up again
  // in each channel's pass (rare: only where the depth test's order is free).
  std::vector<uint8_t>& judgement = st.judgement;
  judgement.resize(reference.pixel_count());
  auto& cov = st.r.coverage;
  cov.fragments_checked = cov.fragments_checked &&
                          reference.fragments.size() == reference.pixel_count() &&
                          gl.fragments.size() == gl.pixel_count();
  using Label = CoverageStats::Label;
  // Blocks of rows on every thread, each counted apart and added in order: the counts are
  // sums, and the first mismatches kept are the first of the blocks' own first ones, in order.
  const int blocks = std::clamp(4 * st.threads, 1, std::max(reference.height, 1));
  std::vector<CoverageStats> part(static_cast<size_t>(blocks));
  std::vector<std::vector<State::Excused>> excused(static_cast<size_t>(blocks));
  constexpr int kRun = ChannelAccumulator::kRun;
  const int runs = (reference.width + kRun - 1) / kRun;
  st.plain_runs.assign(size_t(runs) * size_t(std::max(reference.height, 0)), -1);
  st.own_runs.assign(st.plain_runs.size(), 0);
  const PlainlyOwn plainly_own(c, expected, gl);
  parallel_for(blocks, st.threads, [&](int b) {
    CoverageStats& cv = part[size_t(b)];
    const int first = int(int64_t(reference.height) * b / blocks);
    const int end = int(int64_t(reference.height) * (b + 1) / blocks);
    for (int y = first; y < end; ++y) {
      for (int x = 0; x < reference.width; ++x) {
        const size_t i = reference.index(x, y);
        const int32_t pr = reference.primitive[i], pg = gl.primitive[i];
        if (plainly_own(i)) {
          judgement[i] = kOwn;
          ++cv.both;
          continue;
        }
        const Judged judged = judged_against(c, expected, gl, i, tolerance);
        judgement[i] = !judged.compared ? kNotCompared : judged.candidate ? kCandidate : kOwn;
        if (pr == pg && pr == Frame::kNoPrimitive) {
          ++cv.neither;
        } else if (judged.compared) {
          ++cv.both;
        } else if (pg == Frame::kNoPrimitive) {
          ++cv.reference_only;
        } else if (pr == Frame::kNoPrimitive) {
          ++cv.gl_only;
        } else {
          ++cv.other_primitive;
        }
        const std::optional<Label> label = coverage_label(expected, gl, i);
        if (count_excused(expected, gl, i, label))
          excused[size_t(b)].push_back({size_t(y0 + y) * size_t(st.width) + size_t(x),
                                        {x, y0 + y, pr, pg, label && explained(*label),
                                         label.value_or(Label::within_snapping)},
                                        label,
                                        untraceable_label(expected, gl, i),
                                        gl.fragments[i]});
        if (!label) continue;
        ++(*label == Label::exact_tie         ? cv.exact_tie
           : *label == Label::within_snapping ? cv.within_snapping
           : *label == Label::gap             ? cv.gaps
           : *label == Label::double_hit      ? cv.double_hits
                                              : cv.fill_rule);
        const bool free = explained(*label);
        if (free) ++cv.boundary;
        if (!free || !tolerance.allow_boundary || exact) ++cv.failures;
        if (cv.mismatches.size() < kMismatchesKept)
          cv.mismatches.push_back({x, y0 + y, pr, pg, free, *label});
      }
      // The row's plain runs, now that its judgement is known (whole runs only: add_run's).
      for (int r = 0; r < reference.width / kRun; ++r) {
        const size_t first_pixel = reference.index(r * kRun, y);
        const int32_t p = reference.primitive[first_pixel];
        bool own = true, plain = true;
        for (int j = 0; j < kRun; ++j) {
          own = own && judgement[first_pixel + size_t(j)] == kOwn;
          plain = plain && reference.primitive[first_pixel + size_t(j)] == p;
        }
        const size_t run = size_t(y) * size_t(runs) + size_t(r);
        st.own_runs[run] = uint8_t(own);
        if (own && plain) st.plain_runs[run] = p;
      }
    }
  });
  for (const CoverageStats& cv : part) {
    cov.neither += cv.neither, cov.both += cv.both, cov.reference_only += cv.reference_only;
    cov.gl_only += cv.gl_only, cov.other_primitive += cv.other_primitive;
    cov.exact_tie += cv.exact_tie, cov.within_snapping += cv.within_snapping;
    cov.gaps += cv.gaps, cov.double_hits += cv.double_hits, cov.fill_rule += cv.fill_rule;
    cov.boundary += cv.boundary, cov.failures += cv.failures;
    for (const CoverageStats::Pixel& m : cv.mismatches)
      if (cov.mismatches.size() < kMismatchesKept) cov.mismatches.push_back(m);
  }
  for (const std::vector<State::Excused>& list : excused)
    for (const State::Excused& e : list)
      if (st.excused.size() < kMostTracedPixels)
        st.excused.push_back(e);
      else
        ++st.excused_beyond;

  // Then the values, channel by channel (depth, then each component), each in pixel order. The
  // channels share nothing but what they read, so several threads take one each: every
  // channel's figures are the same bits for any number of threads.
  // A frame compared whole guesses its floors from itself, unless they were guessed from
  // sample bands already (a stream of one band).
  const bool whole = y0 == 0 && reference.height == st.height && !st.floors_guessed;
  parallel_for(int(st.channels.size()), st.threads, [&](int slot) {
    if (whole)
      add_whole_channel(expected, gl, slot - 1);
    else
      add_band_channel(expected, gl, y0, slot - 1);
  });
}

namespace {

// How many samples ahead assume_floors and run_bounds ask for a sample's values to be fetched
// into the cache (__builtin_prefetch): far enough that they arrive before they are read.
constexpr size_t kPrefetchAhead = 8;

// Below a sample's value at the share that should be kept, `margin` times what a compaction
// keeps (one and a half for a sample of the whole frame: with 4096 samples or more, the
// frame's share above it is within a few percent of the sample's), and strictly below it, so
// that a value many pixels share is kept rather than dropped: that share, for a frame of
// `pixels` pixels, `plain` of its runs plain, `sampled` of them sampled; none where plain runs
// are under half the frame (many small triangles: a sample of them would be a poor one, and
// their values rise little), or too few are sampled.
constexpr size_t kFewestFloorSamples = 4096;
std::optional<double> floor_share(const ChannelAccumulator& acc, double plain, double pixels,
                                  size_t sampled, double margin = 1.5) {
  constexpr int kRun = ChannelAccumulator::kRun;
  const double share = margin * double(acc.ulps.kept_after_compaction()) / (plain * kRun);
  if (plain * kRun * 2 < pixels || sampled < kFewestFloorSamples || share > 0.25)
    return std::nullopt;
  return share;
}

// The order keys of a sample of a frame's (or a band's) ulps and shares of the allowance, for
// guessing the floors of a channel's largest values: one pixel of each plain run (compared
// against the reference's own fragment of one primitive, as add_run takes them), at an offset
// that moves from run to run and row to row. With a deferred allowance, each sampled pixel's
// run's bound above it stands for it (`bounds`, as add_channel's): the ratios sampled are then
// no larger than the pixels' own, the floor guessed no higher (a lower one keeps more values,
// which complete() allows; what the figures are does not depend on the floor, only how many
// values are kept on the way). Appended to ulps and ratios.
void sample_floor_keys(const std::vector<int32_t>& plain_runs, const UlpTable& table,
                       const ChannelAllowance& allowance, const Frame& reference,
                       const float* gl_values, const float* own_values, int k,
                       const Comparator::ChannelBounds* bounds, std::vector<uint32_t>& ulps,
                       std::vector<uint32_t>& ratios) {
  constexpr int kSampledRuns = 4;  // run_bounds' sample too: one plain run in four
  constexpr int kRun = ChannelAccumulator::kRun;
  const int runs = (reference.width + kRun - 1) / kRun;
  // One pixel of each plain run, at an offset that moves from run to run; with bounds,
  // kSampledRuns neighbouring pixels of each run whose bounds run_bounds found (one in
  // kSampledRuns: as many pixels), each run's hi standing for the pixels' allowances.
  const int per_run = bounds ? kSampledRuns : 1;
  struct Sample {
    size_t run, first;
  };
  std::vector<Sample> samples;
  for (int row = 0; row < reference.height; ++row)
    for (int r = 0; r < reference.width / kRun; ++r) {
      const size_t run = size_t(row) * size_t(runs) + size_t(r);
      if (plain_runs[run] < 0 || (bounds && !bounds->runs[run].computed)) continue;
      samples.push_back(
          {run, reference.index(r * kRun + (row * 37 + r * 11) % (kRun - per_run + 1), row)});
    }
  const float* own_allowed = allowance.per_pixel_values();
  ulps.reserve(ulps.size() + samples.size() * size_t(per_run));
  ratios.reserve(ratios.size() + samples.size() * size_t(per_run));
  for (size_t s = 0; s < samples.size(); ++s) {
    {
      // A sample's pixels are a row or more from the last one's: in no cache line the
      // processor fetches ahead by itself (measured on the quad: without this, nine tenths of
      // the sampling's time was spent waiting for them).
      const size_t ahead = samples[std::min(s + kPrefetchAhead, samples.size() - 1)].first;
      __builtin_prefetch(gl_values + ahead);
      __builtin_prefetch(own_values + ahead);
      // The allowance held per pixel (not a deferred one's) is a third such line: the quad's
      // comparison against an allowance held per pixel (diff's) took 70.3-72.2 ms of CPU
      // without this, 67.1-69.0 ms with it.
      if (own_allowed) __builtin_prefetch(own_allowed + ahead);
    }
    const size_t run = samples[s].run, first = samples[s].first;
    const int32_t p = plain_runs[run];
    for (size_t i = first; i < first + size_t(per_run); ++i) {
      const float g = gl_values[i], v = own_values[i];
      if (!std::isfinite(g) || !std::isfinite(v)) continue;
      const double ulp = table.ulp(p, k);
      const double allowed = bounds ? bounds->runs[run].hi : allowance.at(i, ulp);
      const double abs_error = std::fabs(double(g) - double(v));
      ulps.push_back(order_key(float(abs_error * table.inverse_ulp(p, k))));
      ratios.push_back(order_key(float(abs_error == 0 ? 0.0
                                       : allowed > 0  ? abs_error / allowed
                                                      : kInf)));
    }
  }
}

// The floors of a channel's largest values (LargestValues::assume_floor) from the keys of a
// sample (sample_floor_keys) at `share` (floor_share); none from too few (non-finite values
// left out).
void assume_sampled_floors(ChannelAccumulator& acc, std::vector<uint32_t>& ulps,
                           std::vector<uint32_t>& ratios, double share) {
  if (ulps.size() < kFewestFloorSamples) return;
  const auto floor_of = [&](std::vector<uint32_t>& keys) -> std::optional<uint32_t> {
    const auto nth = keys.end() - ptrdiff_t(std::max(1.0, double(keys.size()) * share));
    std::nth_element(keys.begin(), nth, keys.end());
    uint32_t below = 0;
    for (auto it = keys.begin(); it != nth; ++it)
      if (*it < *nth) below = std::max(below, *it);
    if (below <= order_key(0.0f) || below >= order_key(std::numeric_limits<float>::infinity()))
      return std::nullopt;
    return below;
  };
  if (const auto floor = floor_of(ulps)) acc.ulps.assume_floor(*floor);
  if (const auto floor = floor_of(ratios)) acc.ratios.assume_floor(*floor);
}

// The floors of a channel's largest values guessed from a sample of a frame compared whole
// (sample_floor_keys, floor_share).
void assume_floors(ChannelAccumulator& acc, const std::vector<int32_t>& plain_runs,
                   const UlpTable& table, const ChannelAllowance& allowance, const Frame& reference,
                   const float* gl_values, const float* own_values, int k,
                   const Comparator::ChannelBounds* bounds) {
  const size_t plain =
      size_t(std::count_if(plain_runs.begin(), plain_runs.end(), [](int32_t p) { return p >= 0; }));
  const auto share = floor_share(acc, double(plain), double(reference.pixel_count()), plain);
  if (!share) return;
  std::vector<uint32_t> ulps, ratios;
  sample_floor_keys(plain_runs, table, allowance, reference, gl_values, own_values, k, bounds, ulps,
                    ratios);
  assume_sampled_floors(acc, ulps, ratios, *share);
}

}  // namespace

namespace {

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

// Channel k's values in frame f: kDepth's or a component's.
const float* channel_values(const Frame& f, int k) {
  return k == kDepth ? f.depth.data() : f.components[size_t(k)].data();
}

// value_range of a whole run: a count the compiler sees, and an AVX2 copy.
GLRC_VECTOR_CLONES bool run_range(const float* v, float& lo, float& hi) {
  return value_range(v, ChannelAccumulator::kRun, lo, hi);
}

// One plain run's bounds (ChannelBounds), for component k's values there: none where one is
// NaN or Inf.
void find_run_bounds(const DeferredAllowance& deferred, const Frame& reference, int k, int32_t p,
                     int x, int row, Comparator::RunBounds& b) {
  constexpr int kRun = ChannelAccumulator::kRun;
  b.computed = true;
  float lo, hi;
  if (!run_range(channel_values(reference, k) + reference.index(x, row), lo, hi)) return;
  const auto range = deferred.range(k, p, x, x + kRun - 1, row, lo, hi);
  b.lo = range[0], b.hi = range[1];
}

// The ChannelBounds of a frame compared whole, for component k's deferred allowance: the bounds
// of one plain run in four (the others are found as they are compared, their values then in
// cache), and from them the largest allowance certainly in the channel: every plain run with
// finite bounds has its allowances counted in the channel's largest (all finite: every pixel's
// value is judged), so that is at least the largest lo of those.
Comparator::ChannelBounds run_bounds(const DeferredAllowance& deferred,
                                     const std::vector<int32_t>& plain_runs, const UlpTable& table,
                                     const Frame& reference, int k) {
  constexpr int kRun = ChannelAccumulator::kRun;
  constexpr int kSampledRuns = 4;
  const int runs = (reference.width + kRun - 1) / kRun;
  Comparator::ChannelBounds out;
  out.runs.resize(plain_runs.size());
  size_t plain = 0;
  struct Sampled {
    size_t run;
    int x, row;
  };
  std::vector<Sampled> sampled;
  for (int row = 0; row < reference.height; ++row)
    for (int r = 0; r < reference.width / kRun; ++r) {
      const size_t run = size_t(row) * size_t(runs) + size_t(r);
      if (plain_runs[run] >= 0 && plain++ % kSampledRuns == 0)
        sampled.push_back({run, r * kRun, row});
    }
  const float* values = channel_values(reference, k);
  for (size_t s = 0; s < sampled.size(); ++s) {
    // The runs sampled are four apart: their values are in no cache line the processor
    // fetches ahead by itself (assume_floors' samples too).
    const Sampled& ahead = sampled[std::min(s + kPrefetchAhead, sampled.size() - 1)];
    for (int line = 0; line < kRun; line += 16)
      __builtin_prefetch(values + reference.index(ahead.x + line, ahead.row));
    const auto [run, x, row] = sampled[s];
    const int32_t p = plain_runs[run];
    Comparator::RunBounds& b = out.runs[run];
    find_run_bounds(deferred, reference, k, p, x, row, b);
    if (b.hi < kInf) out.largest_lo = std::max(out.largest_lo, b.lo * table.inverse_ulp(p, k));
  }
  return out;
}

// The least float not below a bound lo >= 0: an allowance that is a float at least lo is at
// least this one too.
float float_up(double lo) {
  float f = float(lo);
  if (double(f) < lo) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

void Comparator::add_whole_channel(const Expectation& expected, const Frame& gl, int k) {
  State& st = *state_;
  ChannelAccumulator& acc = st.channels[size_t(k + 1)];
  const ChannelAccumulator before = acc;
  const Frame& reference = expected.frame;
  const ChannelAllowance allowance(st.c, expected, st.r.tolerance, k);
  std::optional<ChannelBounds> bounds;
  if (const DeferredAllowance* deferred = allowance.deferred())
    bounds = run_bounds(*deferred, st.plain_runs, st.ulps, reference, k);
  ChannelBounds* known = bounds ? &*bounds : nullptr;
  assume_floors(acc, st.plain_runs, st.ulps, allowance, reference, channel_values(gl, k),
                channel_values(reference, k), k, known);
  add_channel(expected, gl, 0, k, known);
  if (acc.ulps.complete() && acc.ratios.complete()) return;
  acc = before;
  add_channel(expected, gl, 0, k, known);
}

void Comparator::add_band_channel(const Expectation& expected, const Frame& gl, int y0, int k) {
  State& st = *state_;
  const ChannelAllowance allowance(st.c, expected, st.r.tolerance, k);
  const DeferredAllowance* deferred = allowance.deferred();
  if (!deferred) return add_channel(expected, gl, y0, k);
  // The band's bounds as a whole frame's (run_bounds); the largest allowance the channel
  // certainly has is also the largest of the bands before (the tally's: it only grows). Its
  // floors are not guessed from the band: a band cannot be compared again should they not hold
  // (the caller may guess them from sample bands first: guess_floors).
  ChannelBounds bounds = run_bounds(*deferred, st.plain_runs, st.ulps, expected.frame, k);
  bounds.largest_lo =
      std::max(bounds.largest_lo, st.channels[size_t(k + 1)].tally.largest_allowance_ulps);
  add_channel(expected, gl, y0, k, &bounds);
}

void Comparator::add_channel(const Expectation& expected, const Frame& gl, int y0, int k,
                             ChannelBounds* bounds) {
  State& st = *state_;
  const Case& c = st.c;
  const Tolerance& tolerance = st.r.tolerance;
  const Frame& reference = expected.frame;
  const size_t slot = size_t(k + 1);
  ChannelAccumulator& acc = st.channels[slot];
  Tally t = acc.tally;
  const ChannelAllowance allowance(c, expected, tolerance, k);
  if (!allowance.per_pixel()) st.fixed_ulps[slot] = allowance.fixed_ulps();
  // The reference's own fragments (nearly every compared pixel) read through pointers taken
  // once: the loop's stores (the tally, LargestValues) could alias a vector's members, and its
  // data pointer would be loaded again at every pixel. A candidate goes through Judged.
  const float* gl_values = channel_values(gl, k);
  const float* own_values = channel_values(reference, k);
  const int32_t* own_primitive = reference.primitive.data();
  const uint8_t* judged_as = st.judgement.data();
  const float* own_allowed = allowance.per_pixel_values();
  const double fixed_ulps = allowance.fixed_ulps();
  // A deferred allowance: computed for a run where it is needed (run_allowed below), else only
  // bounded.
  const DeferredAllowance* deferred = allowance.deferred();
  constexpr int kRun = ChannelAccumulator::kRun;
  // The ulp of the last primitive seen: along a row it rarely changes.
  int32_t ulp_primitive = -1;
  double own_ulp = 0, own_inverse_ulp = 0;
  auto own_ulps = [&](int32_t primitive) {
    if (primitive == ulp_primitive) return;
    ulp_primitive = primitive;
    own_ulp = st.ulps.ulp(primitive, k);
    own_inverse_ulp = st.ulps.inverse_ulp(primitive, k);
  };
  // One pixel of row `row`, whatever it is judged against. `deferring`: std::true_type with a
  // deferred allowance (its run's in run_allowed), std::false_type otherwise, so that the loop
  // without one is compiled without its tests.
  // `run_allowed`: with a deferred allowance, its run's (from column run_x).
  auto add_pixel = [&](int x, int row, auto deferring, const float* run_allowed, int run_x) {
    const size_t i = reference.index(x, row);
    if (judged_as[i] == kNotCompared) return;
    const int y = y0 + row;
    double ulp, inverse_ulp, allowed;
    float value;
    if (judged_as[i] == kOwn) {
      own_ulps(own_primitive[i]);
      ulp = own_ulp, inverse_ulp = own_inverse_ulp;
      // ChannelAllowance::at
      if constexpr (decltype(deferring)::value)
        allowed = double(run_allowed[x - run_x]);
      else
        allowed = own_allowed ? double(own_allowed[i]) : fixed_ulps * ulp;
      value = own_values[i];
    } else {
      const Judged judged = judged_against(c, expected, gl, i, tolerance);
      const int32_t primitive = judged.primitive(expected, i);
      ulp = st.ulps.ulp(primitive, k);
      inverse_ulp = st.ulps.inverse_ulp(primitive, k);
      allowed = judged.allowed(allowance, i, ulp, k);
      value = judged.value(expected, i, k);
    }
    // Not judged, and its unbounded allowance is not one the verdict applied. Where the value
    // is finite but the specification's allowance unbounded (a triangle reaching the eye
    // within rounding, ref/freedom.hpp), any number passes, and NaN or Inf is not determined
    // either; a fixed threshold, however large, still fails NaN.
    if (!value_determined(value, tolerance) ||
        (tolerance.mode == ToleranceMode::spec && std::isinf(allowed) &&
         !std::isfinite(gl_values[i]))) {
      acc.add_undetermined(x, y, value, gl_values[i], allowed);
      return;
    }
    // allowed·(1/ulp) is allowed/ulp: ulps are powers of two (UlpTable::inverse_ulp).
    t.largest_allowance_ulps = std::max(t.largest_allowance_ulps, allowed * inverse_ulp);
    acc.add(t, x, y, value, gl_values[i], ulp, inverse_ulp, allowed);
  };
  // The run from pixel `first`, n pixels: run_allowed's lanes given as bits computed (the
  // others hold a float from their lo up, which decides nothing: add_run_within).
  auto deferred_lanes = [&](size_t first, int n, uint64_t lanes, float* run_allowed) {
    if (lanes == ChannelAccumulator::kEveryLane)
      return deferred->at(reference, k, first, n, run_allowed);
    // The lanes needed only (some lanes are only returned for a whole run, segment_lanes'): the
    // deferred allowance computes a block of them as fast as one, wherever they are in the run
    // (a run's lanes needed are about one in seven, seldom next to each other: blocks of eight
    // neighbours computed three times as many as needed).
    deferred->at_lanes(reference, k, first, lanes, run_allowed);
  };
  // A whole run of several primitives (or with candidates, or pixels not compared): bounds of
  // each stretch of one primitive's own fragments, and for each pixel whether they decide
  // nothing, as add_run_within finds for a plain run; the rest of run_allowed set as there. A
  // pixel whose decision needs its allowance, or any in doubt, is a lane returned; a pixel not
  // judged against the reference's own fragment needs none of the deferred allowance.
  auto segment_lanes = [&](int x, int row, size_t first, float* run_allowed) -> uint64_t {
    if (!acc.ratios.may_drop()) return ChannelAccumulator::kEveryLane;
    const double ratio_floor = acc.ratios.floor_value();
    uint64_t lanes = 0;
    for (int j = 0; j < kRun;) {
      const size_t i = first + size_t(j);
      if (judged_as[i] != kOwn) {
        run_allowed[j++] = 0.0f;
        continue;
      }
      const int32_t p = own_primitive[i];
      int end = j + 1;
      while (end < kRun && judged_as[first + size_t(end)] == kOwn &&
             own_primitive[first + size_t(end)] == p)
        ++end;
      float lo, hi;
      std::array<double, 2> range{0.0, kInf};
      if (value_range(own_values + i, end - j, lo, hi))
        range = deferred->range(k, p, x + j, x + end - 1, row, lo, hi);
      const bool largest_known = bounds->below_largest(range[1], st.ulps.inverse_ulp(p, k));
      const float substitute = float_up(range[0]);
      for (; j < end; ++j) {
        const size_t pixel = first + size_t(j);
        const float g = gl_values[pixel];
        const double abs_error = std::fabs(double(g) - double(own_values[pixel]));
        const bool decided = largest_known && std::isfinite(g) && abs_error <= range[0] &&
                             LargestValues::below_drop_bound(abs_error, range[0], ratio_floor);
        run_allowed[j] = substitute;
        lanes |= uint64_t(!decided) << j;
      }
    }
    return lanes;
  };
  // Whether the kRun primitives from `primitive` (each drawn) have this channel's ulp of the
  // first.
  const auto same_ulp = [&](const int32_t* primitive) {
    const double ulp = st.ulps.ulp(primitive[0], k);
    bool same = true;
    for (int j = 1; j < kRun; ++j)
      same = same && st.ulps.ulp(primitive[j], k) == ulp;
    return same;
  };
  const int runs = (reference.width + kRun - 1) / kRun;
  // Not inlined: each form a function of its own, whose registers the other's code does not
  // crowd (measured: the fan's comparison 12.5 ms with, 13.7 ms without).
  auto add_rows = [&](auto deferring) __attribute__((noinline)) {
    float run_allowed[kRun];  // with a deferred allowance: the run's, from column run_x
    int run_x = 0;
    for (int row = 0; row < reference.height; ++row)
      for (int x = 0; x < reference.width; x += kRun) {
        // Whole runs of pixels compared against the reference's own fragment of one primitive,
        // every value finite (nearly all of a frame): add_run, whose loops are vectorized. Any
        // other run (a row's last, shorter one too) pixel by pixel.
        const int n = std::min(kRun, reference.width - x);
        const size_t first = reference.index(x, row);
        const size_t run = size_t(row) * size_t(runs) + size_t(x / kRun);
        const int32_t run_primitive = st.plain_runs[run];
        const float* allowed = own_allowed ? own_allowed + first : nullptr;
        if constexpr (decltype(deferring)::value) {
          // Most runs need only bounds of their allowances; the others the allowances of some of
          // their pixels, or of all, computed here (deferred_lanes).
          uint64_t lanes = ChannelAccumulator::kEveryLane;
          if (run_primitive >= 0 && bounds) {
            own_ulps(run_primitive);
            RunBounds& b = bounds->runs[run];
            if (!b.computed) find_run_bounds(*deferred, reference, k, run_primitive, x, row, b);
            lanes = acc.add_run_within(t, own_values + first, gl_values + first, b.lo,
                                       bounds->below_largest(b.hi, own_inverse_ulp), own_ulp,
                                       own_inverse_ulp);
            if (lanes == 0) continue;
            if (lanes != ChannelAccumulator::kEveryLane) {
              deferred->at_lanes(reference, k, first, lanes, run_allowed);
              acc.add_lanes(t, x, y0 + row, own_values + first, gl_values + first, lanes,
                            run_allowed, float_up(b.lo), own_ulp, own_inverse_ulp);
              continue;
            }
          } else if (bounds && n == kRun) {
            lanes = segment_lanes(x, row, first, run_allowed);
          }
          deferred_lanes(first, n, lanes, run_allowed);
          run_x = x, allowed = run_allowed;
        }
        // A whole run of the reference's own fragments of several primitives (where triangles
        // meet: on the quad's diagonal, a run in sixteen) whose ulps in this channel are the
        // same: add_run takes it too, its figures depending on the primitive only through the
        // ulp (and the allowance, per pixel in `allowed`).
        const int32_t ulp_of_run = run_primitive >= 0 ? run_primitive
                                   : st.own_runs[run] && same_ulp(own_primitive + first)
                                       ? own_primitive[first]
                                       : -1;
        if (ulp_of_run >= 0) {
          own_ulps(ulp_of_run);
          if (acc.add_run(t, x, y0 + row, own_values + first, gl_values + first, allowed,
                          fixed_ulps * own_ulp, own_ulp, own_inverse_ulp))
            continue;
        }
        for (int j = 0; j < n; ++j)
          add_pixel(x + j, row, deferring, run_allowed, run_x);
      }
  };
  if (deferred)
    add_rows(std::true_type{});
  else
    add_rows(std::false_type{});
  acc.tally = t;
}

void Comparator::add_floor_sample(const Expectation& expected, const Frame& gl) {
  State& st = *state_;
  const Frame& reference = expected.frame;
  if (st.next_row != 0)
    throw std::logic_error("Comparator: a floor sample after the first band of " + st.c.name);
  if (reference.width != st.width || gl.width != st.width || gl.height != reference.height ||
      reference.height > st.height || gl.components.size() != reference.components.size() ||
      reference.components.size() != size_t(st.c.component_count()) ||
      expected.edges.size() != reference.pixel_count())
    throw std::invalid_argument("compare: a floor sample of another shape for case " + st.c.name);
  // Plain runs as add_rows finds most of them: every pixel plainly its own, of one primitive
  // (a pixel add_rows judges against the reference's own fragment by another way is only left
  // out of the sample).
  constexpr int kRun = ChannelAccumulator::kRun;
  const int runs = (reference.width + kRun - 1) / kRun;
  const PlainlyOwn plainly_own(st.c, expected, gl);
  std::vector<int32_t> plain(size_t(runs) * size_t(reference.height), -1);
  size_t plain_count = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int r = 0; r < reference.width / kRun; ++r) {
      const size_t first = reference.index(r * kRun, y);
      const int32_t p = reference.primitive[first];
      bool own = true;
      for (size_t i = first; own && i < first + kRun; ++i)
        own = reference.primitive[i] == p && plainly_own(i);
      if (!own) continue;
      plain[size_t(y) * size_t(runs) + size_t(r)] = p;
      ++plain_count;
    }
  st.sampled_rows += size_t(reference.height);
  st.sampled_plain += plain_count;
  st.sampled_ulps.resize(st.channels.size());
  st.sampled_ratios.resize(st.channels.size());
  parallel_for(int(st.channels.size()), st.threads, [&](int slot) {
    const int k = slot - 1;
    const ChannelAllowance allowance(st.c, expected, st.r.tolerance, k);
    std::optional<ChannelBounds> bounds;
    if (const DeferredAllowance* deferred = allowance.deferred())
      bounds = run_bounds(*deferred, plain, st.ulps, reference, k);
    sample_floor_keys(plain, st.ulps, allowance, reference, channel_values(gl, k),
                      channel_values(reference, k), k, bounds ? &*bounds : nullptr,
                      st.sampled_ulps[size_t(slot)], st.sampled_ratios[size_t(slot)]);
  });
}

void Comparator::guess_floors() {
  State& st = *state_;
  if (st.next_row != 0)
    throw std::logic_error("Comparator: floors guessed after the first band of " + st.c.name);
  if (st.sampled_rows > 0) {
    st.floors_guessed = true;
    // The frame's plain runs as the sample's share of them over its rows.
    const double plain = double(st.sampled_plain) * double(st.height) / double(st.sampled_rows);
    const double pixels = double(st.width) * double(st.height);
    // Twice what a compaction keeps, not one and a half times: sample bands are a few places
    // of the frame, not all of it, and where the largest errors gather in a few of its rows
    // they may be over- or under-represented (the 4096x4096 scene's v6.w with 32 bands of four
    // rows: its shares' floor guessed too high, and the stream compared twice).
    constexpr double kMargin = 2;
    parallel_for(int(st.channels.size()), st.threads, [&](int slot) {
      ChannelAccumulator& acc = st.channels[size_t(slot)];
      if (const auto share = floor_share(acc, plain, pixels, st.sampled_plain, kMargin))
        assume_sampled_floors(acc, st.sampled_ulps[size_t(slot)], st.sampled_ratios[size_t(slot)],
                              *share);
    });
  }
  st.sampled_ulps = {}, st.sampled_ratios = {};
  st.sampled_rows = st.sampled_plain = 0;
}

bool Comparator::floors_held() const {
  for (const ChannelAccumulator& acc : state_->channels)
    if (!acc.ulps.complete() || !acc.ratios.complete()) return false;
  return true;
}

namespace {

// Whether a mismatch labelled l counts against the verdict under tolerance t (add_rows' rule).
bool counts_against(CoverageStats::Label l, const Tolerance& t) {
  return !explained(l) || !t.allow_boundary || t.mode == ToleranceMode::exact;
}

// The counter of label l.
uint64_t& label_counter(CoverageStats& cov, CoverageStats::Label l) {
  using Label = CoverageStats::Label;
  return l == Label::exact_tie         ? cov.exact_tie
         : l == Label::within_snapping ? cov.within_snapping
         : l == Label::gap             ? cov.gaps
         : l == Label::double_hit      ? cov.double_hits
                                       : cov.fill_rule;
}

}  // namespace

void Comparator::trace_excused(CoverageStats& cov, const TraceSource* traces) {
  State& st = *state_;
  cov.counts_untraced += st.excused_beyond;
  if (st.excused.empty()) return;
  if (!traces || !traces->gl || !traces->choices) {
    cov.counts_untraced += st.excused.size();
    return;
  }
  std::vector<size_t> pixels;
  pixels.reserve(st.excused.size());
  for (const State::Excused& e : st.excused)
    pixels.push_back(e.pixel);
  const std::vector<std::optional<FragmentTrace>> gl = traces->gl(pixels);
  const std::vector<FragmentChoices> choices = traces->choices(pixels);
  if (gl.size() != pixels.size() || choices.size() != pixels.size())
    throw std::logic_error("compare: a trace source gave " + std::to_string(gl.size()) +
                           " traces and " + std::to_string(choices.size()) + " choices for " +
                           std::to_string(pixels.size()) + " pixels");
  const Tolerance& t = st.r.tolerance;
  for (size_t k = 0; k < pixels.size(); ++k) {
    const State::Excused& e = st.excused[k];
    // A trace of another count than the frame's is not this frame's (a fault planted in the
    // frame alone, or a pass that went wrong): not judged.
    const std::optional<std::vector<FragmentTrace>> allowed =
        gl[k] && gl[k]->count == e.gl_fragments ? admitted(choices[k]) : std::nullopt;
    if (!allowed) {
      ++cov.counts_untraced;
      continue;
    }
    ++cov.counts_traced;
    const auto key = [](const FragmentTrace& i) { return std::tie(i.count, i.id_sum, i.hash_sum); };
    if (std::binary_search(allowed->begin(), allowed->end(), *gl[k],
                           [&](const auto& a, const auto& b) { return key(a) < key(b); }))
      continue;
    // No conforming implementation rasterizes these fragments here: the count's own label.
    if (e.label) {
      --label_counter(cov, *e.label);
      if (explained(*e.label)) --cov.boundary;
      if (counts_against(*e.label, t)) --cov.failures;
    }
    ++label_counter(cov, e.untraceable);
    ++cov.failures;
    CoverageStats::Pixel at = e.at;
    at.label = e.untraceable, at.boundary = false;
    cov.traced_failures.push_back(at);
    const auto kept = std::find_if(cov.mismatches.begin(), cov.mismatches.end(),
                                   [&](const auto& m) { return m.x == at.x && m.y == at.y; });
    if (kept != cov.mismatches.end())
      *kept = at;
    else if (cov.mismatches.size() < kMismatchesKept)
      cov.mismatches.push_back(at);
  }
}

CaseResult Comparator::finish(const TraceSource* traces) {
  State& st = *state_;
  trace_excused(st.r.coverage, traces);
  CaseResult r = std::move(st.r);
  for (size_t slot = 0; slot < st.channels.size(); ++slot) {
    ChannelAccumulator& acc = st.channels[slot];
    acc.stats.tolerance_ulps =
        st.fixed_ulps[slot] ? *st.fixed_ulps[slot] : acc.tally.largest_allowance_ulps;
    r.channels.push_back(acc.finish());
  }
  const Case& c = st.c;
  const auto& cov = r.coverage;
  bool pass = cov.failures == 0;
  for (const auto& ch : r.channels)
    pass = pass && ch.pass();
  r.status = pass ? Status::pass : Status::fail;
  if (!pass) r.message = failure_message(r);
  // A NaN or Inf where the specification determines no value (value_determined) is no failure,
  // and no pass either.
  if (pass)
    for (size_t slot = 0; slot < st.channels.size(); ++slot)
      if (const auto& p = st.channels[slot].undetermined_non_finite) {
        r.status = Status::skip;
        r.message = undetermined_message(r.channels[slot].name, *p);
        break;
      }
  // Beyond the magnitudes GL guarantees, a difference is no failure of the implementation.
  if (const auto why = pass ? std::nullopt : outside_specified_range(c)) {
    r.status = Status::skip;
    r.message = "outside GL's specified range: " + *why + "; GL drew: " + r.message;
  }
  r.outcome = r.status;
  return r;
}

CaseResult compare(const Case& c, const Expectation& expected, const Frame& gl,
                   const Tolerance& tolerance, int threads, const TraceSource* traces) {
  Comparator comparator(c, tolerance, expected.frame.width, expected.frame.height, threads);
  comparator.add_rows(expected, gl, 0);
  return comparator.finish(traces);
}

}  // namespace glrc::compare
