// The values of one channel in a slice (Comparator::add_channel): the comparator's inner loop,
// run by run (channel_accumulator.hpp's kernels) where a run allows, pixel by pixel elsewhere.
#include <algorithm>
#include <array>
#include <cmath>

#include "compare/comparator_state.hpp"
#include "compare/run_bounds.hpp"

namespace glrc::compare {

// One pass over channel ch of a slice: what add_channel's loop reads, taken once, and the loop's
// steps. Lives for one add_channel call; its tally is the channel's, copied in and back out.
class Comparator::ChannelPass {
 public:
  ChannelPass(State& st, const Expectation& expected, const Frame& gl, int y0, Channel ch,
              ChannelBounds* bounds)
      : st_(st),
        expected_(expected),
        reference_(expected.frame),
        y0_(y0),
        channel_(ch),
        bounds_(bounds),
        acc_(st.channels[ch.slot()]),
        t_(acc_.tally),
        allowance_(st.c, expected, st.r.tolerance, ch),
        gl_(gl),
        gl_values_(gl.values(ch).data()),
        own_values_(reference_.values(ch).data()),
        own_primitive_(reference_.primitive.data()),
        judged_as_(st.judgement.data()),
        own_allowed_(allowance_.per_pixel_values()),
        fixed_ulps_(allowance_.fixed_ulps()),
        deferred_(allowance_.deferred()),
        grid_{reference_.width, reference_.height} {
    if (!allowance_.per_pixel()) st.fixed_ulps[ch.slot()] = fixed_ulps_;
  }

  void run() {
    if (deferred_)
      add_rows<true>();
    else
      add_rows<false>();
    acc_.tally = t_;
  }

 private:
  static constexpr int kRun = RunGrid::kRun;

  // The ulp of the last primitive seen: along a row it rarely changes.
  void own_ulps(int32_t primitive) {
    if (primitive == ulp_primitive_) return;
    ulp_primitive_ = primitive;
    own_ulp_ = st_.ulps.ulp(primitive, channel_);
    own_inverse_ulp_ = st_.ulps.inverse_ulp(primitive, channel_);
  }

  // Every run of every row. Deferring: with a deferred allowance (its run's in run_allowed), so
  // that the loop without one is compiled without its tests. Not inlined: each form a function
  // of its own, whose registers the other's code does not crowd (measured: the fan's comparison
  // 12.5 ms with, 13.7 ms without).
  template <bool kDeferring>
  [[gnu::noinline]] void add_rows() {
    float run_allowed[kRun];  // with a deferred allowance: the run's, from column run_x
    int run_x = 0;
    for (int row = 0; row < reference_.height; ++row)
      for (int x = 0; x < reference_.width; x += kRun) {
        // Whole runs of pixels compared against the reference's own fragment of one primitive,
        // every value finite (nearly all of a frame): add_run, whose loops are vectorized. Any
        // other run (a row's last, shorter one too) pixel by pixel.
        const int n = std::min(kRun, reference_.width - x);
        const size_t first = reference_.index(x, row);
        const size_t run = grid_.index(row, x / kRun);
        const int32_t run_primitive = st_.plain_runs[run];
        const float* allowed = own_allowed_ ? own_allowed_ + first : nullptr;
        if constexpr (kDeferring) {
          if (deferred_run(x, row, n, first, run, run_primitive, run_allowed)) continue;
          run_x = x, allowed = run_allowed;
        }
        // A whole run of the reference's own fragments of several primitives (where triangles
        // meet: on the quad's diagonal, a run in sixteen) whose ulps in this channel are the
        // same: add_run takes it too, its figures depending on the primitive only through the
        // ulp (and the allowance, per pixel in `allowed`).
        const int32_t ulp_of_run = run_primitive >= 0 ? run_primitive
                                   : st_.own_runs[run] && same_ulp(own_primitive_ + first)
                                       ? own_primitive_[first]
                                       : -1;
        if (ulp_of_run >= 0) {
          own_ulps(ulp_of_run);
          if (acc_.add_run(t_, x, y0_ + row, own_values_ + first, gl_values_ + first, allowed,
                           fixed_ulps_ * own_ulp_, own_ulp_, own_inverse_ulp_))
            continue;
        }
        for (int j = 0; j < n; ++j)
          add_pixel<kDeferring>(x + j, row, run_allowed, run_x);
      }
  }

