// The comparator on hand-built frames: the reference frame is made up here, not rendered, so
// these tests check the comparator alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "compare/compare.hpp"

namespace glrc::compare {
namespace {

// One triangle with a smooth vec2 "uv" (scales 1.0 and 1000.0) and a flat float "id".
Case two_varyings_case() {
  Case c;
  c.name = "synthetic";
  c.fb_width = c.fb_height = 8;
  c.viewport = {0, 0, 8, 8};
  c.varyings = {{"uv", 2, Interpolation::smooth}, {"id", 1, Interpolation::flat}};
  c.vertices = {{{-1, -1, 0, 1}, {0.25f, -1000.0f, 7}},
                {{1, -1, 0, 1}, {1.0f, 10.0f, 7}},
                {{-1, 1, 0, 1}, {0.5f, 3.0f, 7}}};
  c.triangles = {{0, 1, 2}};
  return c;
}

// A frame with primitive 0 over the lower-left half (x + y < 8) and smooth-looking values.
Frame reference_frame(const Case& c) {
  Frame f(c.fb_width, c.fb_height, c.component_count());
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      if (x + y >= 8) continue;
      const size_t i = f.index(x, y);
      f.primitive[i] = 0;
      f.depth[i] = 0.5f + 0.01f * float(x);
      f.components[0][i] = 0.25f + 0.05f * float(y);
      f.components[1][i] = 100.0f * float(x) - 3.0f;
      f.components[2][i] = 7;
    }
  return f;
}

// Fixed thresholds of 64 and 16 ULPs: the tolerance most tests here reason in.
Tolerance ulps_tolerance() {
  Tolerance t;
  t.mode = ToleranceMode::ulps;
  return t;
}

Expectation expect(const Frame& reference, std::vector<uint8_t> edges, Frame allowed = Frame()) {
  return Expectation{reference, std::move(edges), std::move(allowed)};
}

const ChannelStats& channel(const CaseResult& r, const std::string& name) {
  for (const auto& ch : r.channels)
    if (ch.name == name) return ch;
  throw std::runtime_error("no channel " + name);
}

TEST(UlpOfScale, IsTheFloatSpacingAtTheScale) {
  EXPECT_EQ(ulp_of_scale(1.0), std::ldexp(1.0, -23));
  EXPECT_EQ(ulp_of_scale(1.5), std::ldexp(1.0, -23));
  EXPECT_EQ(ulp_of_scale(0.999), std::ldexp(1.0, -24));
  EXPECT_EQ(ulp_of_scale(1000.0), std::ldexp(1.0, 9 - 23));
  EXPECT_EQ(ulp_of_scale(1e-6), std::ldexp(1.0, -20 - 23));
  EXPECT_EQ(ulp_of_scale(0.0), std::ldexp(1.0, -149));
  EXPECT_EQ(ulp_of_scale(1e-44), std::ldexp(1.0, -149));  // subnormal range
}

TEST(AttributeScale, IsTheLargestMagnitudeAtTheTrianglesVertices) {
  const Case c = two_varyings_case();
  EXPECT_EQ(attribute_scale(c, 0, Channel::component(0)), 1.0);
  EXPECT_EQ(attribute_scale(c, 0, Channel::component(1)), 1000.0);
  EXPECT_EQ(attribute_scale(c, 0, Channel::depth()), 1.0);
}

TEST(Compare, IdenticalFramesPassWithZeroError) {
  const Case c = two_varyings_case();
  const Frame ref = reference_frame(c);
  const std::vector<uint8_t> band(ref.pixel_count(), 0);
  const CaseResult r = compare(c, expect(ref, band), ref, ulps_tolerance());
  EXPECT_EQ(r.status, Status::pass);
  EXPECT_EQ(r.coverage.both, 36u);
  EXPECT_EQ(r.coverage.neither, 28u);
  ASSERT_EQ(r.channels.size(), 4u);
  EXPECT_EQ(r.channels[0].name, "depth");
  EXPECT_EQ(r.channels[1].name, "uv.x");
  EXPECT_EQ(r.channels[3].name, "id.x");
  for (const auto& ch : r.channels) {
    EXPECT_EQ(ch.compared, 36u);
    EXPECT_EQ(ch.max_ulps, 0.0);
    EXPECT_TRUE(ch.worst.empty());
  }
  EXPECT_EQ(channel(r, "id.x").tolerance_ulps, 0.0);  // flat: exact
  EXPECT_EQ(channel(r, "uv.y").tolerance_ulps, 64.0);
}

TEST(Compare, CatchesOneInjectedErrorInOneComponentOfOnePixel) {
  const Case c = two_varyings_case();
  const Frame ref = reference_frame(c);
  Frame gl = ref;
  const size_t i = gl.index(2, 3);
  // 100 ULPs of uv.y's scale (1000: ulp 2^-14) added at one pixel.
  gl.components[1][i] += float(100 * std::ldexp(1.0, -14));
  const std::vector<uint8_t> band(ref.pixel_count(), 0);
  const CaseResult r = compare(c, expect(ref, band), gl, ulps_tolerance());
  EXPECT_EQ(r.status, Status::fail);
  const auto& uv_y = channel(r, "uv.y");
  EXPECT_EQ(uv_y.over_tolerance, 1u);
  EXPECT_EQ(uv_y.max_ulps, 100.0);
  ASSERT_FALSE(uv_y.worst.empty());
  EXPECT_EQ(uv_y.worst[0].x, 2);
  EXPECT_EQ(uv_y.worst[0].y, 3);
  EXPECT_EQ(uv_y.worst[0].reference, ref.components[1][i]);
  EXPECT_EQ(uv_y.worst[0].gl, gl.components[1][i]);
  EXPECT_EQ(channel(r, "uv.x").over_tolerance, 0u);
  EXPECT_EQ(channel(r, "depth").over_tolerance, 0u);
  EXPECT_NE(r.message.find("uv.y"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("2,3"), std::string::npos) << r.message;

  // Under a tolerance of 100 ULPs the same error passes; at 99 it does not.
  Tolerance loose = ulps_tolerance();
  loose.varying_ulps = 100;
  EXPECT_EQ(compare(c, expect(ref, band), gl, loose).status, Status::pass);
  loose.varying_ulps = 99;
  EXPECT_EQ(compare(c, expect(ref, band), gl, loose).status, Status::fail);
}

TEST(Compare, NaNOrInfInGLFailsUnderAnyTolerance) {
  const Case c = two_varyings_case();
  const Frame ref = reference_frame(c);
  const std::vector<uint8_t> band(ref.pixel_count(), 0);
  for (double tolerance : {1e300, std::numeric_limits<double>::infinity()}) {
    Tolerance huge = ulps_tolerance();
    huge.varying_ulps = huge.depth_ulps = tolerance;
    for (float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
      Frame gl = ref;
      gl.components[0][gl.index(1, 1)] = bad;
      gl.depth[gl.index(2, 2)] = bad;
      const CaseResult r = compare(c, expect(ref, band), gl, huge);
      EXPECT_EQ(r.status, Status::fail);
      EXPECT_EQ(channel(r, "uv.x").non_finite, 1u);
      EXPECT_EQ(channel(r, "uv.x").over_tolerance, 1u);
      EXPECT_FALSE(channel(r, "depth").pass());
      EXPECT_TRUE(std::isinf(channel(r, "uv.x").max_ulps));
      EXPECT_NE(r.message.find("NaN"), std::string::npos) << r.message;
    }
  }
}

TEST(Compare, FlatValuesMustBeExact) {
  const Case c = two_varyings_case();
  const Frame ref = reference_frame(c);
  Frame gl = ref;
  gl.components[2][gl.index(0, 0)] = std::nextafter(7.0f, 8.0f);
  const std::vector<uint8_t> band(ref.pixel_count(), 0);
  const CaseResult r = compare(c, expect(ref, band), gl, ulps_tolerance());
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(channel(r, "id.x").max_ulps, 1.0);
}

TEST(Compare, CoverageMismatchesAreClassifiedByTheEdgeBand) {
  const Case c = two_varyings_case();
  const Frame ref = reference_frame(c);
  Frame gl = ref;
  std::vector<uint8_t> band(ref.pixel_count(), 0);
  gl.primitive[gl.index(7, 1)] = 0;                    // GL covers a pixel the reference does not
  band[gl.index(7, 1)] = edge::snapping;               // ... next to an edge: boundary
  gl.primitive[gl.index(0, 0)] = Frame::kNoPrimitive;  // GL drops a pixel deep inside
  Tolerance t = ulps_tolerance();
  CaseResult r = compare(c, expect(ref, band), gl, t);
  EXPECT_EQ(r.coverage.gl_only, 1u);
  EXPECT_EQ(r.coverage.reference_only, 1u);
  EXPECT_EQ(r.coverage.boundary, 1u);
  EXPECT_EQ(r.coverage.failures, 1u);
  EXPECT_EQ(r.coverage.both, 35u);
  ASSERT_EQ(r.coverage.mismatches.size(), 2u);
  EXPECT_EQ(r.status, Status::fail);

  gl.primitive[gl.index(0, 0)] = 0;  // only the boundary pixel left: allowed by default
  r = compare(c, expect(ref, band), gl, t);
  EXPECT_EQ(r.status, Status::pass);
  EXPECT_EQ(r.coverage.boundary, 1u);
  t.allow_boundary = false;
  r = compare(c, expect(ref, band), gl, t);
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(r.coverage.failures, 1u);
}

TEST(Compare, StatisticsOverManyPixels) {
  const Case c = two_varyings_case();
  const Frame ref = reference_frame(c);
  Frame gl = ref;
  // Depth off by exactly 1 ULP of 1.0 (2^-23) on every covered pixel with x == 0 (8 of 36),
  // by 4 ULPs at one pixel.
  for (int y = 0; y < 8; ++y)
    gl.depth[gl.index(0, y)] += float(std::ldexp(1.0, -23));
  gl.depth[gl.index(1, 1)] += float(std::ldexp(4.0, -23));
  const std::vector<uint8_t> band(ref.pixel_count(), 0);
  const CaseResult r = compare(c, expect(ref, band), gl, ulps_tolerance());
  const auto& d = channel(r, "depth");
  EXPECT_EQ(d.max_ulps, 4.0);
  EXPECT_DOUBLE_EQ(d.mean_ulps, 12.0 / 36.0);
  EXPECT_DOUBLE_EQ(d.rms_ulps, std::sqrt(24.0 / 36.0));
  EXPECT_EQ(d.p99_ulps, 4.0);  // nearest rank 36 of 36
  EXPECT_EQ(d.worst.size(), 9u);
  EXPECT_EQ(d.worst[0].ulps, 4.0);
  EXPECT_EQ(r.status, Status::pass);
}

// A case without varyings has an allowance without components: its depth is still judged by the
// allowance, not by the fixed 16 ULPs (found by a fuzz campaign: llvmpipe's depth 21 ULPs off,
// where the allowance was 2e-3, failed).
TEST(Compare, DepthOfACaseWithoutVaryingsIsJudgedByTheAllowance) {
  Case c = two_varyings_case();
  c.varyings.clear();
  for (Vertex& v : c.vertices)
    v.values.clear();
  Frame ref = reference_frame(two_varyings_case());
  ref.components.clear();
  Frame allowed(ref.width, ref.height, 0);
  allowed.primitive = ref.primitive;
  for (float& d : allowed.depth)
    d = 1e-3f;
  const std::vector<uint8_t> band(ref.pixel_count(), 0);
  Frame gl = ref;
  gl.depth[gl.index(2, 2)] += 5e-4f;  // about 8,000 ULPs of 1.0, half the allowance
  CaseResult r = compare(c, expect(ref, band, allowed), gl, Tolerance{});
  EXPECT_EQ(r.status, Status::pass) << r.message;
  EXPECT_NEAR(channel(r, "depth").max_ratio, 0.5, 1e-3);
  gl.depth[gl.index(2, 2)] += 1e-3f;
  r = compare(c, expect(ref, band, allowed), gl, Tolerance{});
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_NEAR(channel(r, "depth").max_ratio, 1.5, 1e-3);
}

TEST(Compare, SpecToleranceIsThePerPixelAllowance) {
  const Case c = two_varyings_case();
  const Frame ref = reference_frame(c);
  Frame allowed(ref.width, ref.height, int(ref.components.size()));
  allowed.primitive = ref.primitive;
  // uv.x may be off by 1e-3 everywhere but at (1, 2), where by 1e-5; flat id by nothing.
  for (auto& v : allowed.components[0])
    v = 1e-3f;
  allowed.components[0][allowed.index(1, 2)] = 1e-5f;
  const std::vector<uint8_t> band(ref.pixel_count(), 0);
  Frame gl = ref;
  gl.components[0][gl.index(4, 1)] += 5e-4f;  // half of its allowance
  Tolerance spec;                             // the default
  CaseResult r = compare(c, expect(ref, band, allowed), gl, spec);
  EXPECT_EQ(r.status, Status::pass) << r.message;
  const auto& uv_x = channel(r, "uv.x");
  EXPECT_NEAR(uv_x.max_ratio, 0.5, 1e-3);
  EXPECT_NEAR(uv_x.p99_ratio, uv_x.max_ratio, 1e-6);  // nearest rank 36 of 36
  EXPECT_NEAR(uv_x.worst[0].allowed, 1e-3, 1e-9);

  gl.components[0][gl.index(1, 2)] += 2e-5f;  // twice its (small) allowance
  r = compare(c, expect(ref, band, allowed), gl, spec);
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(channel(r, "uv.x").over_tolerance, 1u);
  EXPECT_NEAR(channel(r, "uv.x").max_ratio, 2.0, 0.1);
  EXPECT_EQ(channel(r, "uv.x").worst[0].x, 1);
  EXPECT_NE(r.message.find("allowance"), std::string::npos) << r.message;

  // Spec mode without an allowance is a programming error, not a pass.
  EXPECT_THROW(compare(c, expect(ref, band), gl, spec), std::invalid_argument);
}

TEST(Compare, ExactToleranceCountsDifferingBitsAndNaNNeverPasses) {
  const Case c = two_varyings_case();
  Frame ref = reference_frame(c);
  const std::vector<uint8_t> band(ref.pixel_count(), 0);
  Tolerance exact;
  exact.mode = ToleranceMode::exact;
  Frame gl = ref;
  EXPECT_EQ(compare(c, expect(ref, band), gl, exact).status, Status::pass);
  gl.components[1][gl.index(3, 3)] = std::nextafter(gl.components[1][gl.index(3, 3)], 1e9f);
  CaseResult r = compare(c, expect(ref, band), gl, exact);
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(channel(r, "uv.y").differing, 1u);
  // The same NaN in both (a driver model reproducing a driver bug): no differing bit, and
  // still a failure.
  ref.components[0][ref.index(1, 1)] = std::numeric_limits<float>::quiet_NaN();
  gl = ref;
  r = compare(c, expect(ref, band), gl, exact);
  EXPECT_EQ(channel(r, "uv.x").differing, 0u);
  EXPECT_EQ(channel(r, "uv.x").non_finite, 1u);
  EXPECT_EQ(r.status, Status::fail);
}

TEST(Compare, CoverageLabelsAndWatertightness) {
  const Case c = two_varyings_case();
  Frame ref = reference_frame(c);
  ref.fragments.assign(ref.pixel_count(), 0);
  for (size_t i = 0; i < ref.pixel_count(); ++i)
    ref.fragments[i] = ref.primitive[i] >= 0;
  std::vector<uint8_t> band(ref.pixel_count(), 0);
  band[ref.index(7, 1)] = edge::snapping | edge::tie;  // on an outer edge
  band[ref.index(6, 1)] = edge::snapping;              // near an outer edge
  band[ref.index(3, 3)] = edge::shared;                // near a shared edge
  band[ref.index(2, 3)] = edge::shared | edge::tie;    // on a shared edge
  Frame gl = ref;
  auto set = [&gl](int x, int y, int32_t primitive, uint16_t fragments) {
    gl.primitive[gl.index(x, y)] = primitive;
    gl.fragments[gl.index(x, y)] = fragments;
  };
  set(7, 1, 0, 1);                    // GL covers the tie centre: exact tie
  set(6, 1, Frame::kNoPrimitive, 0);  // GL leaves the near-edge centre out: within snapping
  set(3, 3, Frame::kNoPrimitive, 0);  // a hole next to a shared edge: gap
  set(2, 3, 0, 2);                    // the shared-edge centre drawn twice: double hit
  set(0, 5, Frame::kNoPrimitive, 0);  // far from every edge: fill-rule error
  const Tolerance t = ulps_tolerance();
  const CaseResult r = compare(c, expect(ref, band), gl, t);
  EXPECT_TRUE(r.coverage.fragments_checked);
  EXPECT_EQ(r.coverage.exact_tie, 1u);
  EXPECT_EQ(r.coverage.within_snapping, 1u);
  EXPECT_EQ(r.coverage.gaps, 1u);
  EXPECT_EQ(r.coverage.double_hits, 1u);
  EXPECT_EQ(r.coverage.fill_rule, 1u);
  EXPECT_EQ(r.coverage.failures, 3u);
  EXPECT_EQ(r.status, Status::fail);
  // One of each, in the singular.
  EXPECT_NE(r.message.find("coverage: 3 px fail (1 fill-rule error, 1 gap on a shared edge, 1 "
                           "double hit on a shared edge)"),
            std::string::npos)
      << r.message;
  EXPECT_EQ(coverage_label(expect(ref, band), gl, ref.index(3, 3)), CoverageStats::Label::gap);
  EXPECT_EQ(coverage_label(expect(ref, band), gl, ref.index(1, 1)), std::nullopt);
}

// A count the edge bits excuse (an outer edge's band) judged by the fragment traces: GL's
// fragments from a set the choices admit pass, from another set fail with the count's own label;
// without a trace (or one of another count than the frame's) the count stays excused.
TEST(Compare, TracesJudgeTheCountsTheBandsExcuse) {
  const Case c = two_varyings_case();
  Frame ref = reference_frame(c);
  ref.fragments.assign(ref.pixel_count(), 0);
  for (size_t i = 0; i < ref.pixel_count(); ++i)
    ref.fragments[i] = ref.primitive[i] >= 0;
  std::vector<uint8_t> band(ref.pixel_count(), 0);
  // Near an outer edge of a third triangle (5) and an edge triangles 0 and 1 share.
  const size_t i = ref.index(3, 3);
  band[i] = edge::snapping | edge::shared;
  ref.primitive[i] = 0, ref.fragments[i] = 1;
  Frame gl = ref;
  gl.fragments[i] = 2;  // two fragments: 0 and 5 (legal), or 0 and 1 (a double hit)
  // The choices there: one of 0 and 1 by the shared edge's side, and 5 or not.
  FragmentChoices choices;
  choices.edges = 1;
  choices.members = {{0, false, {{0, true}}}, {1, false, {{0, false}}}, {5, true, {}}};
  std::optional<FragmentTrace> trace;
  std::vector<size_t> asked;
  const TraceSource source{[&](const std::vector<size_t>& pixels) {
                             asked = pixels;
                             return std::vector<std::optional<FragmentTrace>>(pixels.size(), trace);
                           },
                           [&](const std::vector<size_t>& pixels) {
                             return std::vector<FragmentChoices>(pixels.size(), choices);
                           }};
  const Tolerance t = ulps_tolerance();
  auto traced = [](std::initializer_list<int32_t> primitives) {
    FragmentTrace out;
    for (int32_t p : primitives)
      out += fragment_trace(p);
    return out;
  };
  // Without traces (or a trace source that has none) the band excuses the count.
  CaseResult r = compare(c, expect(ref, band), gl, t);
  EXPECT_EQ(r.status, Status::pass);
  EXPECT_EQ(r.coverage.counts_untraced, 1u);
  r = compare(c, expect(ref, band), gl, t, 1, &source);
  EXPECT_EQ(r.status, Status::pass);
  EXPECT_EQ(asked, std::vector<size_t>{i});
  EXPECT_EQ(r.coverage.counts_untraced, 1u);
  // The third triangle's fragment beside the reference's: admitted.
  trace = traced({0, 5});
  r = compare(c, expect(ref, band), gl, t, 1, &source);
  EXPECT_EQ(r.status, Status::pass);
  EXPECT_EQ(r.coverage.counts_traced, 1u);
  EXPECT_EQ(r.coverage.counts_untraced, 0u);
  // Both triangles of the shared edge: a double hit, the band notwithstanding.
  trace = traced({0, 1});
  r = compare(c, expect(ref, band), gl, t, 1, &source);
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(r.coverage.double_hits, 1u);
  EXPECT_EQ(r.coverage.failures, 1u);
  EXPECT_EQ(r.coverage.boundary, 0u);
  ASSERT_EQ(r.coverage.traced_failures.size(), 1u);
  EXPECT_EQ(r.coverage.traced_failures[0].label, CoverageStats::Label::double_hit);
  ASSERT_EQ(r.coverage.mismatches.size(), 1u);
  EXPECT_EQ(r.coverage.mismatches[0].label, CoverageStats::Label::double_hit);
  EXPECT_NE(r.message.find("1 double hit on a shared edge"), std::string::npos) << r.message;
  // A trace of another count than the frame's is not this frame's: not judged.
  trace = traced({0, 1, 5});
  r = compare(c, expect(ref, band), gl, t, 1, &source);
  EXPECT_EQ(r.status, Status::pass);
  EXPECT_EQ(r.coverage.counts_untraced, 1u);
  // One fragment, of the third triangle alone (neither side of the shared edge), kept where the
  // band excuses another primitive: as many fragments as the reference's, from triangles no
  // conforming implementation gives, a fill-rule error.
  gl.fragments[i] = 1, gl.primitive[i] = 5;
  trace = traced({5});
  r = compare(c, expect(ref, band), gl, t, 1, &source);
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(r.coverage.fill_rule, 1u);
  EXPECT_EQ(r.coverage.within_snapping, 0u);
  // The other side's triangle instead: admitted.
  gl.primitive[i] = 1;
  trace = traced({1});
  r = compare(c, expect(ref, band), gl, t, 1, &source);
  EXPECT_EQ(r.status, Status::pass);
  EXPECT_EQ(r.coverage.within_snapping, 1u);
  EXPECT_EQ(r.coverage.counts_traced, 1u);
  gl.fragments[i] = 0, gl.primitive[i] = Frame::kNoPrimitive;
  trace = traced({});
  r = compare(c, expect(ref, band), gl, t, 1, &source);
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_EQ(r.coverage.gaps, 1u);
  EXPECT_EQ(r.coverage.within_snapping, 0u);
}

}  // namespace
}  // namespace glrc::compare

