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

#include "core/case.hpp"
#include "core/fragment_trace.hpp"
#include "core/frame.hpp"
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

// The same comparison, band of rows by band of rows, so that neither frame need be held whole:
// the result of adding a frame's bands in order, top row of each following the last, is the
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
  // band). y0 must be the row after the previous band's. Throws std::invalid_argument for bands
  // of another shape or out of order.
  void add_rows(const Expectation& expected, const Frame& gl, int y0);
  // For a frame compared band by band, before its first band: the floors of each channel's
  // largest values guessed from a sample of its rows (as compare() guesses them from a sample of
  // its whole frame), so that values below them are dropped from the first band on, not only
  // once as many as a percent of the frame's have been kept. add_floor_sample() takes a band of
  // rows from anywhere in the frame (as add_rows() takes one, its allowance deferred or not),
  // keeping a sample of its values, not the band; guess_floors() then assumes floors from
  // every band sampled (none where too little of the sample is plain runs of one primitive).
  // The stream may not bear a guess out: then floors_held() is false after the last band, and
  // finish() is not to be trusted: compare the bands again with a fresh Comparator without
  // guessing. Throws std::logic_error after the first band, std::invalid_argument for a band of
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
  // The values of channel k (kDepth or a component) in the band add_rows is comparing.
  // `bounds`: for a component whose allowance is deferred, bounds of it over each of the band's
  // plain runs (add_whole_channel), or none: every run's allowances are computed.
  void add_channel(const Expectation& expected, const Frame& gl, int y0, int k,
                   ChannelBounds* bounds = nullptr);
  // add_channel(), for a frame compared whole (one band) after the floors of its largest
  // values are guessed from a sample (LargestValues::assume_floor), and again without them
  // should the frame not bear them out.
  void add_whole_channel(const Expectation& expected, const Frame& gl, int k);
  // add_channel() of a band of a frame compared band by band: with a deferred allowance, bounds
  // of it over the band's plain runs, as add_whole_channel finds them; no floors guessed from
  // the band (guess_floors guesses them from sample bands).
  void add_band_channel(const Expectation& expected, const Frame& gl, int y0, int k);
  struct State;
  std::unique_ptr<State> state_;
};

// The scale of component k at a pixel covered by triangle `primitive`: the largest |v_i| of
// that triangle's three vertices. Depth is component kDepth, of scale 1.0. Errors are counted in
// ULPs of the scale. Flat components are held to 0 ULPs: they are copied, never computed.
inline constexpr int kDepth = -1;
double attribute_scale(const Case& c, int primitive, int component);
// ulp of a positive scale: 2^(floor(log2 scale) - 23); 2^-149 (the subnormal spacing) for 0.
double ulp_of_scale(double scale);

// ulp_of_scale(attribute_scale(...)) for every triangle and component of a case, computed once
// instead of per pixel.
class UlpTable {
 public:
  explicit UlpTable(const Case& c);
  double ulp(int primitive, int component) const {  // component kDepth: 2^-23
    return component == kDepth ? depth_ulp_
                               : ulps_[size_t(primitive) * size_t(components_) + size_t(component)];
  }
  // 1 / ulp(primitive, component), exact: every ulp is a power of two.
  double inverse_ulp(int primitive, int component) const {
    return component == kDepth
               ? depth_inverse_
               : inverses_[size_t(primitive) * size_t(components_) + size_t(component)];
  }

 private:
  int components_;
  double depth_ulp_, depth_inverse_;
  std::vector<double> ulps_, inverses_;
};

// What the verdict accepts in one channel (compare::kDepth or a component): per pixel, the
// largest |gl - reference| in value units. The specification's allowance where the expectation
// carries one and the tolerance is spec; a fixed number of ULPs of the attribute's scale in
// ulps mode (0 for flat values: they are copied, never computed); 0 in exact mode.
class ChannelAllowance {
 public:
  ChannelAllowance(const Case& c, const Expectation& expected, const Tolerance& tolerance,
                   int channel);
  double at(size_t pixel, double ulp) const {
    if (deferred_) return double(deferred_->at(*frame_, channel_, pixel));
    return per_pixel_ ? double((*per_pixel_)[pixel]) : fixed_ulps_ * ulp;
  }
  // Whether the allowance is the specification's, per pixel (held, or deferred).
  bool per_pixel() const { return per_pixel_ != nullptr || deferred_ != nullptr; }
  // The per-pixel allowances held (at() of pixel i is element i), or nullptr when fixed or
  // deferred.
  const float* per_pixel_values() const { return per_pixel_ ? per_pixel_->data() : nullptr; }
  // A component's allowance computed where asked for (Expectation::deferred), or nullptr.
  const DeferredAllowance* deferred() const { return deferred_.get(); }
  double fixed_ulps() const { return fixed_ulps_; }

 private:
  const std::vector<float>* per_pixel_ = nullptr;
  std::shared_ptr<const DeferredAllowance> deferred_;
  const Frame* frame_ = nullptr;  // the expectation's, with deferred_
  int channel_ = 0;
  double fixed_ulps_ = 0;
};