  // With a deferred allowance, the run of n pixels from column x of `row` (pixel `first`, run
  // `run` of the grid): most runs need only bounds of their allowances, and are done here
  // (true); the others the allowances of some of their pixels, or of all, computed into
  // run_allowed for the caller to add them (false).
  bool deferred_run(int x, int row, int n, size_t first, size_t run, int32_t run_primitive,
                    float* run_allowed) {
    uint64_t lanes = ChannelAccumulator::kEveryLane;
    if (run_primitive >= 0 && bounds_) {
      own_ulps(run_primitive);
      RunBounds& b = bounds_->runs[run];
      if (!b.computed) find_run_bounds(*deferred_, reference_, channel_, run_primitive, x, row, b);
      lanes = acc_.add_run_within(t_, own_values_ + first, gl_values_ + first, b.lo,
                                  bounds_->below_largest(b.hi, own_inverse_ulp_), own_ulp_,
                                  own_inverse_ulp_);
      if (lanes == 0) return true;
      if (lanes != ChannelAccumulator::kEveryLane) {
        deferred_->at_lanes(reference_, channel_, first, lanes, run_allowed);
        acc_.add_lanes(t_, x, y0_ + row, own_values_ + first, gl_values_ + first, lanes,
                       run_allowed, float_up(b.lo), own_ulp_, own_inverse_ulp_);
        return true;
      }
    } else if (bounds_ && n == kRun) {
      lanes = segment_lanes(x, row, first, run_allowed);
    }
    deferred_lanes(first, n, lanes, run_allowed);
    return false;
  }

  // One pixel of row `row`, whatever it is judged against. `run_allowed`: with a deferred
  // allowance, its run's (from column run_x).
  template <bool kDeferring>
  void add_pixel(int x, int row, const float* run_allowed, int run_x) {
    const size_t i = reference_.index(x, row);
    if (judged_as_[i] == kNotCompared) return;
    const int y = y0_ + row;
    double ulp, inverse_ulp, allowed;
    float value;
    if (judged_as_[i] == kOwn) {
      own_ulps(own_primitive_[i]);
      ulp = own_ulp_, inverse_ulp = own_inverse_ulp_;
      // ChannelAllowance::at
      if constexpr (kDeferring)
        allowed = double(run_allowed[x - run_x]);
      else
        allowed = own_allowed_ ? double(own_allowed_[i]) : fixed_ulps_ * ulp;
      value = own_values_[i];
    } else {
      const Tolerance& tolerance = st_.r.tolerance;
      const Judged judged = judged_against(st_.c, expected_, gl_, i, tolerance);
      const int32_t primitive = judged.primitive(expected_, i);
      ulp = st_.ulps.ulp(primitive, channel_);
      inverse_ulp = st_.ulps.inverse_ulp(primitive, channel_);
      allowed = judged.allowed(allowance_, i, ulp, channel_);
      value = judged.value(expected_, i, channel_);
    }
    // Not judged, and its unbounded allowance is not one the verdict applied. Where the value
    // is finite but the specification's allowance unbounded (a triangle reaching the eye
    // within rounding, ref/freedom.hpp), any number passes, and NaN or Inf is not determined
    // either; a fixed threshold, however large, still fails NaN.
    const Tolerance& tolerance = st_.r.tolerance;
    if (!value_determined(value, tolerance) ||
        (tolerance.mode == ToleranceMode::spec && std::isinf(allowed) &&
         !std::isfinite(gl_values_[i]))) {
      acc_.add_undetermined(x, y, value, gl_values_[i], allowed);
      return;
    }
    // allowed·(1/ulp) is allowed/ulp: ulps are powers of two (UlpTable::inverse_ulp).
    t_.largest_allowance_ulps = std::max(t_.largest_allowance_ulps, allowed * inverse_ulp);
    acc_.add(t_, x, y, value, gl_values_[i], ulp, inverse_ulp, allowed);
  }

