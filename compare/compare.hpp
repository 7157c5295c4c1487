// The comparator: per pixel, coverage and every value of a GL frame against the reference.
// Knows nothing of GL: two Frames in the same layout, the Case for the attribute scales.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "compare/largest_values.hpp"
#include "compare/rules.hpp"
#include "compare/run_grid.hpp"
#include "core/case.hpp"
#include "core/expectation.hpp"
#include "core/fragment_trace.hpp"
#include "core/result.hpp"

namespace glrc::compare {

// Where GL's coverage differs from the reference's at a pixel whose edge bits excuse it (the
// band of an outer edge or clip plane or of a shared edge, a triangle that may turn over), the
// count and the kept primitive alone cannot tell a free triangle's extra fragment from a double
// hit on an edge two other triangles share beside it: the fragment traces can
// (core/fragment_trace.hpp). What gives them for such pixels once every row is compared
// (Comparator::finish): GL's traces and the reference's choices at `pixels` (window indices
// x + y·width), in their order. A pixel whose GL trace is not known, whose count differs from
// the frame's, or whose choices admit no list (admitted()) stays excused, as without traces
// (CoverageStats::untraced).
struct TraceSource {
  std::function<std::vector<std::optional<FragmentTrace>>(const std::vector<size_t>& pixels)> gl;
  std::function<std::vector<FragmentChoices>(const std::vector<size_t>& pixels)> choices;
};
// At most this many such pixels are traced in a case; the rest stay excused (untraced).
inline constexpr size_t kMostTracedPixels = 100000;

// The fewest samples (one pixel of a plain run each) the floors of a channel's largest values are
// guessed from (Comparator::add_floor_sample, guess_floors): fewer say too little of the frame.
inline constexpr size_t kFewestFloorSamples = 4096;

// Judges a GL frame against what a correct implementation may produce. Spec tolerance needs
// expected.allowed; coverage mismatches are labelled from expected.edges; fragment counts are
// checked for watertightness where both frames have them, and with `traces`, where only the
// edge bits excuse a count, by which triangles GL's fragments came from. Sets status to pass or
// fail, or to skip for a failing case outside the range GL specifies (outside_specified_range,
// with the reason in the message), and fills the statistics. `threads`: how many judge the
// channels at once (0: every core the process may use); the result is the same for any number.
CaseResult compare(const Case& c, const Expectation& expected, const Frame& gl,
                   const Tolerance& tolerance, int threads = 1,
                   const TraceSource* traces = nullptr);

// The same comparison, slice of rows by slice of rows, so that neither frame need be held whole:
// the result of adding a frame's slices in order, top row of each following the last, is the
// result of compare() on the whole frames, field for field. Keeps the statistics, the worst
// pixels, the first coverage mismatches and a percent of each channel's errors (LargestValues),
// not the frames. c must outlive it.
class Comparator {
 public:
  // For frames of width × height pixels; `threads` as compare()'s.
  Comparator(const Case& c, const Tolerance& tolerance, int width, int height, int threads = 1);
  ~Comparator();
  Comparator(const Comparator&) = delete;
  Comparator& operator=(const Comparator&) = delete;
  // Rows [y0, y0 + expected.frame.height) of both frames: `expected` and `gl` hold only them
  // (frames that wide and that high; pixel indices, Candidate::pixel included, within the
  // slice). y0 must be the row after the previous slice's. Throws std::invalid_argument for slices
  // of another shape or out of order.
  void add_rows(const Expectation& expected, const Frame& gl, int y0);
  // For a frame compared slice by slice, before its first slice: the floors of each channel's
  // largest values guessed from a sample of its rows (as compare() guesses them from a sample of
  // its whole frame), so that values below them are dropped from the first slice on, not only
  // once as many as a percent of the frame's have been kept. add_floor_sample() takes a slice of
  // rows from anywhere in the frame (as add_rows() takes one, its allowance deferred or not),
  // keeping a sample of its values, not the slice; guess_floors() then assumes floors from
  // every slice sampled (none where too little of the sample is plain runs of one primitive).
  // The stream may not bear a guess out: then floors_held() is false after the last slice, and
  // finish() is not to be trusted: compare the slices again with a fresh Comparator without
  // guessing. Throws std::logic_error after the first slice, std::invalid_argument for a slice of
  // another shape.
  void add_floor_sample(const Expectation& expected, const Frame& gl);
  void guess_floors();
  // Whether every channel's largest values are those of every value added (always, unless
  // floors were guessed).
  bool floors_held() const;
  // The verdict and the statistics, as compare() gives them, the counts the edge bits excuse
  // judged by `traces` where given. Once.
  CaseResult finish(const TraceSource* traces = nullptr);

  // Bounds of a deferred allowance over a run of pixels of one row (DeferredAllowance::range).
  struct RunBounds {
    double lo = 0, hi = std::numeric_limits<double>::infinity();
    bool computed = false;  // lo and hi found (else none yet)
  };
  // A channel's RunBounds by plain run, and the largest allowance in ULPs that the channel
  // certainly has: the largest lo of a sample of plain runs whose allowances are all finite.
  struct ChannelBounds {
    std::vector<RunBounds> runs;
    double largest_lo = 0;
    // Whether no allowance up to hi, of ulp 1/inverse_ulp, can be the channel's largest (an
    // infinite hi can): below largest_lo strictly, since the run whose lo it is must not be
    // left out of the largest itself (it is when its hi is its lo), or not above 0 (an
    // allowance of 0 is never the largest counted).
    bool below_largest(double hi, double inverse_ulp) const {
      return hi * inverse_ulp < largest_lo || hi <= 0;
    }
  };

 private:
  // finish()'s judging of the pixels count_excused found, by `traces` (the rest untraced).
  void trace_excused(CoverageStats& cov, const TraceSource* traces);
  // add_rows' first pass: the slice's coverage, counted, and which of its pixels each channel's
  // pass compares, and against what (coverage_pass.cpp).
  void add_coverage(const Expectation& expected, const Frame& gl, int y0);
  // The values of channel ch in the slice add_rows is comparing.
  // `bounds`: for a component whose allowance is deferred, bounds of it over each of the slice's
  // plain runs (add_whole_channel), or none: every run's allowances are computed.
  void add_channel(const Expectation& expected, const Frame& gl, int y0, Channel ch,
                   ChannelBounds* bounds = nullptr);
  // add_channel(), for a frame compared whole (one slice) after the floors of its largest
  // values are guessed from a sample (LargestValues::assume_floor), and again without them
  // should the frame not bear them out.
  void add_whole_channel(const Expectation& expected, const Frame& gl, Channel ch);
  // add_channel() of a slice of a frame compared slice by slice: with a deferred allowance, bounds
  // of it over the slice's plain runs, as add_whole_channel finds them; no floors guessed from
  // the slice (guess_floors guesses them from sample slices).
  void add_slice_channel(const Expectation& expected, const Frame& gl, int y0, Channel ch);
  struct State;
  class CoveragePass;  // add_coverage's loop
  class ChannelPass;   // add_channel's loop (channel_pass.cpp)
  std::unique_ptr<State> state_;
};

}  // namespace glrc::compare