// Whether the specification determines a value where the expectation is `expected`: always in
// exact mode (bits are bits, NaN included), else only where it is a finite number. The exact
// reference gives NaN where the interpolation formula is 0/0 and Inf where its value is beyond
// float32: at a pixel covered by the snapped triangle but outside the triangle whose plane it
// is evaluated on, beyond that plane's vanishing line (the denominator sum of lambda_i / w_i
// changes sign there). The allowance there is unbounded, and an implementation anchoring its
// planes at snapped vertices gets a finite value where one using unsnapped planes gets any: no
// value is wrong there, and none is judged. A NaN or Inf from GL there is still never a pass:
// the case is then outside what GL specifies (Comparator::finish).
inline bool value_determined(float expected, const Tolerance& tolerance) {
  return tolerance.mode == ToleranceMode::exact || std::isfinite(expected);
}

// Whether values are compared at a pixel: both frames name the same drawn triangle.
inline bool same_primitive(const Case& c, int32_t reference, int32_t gl) {
  return reference == gl && reference >= 0 && size_t(reference) < c.triangles.size();
}

// What GL's values at pixel i are judged against: the reference's own fragment where both name
// the same triangle, or, where GL kept another fragment that may win the depth test, that
// candidate (not in exact mode, which asks for the reference's bits); nothing to compare
// elsewhere.
struct Judged {
  bool compared = false;
  const Candidate* candidate = nullptr;  // nullptr: the reference's fragment
  int32_t primitive(const Expectation& e, size_t i) const {
    return candidate ? candidate->primitive : e.frame.primitive[i];
  }
  // The expected value of channel (kDepth or a component) and the allowance there. Inline:
  // once per compared pixel and channel.
  float value(const Expectation& e, size_t i, int channel) const {
    if (candidate) return channel == kDepth ? candidate->depth : candidate->values[size_t(channel)];
    return channel == kDepth ? e.frame.depth[i] : e.frame.components[size_t(channel)][i];
  }
  double allowed(const ChannelAllowance& a, size_t i, double ulp, int channel) const {
    if (!candidate || !a.per_pixel()) return a.at(i, ulp);
    return channel == kDepth ? candidate->allowed_depth : candidate->allowed[size_t(channel)];
  }
};
Judged judged_against(const Case& c, const Expectation& e, const Frame& gl, size_t i,
                      const Tolerance& tolerance);

// How pixel i's coverage disagrees with what is expected, or nothing where it does not: a
// different primitive is an exact tie, within snapping or a fill-rule error by the expected
// edge bits (GL may keep a candidate of the depth test where the depth order is free); a
// different fragment count (when both frames have counts: every fragment rasterized, through the
// depth test or not) away from outer edges is a gap or double hit near a shared edge, else a
// fill-rule error, where the depth order is free too.
std::optional<CoverageStats::Label> coverage_label(const Expectation& expected, const Frame& gl,
                                                   size_t i);
// The label of pixel i whose coverage its edge bits excuse (count_excused), once its trace shows
// the fragments came from no set of triangles a conforming implementation may rasterize there:
// a gap or double hit near a shared edge (fewer or more fragments than the reference's), else
// (as many, from other triangles; or away from shared edges) a fill-rule error.
CoverageStats::Label untraceable_label(const Expectation& expected, const Frame& gl, size_t i);
// Whether pixel i's coverage differs from the reference's where its edge bits (a band, a
// shared edge, a triangle that may turn over) excuse it, both frames having counts: a
// mismatch coverage_label explains, or a count it leaves free (no label). The pixels a trace
// judges; a pixel where GL agrees (the same primitive and count) is not traced.
bool count_excused(const Expectation& expected, const Frame& gl, size_t i,
                   const std::optional<CoverageStats::Label>& label);

// Labels that the specification's freedom explains (exact tie, within snapping).
inline bool explained(CoverageStats::Label l) {
  return l == CoverageStats::Label::exact_tie || l == CoverageStats::Label::within_snapping;
}

// The error at one compared pixel of one channel, as every report counts it.
struct PixelError {
  double abs_error = 0;     // |gl - reference| (exact: both are floats); +inf when not finite
  double ulps = 0;          // abs_error / ulp
  bool non_finite = false;  // GL gave NaN or Inf where the reference is finite
};
PixelError pixel_error(float reference, float gl, double ulp);
// The same for an ulp that is a power of two (as ulp_of_scale's are), given with its inverse:
// abs_error·(1/ulp) is then abs_error/ulp bit for bit, without a division per pixel and channel.
// inverse_ulp 0: not given, abs_error/ulp. Inline: once per compared pixel and channel.
inline PixelError pixel_error(float reference, float gl, double ulp, double inverse_ulp) {
  PixelError e;
  if (!std::isfinite(gl) && std::isfinite(reference)) {
    // Never a pass, however large the tolerance: the value is not a number at all.
    e.non_finite = true;
    e.abs_error = e.ulps = std::numeric_limits<double>::infinity();
  } else if (!std::isfinite(reference)) {
    // The reference is finite for every valid case; if it were not, only identical bits
    // could be called equal.
    const bool same = std::bit_cast<uint32_t>(gl) == std::bit_cast<uint32_t>(reference);
    e.abs_error = e.ulps = same ? 0 : std::numeric_limits<double>::infinity();
  } else {
    e.abs_error = std::fabs(double(gl) - double(reference));  // exact: both are floats
    e.ulps = inverse_ulp > 0 ? e.abs_error * inverse_ulp : e.abs_error / ulp;
  }
  return e;
}

