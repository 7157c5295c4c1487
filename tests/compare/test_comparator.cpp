// The streaming Comparator: a frame compared band of rows by band of rows gives compare()'s
// result field for field, and LargestValues gives the p99 of a stream it never holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "compare/compare.hpp"
#include "ref/reference.hpp"

namespace glrc::compare {
namespace {

// p99 by sorting, the definition itself.
double sorted_p99(std::vector<float> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end(), [](float a, float b) { return order_key(a) < order_key(b); });
  return v[size_t(std::ceil(0.99 * double(v.size()))) - 1];
}

TEST(LargestValues, P99OfStreamsInEveryOrder) {
  std::mt19937 random(7);
  for (const size_t n :
       {size_t(1), size_t(99), size_t(100), size_t(101), size_t(5000), size_t(123457)}) {
    std::vector<float> values(n);
    for (float& v : values) {
      const uint32_t kind = random() % 8;
      v = kind == 0   ? 0.0f
          : kind == 1 ? 2.5f  // many ties
          : kind == 2 ? std::numeric_limits<float>::infinity()
                      : std::ldexp(float(random() % 1000) + 1, int(random() % 40) - 20);
    }
    std::vector<std::vector<float>> orders = {values, values, values};
    std::sort(orders[1].begin(), orders[1].end());    // increasing: every value is kept at first
    std::sort(orders[2].rbegin(), orders[2].rend());  // decreasing: the largest come first
    for (const auto& order : orders) {
      LargestValues largest(n);
      for (float v : order)
        largest.add(v);
      EXPECT_EQ(largest.count(), n);
      EXPECT_EQ(largest.p99(), sorted_p99(order)) << n;
    }
  }
  LargestValues none(100);
  EXPECT_EQ(none.p99(), 0.0);
}

// certainly_dropped(a, b) is only ever true for a ratio below the keep_ (n/100 + 16) largest
// seen so far, which add would drop, so the stream's p99 is that of dividing every one out;
// ratios within a few float ulps of each other included.
TEST(LargestValues, CertainlyDroppedOnlyBelowWhatIsKept) {
  std::mt19937 random(11);
  const size_t n = 8000, keep = n / 100 + 16;
  LargestValues divided(n), skipping(n);
  std::vector<float> seen;  // sorted: every ratio so far
  size_t skipped = 0;
  for (size_t k = 0; k < n; ++k) {
    const double b = std::ldexp(double(random() % 4096 + 1), int(random() % 30) - 40);
    const double r = k % 3 == 0 ? 1.0 + double(random() % 64) * 0x1p-23
                                : std::ldexp(double(random() % 1000), -int(random() % 20));
    const double a = r * b;
    const float ratio = float(a / b);
    if (skipping.certainly_dropped(a, b)) {
      const auto above = seen.end() - std::upper_bound(seen.begin(), seen.end(), ratio);
      ASSERT_GE(size_t(above), keep) << k;
      skipping.count_dropped();
      ++skipped;
    } else {
      skipping.add(ratio);
    }
    divided.add(ratio);
    seen.insert(std::upper_bound(seen.begin(), seen.end(), ratio), ratio);
  }
  EXPECT_GT(skipped, n / 2);  // the fast path is taken for most values of a long stream
  EXPECT_EQ(skipping.count(), n);
  EXPECT_EQ(skipping.p99(), divided.p99());
  // Never for a zero allowance, a NaN or an infinite error, or before anything is kept.
  EXPECT_FALSE(skipping.certainly_dropped(1.0, 0.0));
  EXPECT_FALSE(skipping.certainly_dropped(std::numeric_limits<double>::infinity(), 1.0));
  EXPECT_FALSE(skipping.certainly_dropped(std::nan(""), 1.0));
  EXPECT_FALSE(LargestValues(100).certainly_dropped(0.0, 1.0));
}

// The crossing triangles of test_depth_order.cpp (depth candidates), with one varying.
Case crossing() {
  Case c;
  c.name = "bands";
  c.fb_width = 37, c.fb_height = 29;
  c.viewport = {0, 0, 37, 29};
  c.depth_func = DepthFunc::less;
  c.varyings = {{"c", 2, Interpolation::smooth}};
  const float z0 = 0.4999997f, z1 = 0.5000009f, z2 = 0.5000003f, z3 = 0.4999991f;
  c.vertices = {{{-1, -1, z0, 1}, {0, 5}}, {{3, -1, z1, 1}, {1, 6}}, {{-1, 3, z0, 1}, {2, 7}},
                {{-1, -1, z2, 1}, {3, 8}}, {{3, -1, z3, 1}, {4, 9}}, {{-1, 3, z2, 1}, {5, 1}}};
  c.triangles = {{0, 1, 2}, {3, 4, 5}};
  return c;
}

Expectation rows_of(const Expectation& e, int y0, int rows) {
  Expectation band{e.frame.rows(y0, rows), {}, e.allowed.rows(y0, rows), {}};
  const size_t a = e.frame.index(0, y0), b = e.frame.index(0, y0 + rows);
  band.edges.assign(e.edges.begin() + ptrdiff_t(a), e.edges.begin() + ptrdiff_t(b));
  for (Candidate k : e.candidates)
    if (k.pixel >= a && k.pixel < b) {
      k.pixel -= a;
      band.candidates.push_back(k);
    }
  return band;
}

void expect_same(const CaseResult& a, const CaseResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  const CoverageStats &x = a.coverage, &y = b.coverage;
  EXPECT_EQ(x.both, y.both);
  EXPECT_EQ(x.neither, y.neither);
  EXPECT_EQ(x.reference_only, y.reference_only);
  EXPECT_EQ(x.gl_only, y.gl_only);
  EXPECT_EQ(x.other_primitive, y.other_primitive);
  EXPECT_EQ(x.exact_tie, y.exact_tie);
  EXPECT_EQ(x.within_snapping, y.within_snapping);
  EXPECT_EQ(x.fill_rule, y.fill_rule);
  EXPECT_EQ(x.gaps, y.gaps);
  EXPECT_EQ(x.double_hits, y.double_hits);
  EXPECT_EQ(x.failures, y.failures);
  EXPECT_EQ(x.fragments_checked, y.fragments_checked);
  ASSERT_EQ(x.mismatches.size(), y.mismatches.size());
  for (size_t i = 0; i < x.mismatches.size(); ++i) {
    EXPECT_EQ(x.mismatches[i].x, y.mismatches[i].x);
    EXPECT_EQ(x.mismatches[i].y, y.mismatches[i].y);
    EXPECT_EQ(x.mismatches[i].label, y.mismatches[i].label);
  }
  ASSERT_EQ(a.channels.size(), b.channels.size());
  for (size_t k = 0; k < a.channels.size(); ++k) {
    const ChannelStats &p = a.channels[k], &q = b.channels[k];
    EXPECT_EQ(p.name, q.name);
    EXPECT_EQ(p.compared, q.compared);
    EXPECT_EQ(p.over_tolerance, q.over_tolerance);
    EXPECT_EQ(p.differing, q.differing);
    EXPECT_EQ(p.non_finite, q.non_finite);
    for (auto [u, v] : {std::pair{p.max_abs, q.max_abs},
                        {p.max_ulps, q.max_ulps},
                        {p.mean_ulps, q.mean_ulps},
                        {p.rms_ulps, q.rms_ulps},
                        {p.p99_ulps, q.p99_ulps},
                        {p.max_ratio, q.max_ratio},
                        {p.p99_ratio, q.p99_ratio},
                        {p.tolerance_ulps, q.tolerance_ulps}})
      EXPECT_EQ(std::bit_cast<uint64_t>(u), std::bit_cast<uint64_t>(v)) << p.name;
    ASSERT_EQ(p.worst.size(), q.worst.size());
    for (size_t i = 0; i < p.worst.size(); ++i) {
      EXPECT_EQ(p.worst[i].x, q.worst[i].x);
      EXPECT_EQ(p.worst[i].y, q.worst[i].y);
      EXPECT_EQ(p.worst[i].ratio, q.worst[i].ratio);
    }
  }
}

TEST(Comparator, BandsGiveTheWholeFramesResult) {
  const Case c = crossing();
  const Expectation e = ref::render(c, Model{}, 8);
  ASSERT_FALSE(e.candidates.empty());
  // A GL frame with everything to count: candidates winning at every other contested pixel,
  // values off by a little and by a lot, a NaN, pixels dropped and double hits.
  Frame gl = e.frame;
  std::mt19937 random(11);
  for (size_t n = 0; n < e.candidates.size(); n += 2) {
    const Candidate& k = e.candidates[n];
    gl.primitive[k.pixel] = k.primitive, gl.depth[k.pixel] = k.depth;
    for (size_t j = 0; j < k.values.size(); ++j)
      gl.components[j][k.pixel] = k.values[j];
  }
  for (size_t i = 0; i < gl.pixel_count(); ++i) {
    const uint32_t r = random() % 100;
    if (r < 30) gl.components[0][i] = std::nextafter(gl.components[0][i], 100.0f);
    if (r == 30) gl.components[1][i] += 0.5f;
    if (r == 31) gl.primitive[i] = Frame::kNoPrimitive;
    if (r == 32) gl.fragments[i] = 2;
    if (r == 33) gl.depth[i] = std::numeric_limits<float>::quiet_NaN();
  }
  for (const Tolerance& t : {Tolerance{}, Tolerance{ToleranceMode::exact}}) {
    const CaseResult whole = compare(c, e, gl, t);
    ASSERT_EQ(whole.status, Status::fail);
    // The channels judged on several threads at once: the same figures, bit for bit.
    for (int threads : {1, 2, 5})
      for (int rows : {1, 4, 7, c.fb_height}) {
        Comparator comparator(c, t, c.fb_width, c.fb_height, threads);
        for (int y0 = 0; y0 < c.fb_height; y0 += rows) {
          const int n = std::min(rows, c.fb_height - y0);
          comparator.add_rows(rows_of(e, y0, n), gl.rows(y0, n), y0);
        }
        SCOPED_TRACE("bands of " + std::to_string(rows) + " rows on " + std::to_string(threads) +
                     " threads");
        expect_same(comparator.finish(), whole);
      }
  }
}

TEST(Comparator, BandsOutOfOrderAreRefused) {
  const Case c = crossing();
  const Expectation e = ref::render(c, Model{}, 8);
  Comparator comparator(c, Tolerance{}, c.fb_width, c.fb_height);
  EXPECT_THROW(comparator.add_rows(rows_of(e, 4, 4), e.frame.rows(4, 4), 4), std::invalid_argument);
  comparator.add_rows(rows_of(e, 0, 4), e.frame.rows(0, 4), 0);
  EXPECT_THROW(comparator.add_rows(rows_of(e, 0, 4), e.frame.rows(0, 4), 0), std::invalid_argument);
  EXPECT_THROW(comparator.add_rows(rows_of(e, 4, 4), e.frame.rows(4, 5), 4), std::invalid_argument);
}

}  // namespace
}  // namespace glrc::compare
