// The values of one channel in a band (Comparator::add_channel): the comparator's inner loop,
// run by run (channel_accumulator.hpp's kernels) where a run allows, pixel by pixel elsewhere.
#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "compare/comparator_state.hpp"
#include "compare/run_bounds.hpp"

namespace glrc::compare {

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
  constexpr int kRun = RunGrid::kRun;
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
  const RunGrid grid{reference.width, reference.height};
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
        const size_t run = grid.index(row, x / kRun);
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

}  // namespace glrc::compare