// A float's bits as an unsigned key in the float's order: negatives below positives, -0 just
// below +0, a NaN above +infinity, so that every value has a place.
inline uint32_t order_key(float v) {
  const uint32_t bits = std::bit_cast<uint32_t>(v);
  return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}
inline float float_of_order_key(uint32_t key) {
  return std::bit_cast<float>(key & 0x80000000u ? key & 0x7fffffffu : ~key);
}

// The nearest-rank 99th percentile of `values` (the ChannelStats p99s): the element of rank
// ceil(0.99·n) - 1 in ascending order (order_key's order); 0 for no values.
double p99(const std::vector<float>& values);

// The p99 above of a stream of values, without holding the stream: for n values it is the
// (n - rank)-th largest, and n - rank <= n/100 + 1, so only the largest few are kept (at most
// 2·(most/100 + 16) for at most `most` values; those not above the smallest kept value once
// enough are kept are dropped as they come). Amortized constant time per value.
class LargestValues {
 public:
  explicit LargestValues(size_t most);
  void add(float v) {  // inline: once per compared value; most are dropped here
    ++count_;
    offer(order_key(v));
  }
  // add() in two parts, for a loop over many values: count_dropped(n) counts them, and offer()
  // of each value's order_key, in order, keeps it if add() would. offer() may be left out for
  // a key not above floor_key() (for a key above 0): add() drops it.
  void offer(uint32_t key) {
    if (compacted_ && key <= floor_) return;
    keep(key);
  }
  uint32_t floor_key() const { return compacted_ ? floor_ : 0; }
  // Whether add(float(a / b)) certainly drops the value, for a >= 0 and b > 0, without the
  // division: once compacted, when a < floor·b·(1 - 2^-20) as computed, so that a/b <
  // floor·(1 - 2^-22) and neither rounding, the division's nor float's, can carry it up to the
  // floor. Then the value is below every kept value, and below the keep_-th (at least the 16th)
  // largest value added so far: for a floor of a normal float > 0, every value kept was at
  // least floor·(1 - 2^-24) before its rounding to float. False (always for a NaN, an infinite
  // a or a zero b) says nothing: add it.
  bool certainly_dropped(double a, double b) const {
    return may_drop() && below_drop_bound(a, b, floor_value_);
  }
  // certainly_dropped(a, b) is may_drop() && below_drop_bound(a, b, floor_value()): apart, for
  // a loop over many values that tests the one once and the other without a branch.
  bool may_drop() const { return compacted_ && floor_value_ >= 0x1p-100; }
  double floor_value() const { return floor_value_; }
  static bool below_drop_bound(double a, double b, double floor_value) {
    return a < floor_value * b * (1 - 0x1p-20);
  }
  // Counts n values: dropped (certainly_dropped said so), or offered apart.
  void count_dropped(size_t n = 1) { count_ += n; }
  size_t count() const { return count_; }
  // Starts the stream as if it had been compacted to `floor` (an order_key above that of a
  // float > 0), before any value is added: values not above it are dropped from the first.
  // For a floor guessed from a sample of the stream (Comparator): in a stream whose values
  // rise (the errors of a frame growing from row to row), the floor of the largest values so
  // far climbs slowly, and until it reaches the stream's 99th percentile many values are kept
  // and selected among only to be dropped (measured on a 1024x1024 frame: 7% of its values
  // kept, 203 compactions). The stream may not bear the guess out: complete() says whether
  // it did.
  void assume_floor(uint32_t floor);
  // Whether what the kept values give is the stream's: p99(), and certainly_dropped()'s
  // promise that a value it drops is below the keep_ largest (the comparator's largest and
  // worst values rely on it). Always, unless a floor was assumed and no compaction happened
  // since: then only if at least keep_ values were kept, every value above the floor being
  // kept, and p99() reaching down to the (count - rank)-th largest, fewer than keep_.
  bool complete() const { return !assumed_ || keys_.size() >= keep_; }
  // How many of the largest values a compaction keeps (most / 100 + 16).
  size_t kept_after_compaction() const { return keep_; }
  // The nearest-rank 99th percentile of every value added; 0 for none. Requires complete().
  double p99();

 private:
  void keep(uint32_t key);  // out of line: it may grow or compact the keys
  void compact();

  size_t keep_, count_ = 0;
  std::vector<uint32_t> keys_;
  uint32_t floor_ = 0;
  double floor_value_ = 0;  // float_of_order_key(floor_)
  bool compacted_ = false;
  bool assumed_ = false;  // floor_ was assumed, and no compaction has happened since
};

}  // namespace glrc::compare
