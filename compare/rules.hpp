// The per-pixel verdict rules: what is compared where (judged_against), how a coverage
// difference is labelled (coverage_label), what a channel allows (ChannelAllowance) and how an
// error is measured (ULPs of the attribute's scale). The comparator applies them to every
// pixel; report/ (heatmaps, coverage pictures), identify/ and the reproducers' data use the
// same ones, so that a pixel is judged one way everywhere.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"
#include "core/result.hpp"

namespace glrc::compare {

// The scale of channel ch at a pixel covered by triangle `primitive`: for component k the
// largest |v_i| of that triangle's three vertices; for the depth 1.0. A built-in's component
// has no vertex values: gl_FragCoord.x and .y the framebuffer's width and height, .z 1.0 as the
// depth, .w the largest 1/|w_c| of the three vertices, gl_FrontFacing 1.0. Errors are counted
// in ULPs of the scale. Flat components are held to 0 ULPs: they are copied, never computed.
double attribute_scale(const Case& c, int primitive, Channel ch);
// ulp of a positive scale: 2^(floor(log2 scale) - 23); 2^-149 (the subnormal spacing) for 0.
double ulp_of_scale(double scale);

// ulp_of_scale(attribute_scale(...)) for every triangle and component of a case, computed once
// instead of per pixel.
class UlpTable {
 public:
  explicit UlpTable(const Case& c);
  // No primitive (the clear value, a candidate of the depth test where nothing may be kept):
  // the depth's too, as nothing there is compared in ULPs.
  double ulp(int primitive, Channel ch) const {  // the depth's: 2^-23
    return ch.is_depth() || primitive < 0 ? depth_ulp_ : ulps_[index(primitive, ch)];
  }
  // 1 / ulp(primitive, ch), exact: every ulp is a power of two.
  double inverse_ulp(int primitive, Channel ch) const {
    return ch.is_depth() || primitive < 0 ? depth_inverse_ : inverses_[index(primitive, ch)];
  }

 private:
  size_t index(int primitive, Channel ch) const {
    return size_t(primitive) * size_t(components_) + size_t(ch.component());
  }
  int components_;
  double depth_ulp_, depth_inverse_;
  std::vector<double> ulps_, inverses_;
};

// What the verdict accepts in one channel (the depth or a component): per pixel, the
// largest |gl - reference| in value units. The specification's allowance where the expectation
// carries one and the tolerance is spec; a fixed number of ULPs of the attribute's scale in
// ulps mode (0 for flat values: they are copied, never computed); 0 in exact mode.
class ChannelAllowance {
 public:
  ChannelAllowance(const Case& c, const Expectation& expected, const Tolerance& tolerance,
                   Channel channel);
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
  Channel channel_ = Channel::depth();
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
  // The expected value of channel ch and the allowance there. Inline: once per compared pixel
  // and channel.
  float value(const Expectation& e, size_t i, Channel ch) const {
    return candidate ? candidate->value(ch) : e.frame.values(ch)[i];
  }
  double allowed(const ChannelAllowance& a, size_t i, double ulp, Channel ch) const {
    if (!candidate || !a.per_pixel()) return a.at(i, ulp);
    return candidate->allowance(ch);
  }
};
Judged judged_against(const Case& c, const Expectation& e, const Frame& gl, size_t i,
                      const Tolerance& tolerance);

// What GL did at one pixel, relative to what is expected there: all that the coverage verdict
// reads of GL. The rules below are functions of it and of the pixel's edge bits alone, so that
// the comparator and the reproducers (export/, which carry the verdict as a table of these)
// judge a pixel one way.
struct CoverageObservation {
  // GL's kept primitive: the reference's; another that Expectation::candidates lists there (a
  // fragment that may win the depth test); or any other, none included.
  enum class Kept : uint8_t { reference, candidate, other };
  // GL's fragment count against the reference's (both counted without the depth test); `same`
  // where either frame has no counts.
  enum class Count : uint8_t { same, fewer, more };
  Kept kept = Kept::reference;
  Count count = Count::same;
};
inline constexpr int kKeptKinds = 3, kCountKinds = 3;

// How a pixel's coverage disagrees with what is expected, or nothing where it does not: a
// different primitive is an exact tie, within snapping or a fill-rule error by the expected
// edge bits (GL may keep a candidate of the depth test where the depth order is free); a
// different fragment count (when both frames have counts: every fragment rasterized, through the
// depth test or not) away from outer edges is a gap or double hit near a shared edge, else a
// fill-rule error, where the depth order is free too.
//   edges:  the pixel's edge bits (core/frame.hpp, edge::);
//   counts: whether both frames have fragment counts.
std::optional<CoverageStats::Label> coverage_label(uint8_t edges, bool counts,
                                                   const CoverageObservation& gl);
// Whether a pixel's coverage differs from the reference's where its edge bits (a band, a
// shared edge, a triangle that may turn over) excuse it, both frames having counts: a
// mismatch coverage_label explains, or a count it leaves free (no label). The pixels a trace
// judges; a pixel where GL agrees (the same primitive and count) is not traced.
bool count_excused(uint8_t edges, bool counts, const std::optional<CoverageStats::Label>& label,
                   CoverageObservation::Count count);
// The label of a pixel whose coverage its edge bits excuse (count_excused), once its trace shows
// the fragments came from no set of triangles a conforming implementation may rasterize there:
// a gap or double hit near a shared edge (fewer or more fragments than the reference's), else
// (as many, from other triangles; or away from shared edges) a fill-rule error.
CoverageStats::Label untraceable_label(uint8_t edges, CoverageObservation::Count count);
// The whole coverage verdict at a pixel, as the comparator reaches it: coverage_label, then, for
// a pixel count_excused, untraceable_label unless GL's fragment trace there is one a conforming
// implementation may give (trace_admitted; true where no trace is known).
std::optional<CoverageStats::Label> coverage_verdict(uint8_t edges, bool counts,
                                                     const CoverageObservation& gl,
                                                     bool trace_admitted);
// Whether a mismatch labelled l counts against the verdict under tolerance t: always, unless
// the specification's freedom explains it and the case allows such differences (exact mode
// allows none).
bool counts_against(CoverageStats::Label l, const Tolerance& t);

// The observation at pixel i of `gl` against `expected` (both of one case).
CoverageObservation observe(const Expectation& expected, const Frame& gl, size_t i);
// Whether both frames have fragment counts (CoverageObservation::Count means something).
bool counts_checked(const Expectation& expected, const Frame& gl);
// coverage_label at pixel i of `gl` (report/'s coverage picture, the tests).
std::optional<CoverageStats::Label> coverage_label(const Expectation& expected, const Frame& gl,
                                                   size_t i);

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

}  // namespace glrc::compare