  // The run from pixel `first`, n pixels: run_allowed's lanes given as bits computed (the
  // others hold a float from their lo up, which decides nothing: add_run_within).
  void deferred_lanes(size_t first, int n, uint64_t lanes, float* run_allowed) const {
    if (lanes == ChannelAccumulator::kEveryLane)
      return deferred_->at(reference_, channel_, first, n, run_allowed);
    // The lanes needed only (some lanes are only returned for a whole run, segment_lanes'): the
    // deferred allowance computes a block of them as fast as one, wherever they are in the run
    // (a run's lanes needed are about one in seven, seldom next to each other: blocks of eight
    // neighbours computed three times as many as needed).
    deferred_->at_lanes(reference_, channel_, first, lanes, run_allowed);
  }

  // A whole run of several primitives (or with candidates, or pixels not compared): bounds of
  // each stretch of one primitive's own fragments, and for each pixel whether they decide
  // nothing, as add_run_within finds for a plain run; the rest of run_allowed set as there. A
  // pixel whose decision needs its allowance, or any in doubt, is a lane returned; a pixel not
  // judged against the reference's own fragment needs none of the deferred allowance.
  uint64_t segment_lanes(int x, int row, size_t first, float* run_allowed) const {
    if (!acc_.ratios.may_drop()) return ChannelAccumulator::kEveryLane;
    const double ratio_floor = acc_.ratios.floor_value();
    uint64_t lanes = 0;
    for (int j = 0; j < kRun;) {
      const size_t i = first + size_t(j);
      if (judged_as_[i] != kOwn) {
        run_allowed[j++] = 0.0f;
        continue;
      }
      const int32_t p = own_primitive_[i];
      int end = j + 1;
      while (end < kRun && judged_as_[first + size_t(end)] == kOwn &&
             own_primitive_[first + size_t(end)] == p)
        ++end;
      float lo, hi;
      std::array<double, 2> range{0.0, kInf};
      if (value_range(own_values_ + i, end - j, lo, hi))
        range = deferred_->range(channel_, p, x + j, x + end - 1, row, lo, hi);
      const bool largest_known =
          bounds_->below_largest(range[1], st_.ulps.inverse_ulp(p, channel_));
      const float substitute = float_up(range[0]);
      for (; j < end; ++j) {
        const size_t pixel = first + size_t(j);
        const float g = gl_values_[pixel];
        const double abs_error = std::fabs(double(g) - double(own_values_[pixel]));
        const bool decided = largest_known && std::isfinite(g) && abs_error <= range[0] &&
                             LargestValues::below_drop_bound(abs_error, range[0], ratio_floor);
        run_allowed[j] = substitute;
        lanes |= uint64_t(!decided) << j;
      }
    }
    return lanes;
  }

  // Whether the kRun primitives from `primitive` (each drawn) have this channel's ulp of the
  // first.
  bool same_ulp(const int32_t* primitive) const {
    const double ulp = st_.ulps.ulp(primitive[0], channel_);
    bool same = true;
    for (int j = 1; j < kRun; ++j)
      same = same && st_.ulps.ulp(primitive[j], channel_) == ulp;
    return same;
  }

  State& st_;
  const Expectation& expected_;
  const Frame& reference_;
  const int y0_;
  const Channel channel_;
  ChannelBounds* const bounds_;
  ChannelAccumulator& acc_;
  // The channel's tally, a copy: the loop's other stores could alias it.
  Tally t_;
  const ChannelAllowance allowance_;
  const Frame& gl_;
  // The reference's own fragments (nearly every compared pixel) read through pointers taken
  // once: the loop's stores (the tally, LargestValues) could alias a vector's members, and its
  // data pointer would be loaded again at every pixel. A candidate goes through Judged.
  const float* const gl_values_;
  const float* const own_values_;
  const int32_t* const own_primitive_;
  const uint8_t* const judged_as_;
  const float* const own_allowed_;
  const double fixed_ulps_;
  // A deferred allowance: computed for a run where it is needed (deferred_run), else only
  // bounded.
  const DeferredAllowance* const deferred_;
  const RunGrid grid_;
  int32_t ulp_primitive_ = -1;
  double own_ulp_ = 0, own_inverse_ulp_ = 0;
};

void Comparator::add_channel(const Expectation& expected, const Frame& gl, int y0, Channel ch,
                             ChannelBounds* bounds) {
  ChannelPass(*state_, expected, gl, y0, ch, bounds).run();
}

}  // namespace glrc::compare