// The counting p99 of a large channel is the element nth_element finds, on values spread over
// many binades, with ties, zeros and infinities (a driver's NaN ulps are counted as infinite).
TEST(Compare, P99OfALargeFrameIsTheNearestRankElement) {
  std::mt19937 random(13);
  for (const size_t n : {size_t(1) << 16, size_t(100003), size_t(1) << 20}) {
    std::vector<float> values(n);
    for (float& v : values) {
      const uint32_t kind = random() % 16;
      v = kind == 0   ? 0.0f
          : kind == 1 ? std::numeric_limits<float>::infinity()
          : kind == 2 ? 3.0f
                      : std::ldexp(float(random() % 1000000) / 1e6f, int(random() % 60) - 30);
    }
    std::vector<float> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    const size_t rank = size_t(std::ceil(0.99 * double(n))) - 1;
    EXPECT_EQ(glrc::compare::p99(values), double(sorted[rank])) << n;
    // Below the rank everything is finite; a tail of infinities moves p99 to infinity.
    std::fill(sorted.end() - ptrdiff_t(n / 50), sorted.end(),
              std::numeric_limits<float>::infinity());
    EXPECT_EQ(glrc::compare::p99(sorted), std::numeric_limits<double>::infinity()) << n;
  }
  std::vector<float> few = {5, 1, 4, 2, 3};
  EXPECT_EQ(glrc::compare::p99(few), 5.0);
  std::vector<float> none;
  EXPECT_EQ(glrc::compare::p99(none), 0.0);
}

