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
#include "tests/support/same_result.hpp"

namespace glrc::compare {
namespace {

using test::expect_same_result;

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

// A floor assumed from a guess: where the stream bears it out (at least keep_ values above it,
// or a compaction raised it) the p99 is the stream's; where it does not, complete() says so.
TEST(LargestValues, AnAssumedFloorGivesTheStreamsP99OrSaysItCannot) {
  std::mt19937 random(5);
  const size_t n = 20000, keep = n / 100 + 16;
  std::vector<float> values(n);
  for (size_t k = 0; k < n; ++k)  // rising, as a frame's errors may: ties among them
    values[k] = float(random() % (k / 50 + 2)) * 0.25f;
  std::vector<float> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  LargestValues plain(n);
  for (float v : values)
    plain.add(v);
  // A floor with this many values above it in the stream.
  for (const size_t above : {keep / 2, keep - 1, keep, keep * 3 / 2, n / 2}) {
    const float floor = sorted[n - above - 1];
    LargestValues assumed(n);
    assumed.assume_floor(order_key(floor));
    for (float v : values)
      assumed.add(v);
    const auto truly_above =
        size_t(sorted.end() - std::upper_bound(sorted.begin(), sorted.end(), floor));
    EXPECT_EQ(assumed.complete(), truly_above >= keep) << above;
    if (assumed.complete()) {
      EXPECT_EQ(assumed.p99(), plain.p99()) << above;
    } else {
      EXPECT_THROW(assumed.p99(), std::logic_error);
    }
  }
  LargestValues late(n);
  late.add(1.0f);
  EXPECT_THROW(late.assume_floor(order_key(0.5f)), std::logic_error);
  EXPECT_THROW(LargestValues(n).assume_floor(order_key(0.0f)), std::logic_error);
  EXPECT_THROW(LargestValues(n).assume_floor(order_key(std::numeric_limits<float>::infinity())),
               std::logic_error);
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
        expect_same_result(comparator.finish(), whole);
      }
  }
}

// A frame compared whole guesses the floors of each channel's largest values from a sample
// (one pixel of each run of 64 of one triangle); a frame whose errors rise from row to row
// bears the guess out, one whose large errors lie only on the sampled pixels does not, and is
// compared again. Either way the result is that of bands, which guess nothing, bit for bit.
TEST(Comparator, AWholeFramesGuessedFloorsGiveTheBandsResult) {
  Case c;
  c.name = "guessed";
  c.fb_width = 1024, c.fb_height = 512;  // 8192 runs of 64, 4096 needed for a sample
  c.viewport = {0, 0, 1024, 512};
  c.varyings = {{"c", 2, Interpolation::smooth}};
  // A perspective quad filling the framebuffer.
  c.vertices = {{{-1, -1, 0, 1}, {0, 1}},
                {{2, -2, 0, 2}, {1, 3}},
                {{1, 1, 0, 1}, {2, 2}},
                {{-2, 2, 0, 2}, {3, 0.5f}}};
  c.triangles = {{0, 1, 2}, {0, 2, 3}};
  const Expectation e = ref::render(c, Model{}, 8, 2);
  std::mt19937 random(3);
  const auto steps = [](float v, int n) {
    for (int k = 0; k < n; ++k)
      v = std::nextafter(v, 100.0f);
    return v;
  };
  for (const bool misleading : {false, true}) {
    Frame gl = e.frame;
    for (int y = 0; y < c.fb_height; ++y)
      for (int x = 0; x < c.fb_width; ++x) {
        const size_t i = gl.index(x, y);
        const bool sampled = x % 64 == (y * 37 + x / 64 * 11) % 64;
        const int n = misleading ? (sampled ? int(random() % 400) : int(random() % 2))
                                 : int(random() % (y / 16 + 2));
        for (auto& component : gl.components)
          component[i] = steps(component[i], n);
        gl.depth[i] = steps(gl.depth[i], n / 8);
      }
    for (const Tolerance& t : {Tolerance{}, Tolerance{ToleranceMode::ulps}}) {
      SCOPED_TRACE(std::string(misleading ? "misleading" : "rising") +
                   (t.mode == ToleranceMode::ulps ? ", ulps" : ", spec"));
      Comparator bands(c, t, c.fb_width, c.fb_height, 2);
      for (int y0 = 0; y0 < c.fb_height; y0 += 100) {
        const int n = std::min(100, c.fb_height - y0);
        bands.add_rows(rows_of(e, y0, n), gl.rows(y0, n), y0);
      }
      expect_same_result(compare(c, e, gl, t, 2), bands.finish());
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

// Under the spec tolerance the comparator refuses an expectation without an allowance, or whose
// allowance contradicts its state (Expectation::allowance_shape_error); under the exact
// tolerance it reads none.
TEST(Comparator, AMisshapenAllowanceIsRefusedUnderSpec) {
  Case c;
  c.name = "shape";
  c.fb_width = 4, c.fb_height = 3;
  c.varyings.push_back({"v", 2, Interpolation::smooth});
  Expectation good;
  good.frame = Frame(4, 3, 2);
  good.edges.assign(12, 0);
  good.allowed.depth.assign(12, 0.0f);
  good.allowed.components.assign(2, std::vector<float>(12, 0.0f));
  const Tolerance spec{ToleranceMode::spec}, exact{ToleranceMode::exact};
  EXPECT_EQ(compare(c, good, good.frame, spec).status, Status::pass);
  Expectation broken = good;
  broken.allowed.components[0].pop_back();
  EXPECT_THROW(compare(c, broken, broken.frame, spec), std::invalid_argument);
  EXPECT_EQ(compare(c, broken, broken.frame, exact).status, Status::pass);
  Expectation none = good;
  none.allowed = Frame();
  EXPECT_THROW(compare(c, none, none.frame, spec), std::invalid_argument);
}

}  // namespace
}  // namespace glrc::compare
