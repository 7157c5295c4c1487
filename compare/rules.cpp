#include "compare/rules.hpp"

#include <algorithm>

namespace glrc::compare {

double attribute_scale(const Case& c, int primitive, Channel ch) {
  if (ch.is_depth()) return 1.0;
  const auto [varying, i] = varying_component(c, ch.component());
  if (const Varying& v = c.varyings.at(varying); v.is_builtin()) {
    if (v.builtin == Builtin::front_facing || i == 2) return 1.0;
    if (i < 2) return i == 0 ? c.fb_width : c.fb_height;
    double scale = 0;
    for (uint32_t index : c.triangles.at(size_t(primitive)))
      scale = std::max(scale, 1 / std::fabs(double(c.vertices.at(index).clip[3])));
    return scale;
  }
  double scale = 0;
  for (uint32_t v : c.triangles.at(size_t(primitive)))
    scale = std::max(scale, std::fabs(double(c.vertices.at(v).values.at(size_t(ch.component())))));
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
      ulps_.push_back(ulp_of_scale(attribute_scale(c, int(t), Channel::component(k))));
  inverses_.reserve(ulps_.size());
  for (double ulp : ulps_)
    inverses_.push_back(1 / ulp);
}

ChannelAllowance::ChannelAllowance(const Case& c, const Expectation& expected,
                                   const Tolerance& tolerance, Channel channel) {
  if (tolerance.mode == ToleranceMode::exact) return;
  // In spec mode the allowance covers every pixel (add_rows checks its shape): every channel,
  // depth included, is judged by it, also in a case without varyings, whose allowance has no
  // components (the fixed depth ULPs judged those until a campaign found it).
  const AllowanceState state = expected.allowance_state();
  if (tolerance.mode == ToleranceMode::spec && state != AllowanceState::none) {
    const bool deferred = channel.is_depth() ? state == AllowanceState::all_deferred
                                             : state != AllowanceState::per_pixel;
    if (deferred) {
      deferred_ = expected.deferred;
      frame_ = &expected.frame, channel_ = channel;
      return;
    }
    per_pixel_ = &expected.allowed.values(channel);
    return;
  }
  const bool flat =
      !channel.is_depth() &&
      c.varyings.at(size_t(component_varying(c).at(size_t(channel.component())))).interpolation ==
          Interpolation::flat;
  fixed_ulps_ = channel.is_depth() ? tolerance.depth_ulps : flat ? 0.0 : tolerance.varying_ulps;
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

std::optional<CoverageStats::Label> coverage_label(uint8_t edges, bool counts,
                                                   const CoverageObservation& gl) {
  using Label = CoverageStats::Label;
  using Count = CoverageObservation::Count;
  using Kept = CoverageObservation::Kept;
  const bool differs = counts && gl.count != Count::same;
  // Where either fragment may win the depth test, GL may keep any of them.
  const bool kept =
      gl.kept == Kept::reference || (gl.kept == Kept::candidate && (edges & edge::depth_order));
  // Near a triangle the freedom may turn over, make vanish or make appear, any primitive and
  // any count is what some conforming implementation draws.
  if (edges & edge::unstable)
    return !kept || differs ? std::optional(Label::within_snapping) : std::nullopt;
  // Watertightness: away from outer edges, GL must rasterize as many fragments as the
  // reference; near a shared edge that is one, never zero or two. Both count every fragment,
  // passing the depth test or not (core/frame.hpp), so the count is decided even where the
  // depth test's order is free.
  if (differs && !(edges & edge::snapping)) {
    if (!(edges & edge::shared)) return Label::fill_rule;
    return gl.count == Count::fewer ? Label::gap : Label::double_hit;
  }
  if (kept) return std::nullopt;
  if (edges & edge::tie) return Label::exact_tie;
  if (edges & (edge::snapping | edge::shared)) return Label::within_snapping;
  return Label::fill_rule;
}

bool count_excused(uint8_t edges, bool counts, const std::optional<CoverageStats::Label>& label,
                   CoverageObservation::Count count) {
  if (!counts || !(edges & (edge::snapping | edge::unstable | edge::shared))) return false;
  // A mismatch the bands explain, or a count they leave free.
  if (label) return explained(*label);
  return count != CoverageObservation::Count::same;
}

CoverageStats::Label untraceable_label(uint8_t edges, CoverageObservation::Count count) {
  using Label = CoverageStats::Label;
  using Count = CoverageObservation::Count;
  if (!(edges & edge::shared) || count == Count::same) return Label::fill_rule;
  return count == Count::fewer ? Label::gap : Label::double_hit;
}

std::optional<CoverageStats::Label> coverage_verdict(uint8_t edges, bool counts,
                                                     const CoverageObservation& gl,
                                                     bool trace_admitted) {
  const std::optional<CoverageStats::Label> label = coverage_label(edges, counts, gl);
  if (trace_admitted || !count_excused(edges, counts, label, gl.count)) return label;
  return untraceable_label(edges, gl.count);
}

bool counts_against(CoverageStats::Label l, const Tolerance& t) {
  return !explained(l) || !t.allow_boundary || t.mode == ToleranceMode::exact;
}

bool counts_checked(const Expectation& expected, const Frame& gl) {
  return expected.frame.fragments.size() == expected.frame.pixel_count() &&
         gl.fragments.size() == gl.pixel_count();
}

CoverageObservation observe(const Expectation& expected, const Frame& gl, size_t i) {
  using Count = CoverageObservation::Count;
  using Kept = CoverageObservation::Kept;
  const Frame& reference = expected.frame;
  CoverageObservation o;
  // A candidate matters only where the depth order is free (coverage_label): looked for there
  // alone, since most pixels with another primitive have none.
  o.kept = reference.primitive[i] == gl.primitive[i] ? Kept::reference
           : (expected.edges[i] & edge::depth_order) && expected.candidate(i, gl.primitive[i])
               ? Kept::candidate
               : Kept::other;
  if (counts_checked(expected, gl)) {
    const uint16_t g = gl.fragments[i], r = reference.fragments[i];
    o.count = g == r ? Count::same : g < r ? Count::fewer : Count::more;
  }
  return o;
}

std::optional<CoverageStats::Label> coverage_label(const Expectation& expected, const Frame& gl,
                                                   size_t i) {
  return coverage_label(expected.edges[i], counts_checked(expected, gl), observe(expected, gl, i));
}

}  // namespace glrc::compare