namespace glrc::compare {
namespace {

// A width×height framebuffer and viewport, one smooth float varying "v"; no vertices yet.
Case float_case(const char* name, int width, int height) {
  Case c;
  c.name = name;
  c.fb_width = width, c.fb_height = height;
  c.viewport = {0, 0, width, height};
  c.varyings = {{"v", 1, Interpolation::smooth}};
  return c;
}

// Every figure of a channel against a count made here pixel by pixel, in pixel order, on a
// frame 150 pixels wide (runs of 64 and 64 in the comparator's fast path, the last 22 pixels
// one by one) where rows mix two primitives, pixels neither covers, pixels GL covers with the
// other primitive, and random errors within and beyond random allowances: the runs the
// comparator takes at once and the pixels it takes one by one must give the same figures, bit
// for bit, under the specification's allowance per pixel, a fixed number of ULPs and exact
// mode. The percentiles' kept values are compacted many times (about 5,000 values, the largest
// 1% and 16 kept), in the middle of runs too. `largest`: the largest value of primitive 1, 700
// (its ulp is another than primitive 0's, whose largest is 3) or 3.5 (the same ulp: a run where
// the two meet is taken at once too).
void expect_runs_give_a_plain_count(float largest) {
  Case c = float_case("runs", 150, 40);
  c.vertices = {{{-1, -1, 0, 1}, {0.25f}},
                {{1, -1, 0, 1}, {3.0f}},
                {{-1, 1, 0, 1}, {1.0f}},
                {{1, 1, 0, 1}, {largest}},
                {{1, -1, 0, 1}, {-90.0f * largest / 700}},
                {{-1, 1, 0, 1}, {5.0f * largest / 700}}};
  c.triangles = {{0, 1, 2}, {3, 4, 5}};
  std::mt19937 random(21);
  std::uniform_real_distribution<float> unit(0, 1);
  Frame ref(c.fb_width, c.fb_height, 1), allowed(c.fb_width, c.fb_height, 1);
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      const size_t i = ref.index(x, y);
      // Uncovered where x + 3y is 7 mod 97 (a few per row); primitive 1 right of a slanted line.
      if ((x + 3 * y) % 97 == 7) continue;
      ref.primitive[i] = x > 60 + y ? 1 : 0;
      ref.depth[i] = unit(random);
      ref.components[0][i] = (ref.primitive[i] ? largest : 3.0f) * (unit(random) - 0.3f);
      allowed.depth[i] = 1e-6f * unit(random);
      allowed.components[0][i] = (ref.primitive[i] ? 1e-4f : 1e-6f) * unit(random);
    }
  allowed.primitive = ref.primitive;
  Frame gl = ref;
  for (size_t i = 0; i < gl.pixel_count(); ++i) {
    if (ref.primitive[i] < 0) continue;
    if (random() % 211 == 0) gl.primitive[i] = 1 - ref.primitive[i];  // another triangle
    for (float* v : {&gl.depth[i], &gl.components[0][i]}) {
      const uint32_t kind = random() % 4;  // exact, a few ulps, about the allowance, far
      const float steps = kind == 0 ? 0.0f : kind == 1 ? float(random() % 5) : unit(random) * 300;
      const float scale = kind == 3 ? 1e-3f : 1e-7f;
      *v += (random() % 2 ? steps : -steps) * scale * (v == &gl.depth[i] ? 0.01f : 1.0f);
    }
  }
  const std::vector<uint8_t> edges(ref.pixel_count(), 0);
  const UlpTable table(c);
  ASSERT_EQ(table.ulp(0, Channel::component(0)) == table.ulp(1, Channel::component(0)),
            largest < 4);
  for (const ToleranceMode mode : {ToleranceMode::spec, ToleranceMode::ulps, ToleranceMode::exact})
    for (const Channel k : {Channel::depth(), Channel::component(0)}) {
      Tolerance tolerance;
      tolerance.mode = mode;
      tolerance.varying_ulps = 40, tolerance.depth_ulps = 3;
      const CaseResult r = compare(c, expect(ref, edges, allowed), gl, tolerance);
      const std::vector<float>& rv = ref.values(k);
      const std::vector<float>& gv = gl.values(k);
      const std::vector<float>& av = allowed.values(k);
      uint64_t compared = 0, differing = 0, over = 0;
      double sum = 0, sum_sq = 0, max_abs = 0, max_ulps = 0, max_ratio = 0, largest_allowance = 0;
      std::vector<float> ulps, ratios;
      WorstPixel worst{};
      for (size_t i = 0; i < ref.pixel_count(); ++i) {
        if (!same_primitive(c, ref.primitive[i], gl.primitive[i])) continue;
        const double ulp = table.ulp(ref.primitive[i], k);
        const double abs_error = std::fabs(double(gv[i]) - double(rv[i]));
        const double fixed = k.is_depth() ? tolerance.depth_ulps : tolerance.varying_ulps;
        const double e_ulps = abs_error * (1 / ulp);
        const double allow = mode == ToleranceMode::spec   ? double(av[i])
                             : mode == ToleranceMode::ulps ? fixed * ulp
                                                           : 0.0;
        const double ratio = abs_error == 0 ? 0.0 : allow > 0 ? abs_error / allow : INFINITY;
        ++compared;
        differing += rv[i] != gv[i];
        over += mode == ToleranceMode::exact ? rv[i] != gv[i] : !(abs_error <= allow);
        sum += e_ulps, sum_sq += e_ulps * e_ulps;
        max_abs = std::max(max_abs, abs_error), max_ulps = std::max(max_ulps, e_ulps);
        largest_allowance = std::max(largest_allowance, allow * (1 / ulp));
        ulps.push_back(float(e_ulps));
        ratios.push_back(float(ratio));
        if (ratio > max_ratio) {
          max_ratio = ratio;
          worst = {int(i % size_t(ref.width)),
                   int(i / size_t(ref.width)),
                   rv[i],
                   gv[i],
                   abs_error,
                   e_ulps,
                   allow,
                   ratio};
        }
      }
      const ChannelStats& ch = channel(r, k.is_depth() ? "depth" : "v.x");
      ASSERT_GT(compared, 5000u);
      ASSERT_GT(over, 100u);  // some beyond their allowance
      if (mode != ToleranceMode::exact) {
        ASSERT_LT(over, differing);  // and some within it
      }
      EXPECT_EQ(ch.compared, compared) << ch.name;
      EXPECT_EQ(ch.differing, differing) << ch.name;
      EXPECT_EQ(ch.over_tolerance, over) << ch.name;
      EXPECT_EQ(ch.non_finite, 0u) << ch.name;
      EXPECT_EQ(ch.max_abs, max_abs) << ch.name;
      EXPECT_EQ(ch.max_ulps, max_ulps) << ch.name;
      EXPECT_EQ(ch.max_ratio, max_ratio) << ch.name;
      EXPECT_EQ(ch.mean_ulps, sum / double(compared)) << ch.name;
      EXPECT_EQ(ch.rms_ulps, std::sqrt(sum_sq / double(compared))) << ch.name;
      EXPECT_EQ(ch.p99_ulps, p99(ulps)) << ch.name;
      EXPECT_EQ(ch.p99_ratio, p99(ratios)) << ch.name;
      EXPECT_EQ(ch.tolerance_ulps, largest_allowance) << ch.name;
      ASSERT_FALSE(ch.worst.empty());
      // In exact mode every differing pixel is infinitely over its allowance of 0: the worst is
      // the one of them with the most ULPs, not the first.
      if (mode == ToleranceMode::exact) continue;
      EXPECT_EQ(ch.worst[0].x, worst.x) << ch.name;
      EXPECT_EQ(ch.worst[0].y, worst.y) << ch.name;
      EXPECT_EQ(ch.worst[0].ratio, worst.ratio) << ch.name;
    }
}

TEST(Compare, RunsAndSinglePixelsGiveTheFiguresOfAPlainCount) {
  expect_runs_give_a_plain_count(700.0f);
}

TEST(Compare, RunsWherePrimitivesOfOneUlpMeetGiveTheFiguresOfAPlainCount) {
  expect_runs_give_a_plain_count(3.5f);
}

// The coverage pass runs on blocks of rows at once: its figures, and the first mismatches kept
// (in pixel order), are the same on any number of threads.
TEST(Compare, CoverageFiguresAreTheSameOnAnyThreadCount) {
  Case c = float_case("coverage", 90, 70);
  c.vertices = {{{-1, -1, 0, 1}, {1.0f}}, {{1, -1, 0, 1}, {2.0f}}, {{-1, 1, 0, 1}, {3.0f}}};
  c.triangles = {{0, 1, 2}, {0, 1, 2}};
  std::mt19937 random(5);
  Frame ref(c.fb_width, c.fb_height, 1), allowed(c.fb_width, c.fb_height, 1);
  std::vector<uint8_t> edges(ref.pixel_count(), 0);
  for (size_t i = 0; i < ref.pixel_count(); ++i) {
    ref.primitive[i] = int32_t(random() % 3) - 1;  // none, 0 or 1
    edges[i] = random() % 4 == 0 ? edge::snapping : 0;
    allowed.components[0][i] = 1e-3f;
  }
  allowed.primitive = ref.primitive;
  Frame gl = ref;
  for (size_t i = 0; i < gl.pixel_count(); ++i)
    if (random() % 7 == 0) gl.primitive[i] = int32_t(random() % 3) - 1;
  const Expectation e = expect(ref, edges, allowed);
  const CoverageStats one = compare(c, e, gl, Tolerance{}, 1).coverage;
  ASSERT_GT(one.failures + one.boundary, 200u);
  ASSERT_EQ(one.mismatches.size(), 64u);
  for (size_t k = 1; k < one.mismatches.size(); ++k)
    EXPECT_LT(std::pair(one.mismatches[k - 1].y, one.mismatches[k - 1].x),
              std::pair(one.mismatches[k].y, one.mismatches[k].x));
  for (int threads : {2, 3, 5}) {
    const CoverageStats many = compare(c, e, gl, Tolerance{}, threads).coverage;
    EXPECT_EQ(many.both, one.both) << threads;
    EXPECT_EQ(many.neither, one.neither) << threads;
    EXPECT_EQ(many.reference_only, one.reference_only) << threads;
    EXPECT_EQ(many.gl_only, one.gl_only) << threads;
    EXPECT_EQ(many.other_primitive, one.other_primitive) << threads;
    EXPECT_EQ(many.within_snapping, one.within_snapping) << threads;
    EXPECT_EQ(many.fill_rule, one.fill_rule) << threads;
    EXPECT_EQ(many.boundary, one.boundary) << threads;
    EXPECT_EQ(many.failures, one.failures) << threads;
    ASSERT_EQ(many.mismatches.size(), one.mismatches.size()) << threads;
    for (size_t k = 0; k < one.mismatches.size(); ++k) {
      EXPECT_EQ(many.mismatches[k].x, one.mismatches[k].x) << threads;
      EXPECT_EQ(many.mismatches[k].y, one.mismatches[k].y) << threads;
      EXPECT_EQ(many.mismatches[k].label, one.mismatches[k].label) << threads;
    }
  }
}

}  // namespace
}  // namespace glrc::compare
