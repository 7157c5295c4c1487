// A deferred allowance (CheckOptions::deferred_allowance, ref::render_deferred): the components'
// allowances computed only where the comparison needs them must give the verdict and every
// statistic of the allowance computed at every pixel, bit for bit, and its bounds over a run
// must hold every allowance of the run. GL's frames here are the bit-exact models of Mesa's
// llvmpipe and softpipe (driver_models/), which use the freedom the allowance is derived from,
// and the reference's own frame with errors planted.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "compare/compare.hpp"
#include "driver_models/driver_models.hpp"
#include "gl_harness/gl_harness.hpp"
#include "ref/reference.hpp"
#include "report/report.hpp"

namespace glrc::check {
namespace {

std::vector<Case> suite_cases() {
  std::vector<Case> cases;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(GLRC_SOURCE_DIR) + "/cases"))
    if (entry.path().extension() == ".json") cases.push_back(casefile::load(entry.path()));
  return cases;
}

// Two perspective triangles filling size×size, `count` smooth vec4 varyings and one
// noperspective and one flat (bench/scenes.py's quad, with the other interpolations).
Case quad(int size, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-100, 100), depth(-0.5, 0.5);
  std::string varyings, vertices;
  for (int k = 0; k < count; ++k)
    varyings += "{\"name\": \"v" + std::to_string(k) + "\", \"size\": 4},";
  varyings +=
      "{\"name\": \"np\", \"size\": 2, \"interpolation\": \"noperspective\"},"
      "{\"name\": \"fl\", \"size\": 1, \"interpolation\": \"flat\"}";
  const double corners[4][3] = {{-1, -1, 1.0}, {1, -1, 2.0}, {1, 1, 4.0}, {-1, 1, 3.0}};
  for (const auto& [x, y, w] : corners) {
    vertices += std::string(vertices.empty() ? "" : ",") + "{\"clip\": [" + std::to_string(x * w) +
                "," + std::to_string(y * w) + "," + std::to_string(depth(rng) * w) + "," +
                std::to_string(w) + "]";
    const auto numbers = [&](int n) {
      std::string s;
      for (int i = 0; i < n; ++i)
        s += (i ? "," : "") + std::to_string(std::round(value(rng) * 1000) / 1000);
      return "[" + s + "]";
    };
    for (int k = 0; k < count; ++k)
      vertices += ", \"v" + std::to_string(k) + "\": " + numbers(4);
    vertices += ", \"np\": " + numbers(2) + ", \"fl\": " + numbers(1) + "}";
  }
  const std::string text =
      "{\"description\": \"deferred allowance test quad\", \"framebuffer\": "
      "{\"width\": " +
      std::to_string(size) + ", \"height\": " + std::to_string(size) + "}, \"varyings\": [" +
      varyings + "], \"vertices\": [" + vertices + "], \"triangles\": [[0, 1, 2], [0, 2, 3]]}";
  return casefile::parse(text, "test", "deferred_quad_" + std::to_string(size));
}

// The reference's frame with errors planted, in the components and in the depth: a few pixels
// far beyond any allowance, a few values one float step away, NaN at one pixel.
Frame planted(const Frame& reference, unsigned seed) {
  Frame f = reference;
  std::mt19937 rng(seed);
  if (f.components.empty() || f.pixel_count() == 0) return f;
  std::uniform_int_distribution<size_t> pixel(0, f.pixel_count() - 1);
  for (int n = 0; n < 200; ++n) {
    std::vector<float>& channel = f.components[size_t(n) % f.components.size()];
    const size_t i = pixel(rng);
    channel[i] = n % 3 == 0 ? channel[i] + 1.0f : std::nextafter(channel[i], INFINITY);
  }
  for (int n = 0; n < 60; ++n) {
    const size_t i = pixel(rng);
    f.depth[i] = n % 3 == 0 ? f.depth[i] * 0.5f : std::nextafter(f.depth[i], 0.0f);
  }
  f.components[0][pixel(rng)] = NAN;
  f.depth[pixel(rng)] = NAN;
  return f;
}

std::string json_of(CaseResult r) {
  r.seconds = 0;
  return report::case_result_json(r);
}

void expect_same_results(const Case& c, const std::vector<Frame>& frames,
                         const CheckOptions& options) {
  const Expectation everywhere = expectation_for(c, options, 8);
  // Deferred whether or not it pays (deferral_pays): the same results either way.
  Expectation deferred = ref::render_deferred(c, options.model, freedom_bits(options, 8), 1);
  ASSERT_TRUE(deferred.deferred) << c.name;
  EXPECT_TRUE(deferred.allowed.components.empty()) << c.name;
  // The depth's too, where no depth test needs it while drawing.
  const bool depth = c.depth_func == DepthFunc::always;
  EXPECT_EQ(deferred.deferred->defers_depth(), depth) << c.name;
  EXPECT_EQ(deferred.allowed.depth.empty(), depth) << c.name;
  const Tolerance t = tolerance_for(c, options, 8);
  for (size_t n = 0; n < frames.size(); ++n) {
    EXPECT_EQ(json_of(compare::compare(c, deferred, frames[n], t, 2)),
              json_of(compare::compare(c, everywhere, frames[n], t, 2)))
        << c.name << ", frame " << n;
  }
  // Band by band, as a streamed check compares them, each band's allowance deferred
  // (render_rows_deferred: its rows' bounds, the largest allowance of the bands before, no
  // floors guessed): the same results as the whole frame's allowance at every pixel.
  const int band = std::max(1, c.fb_height / 5 + 3);
  for (size_t n = 0; n < frames.size(); ++n) {
    compare::Comparator comparator(c, t, c.fb_width, c.fb_height, 2);
    for (int y0 = 0; y0 < c.fb_height; y0 += band) {
      const int rows = std::min(band, c.fb_height - y0);
      const Expectation e =
          ref::render_rows_deferred(c, options.model, freedom_bits(options, 8), 1, y0, rows);
      ASSERT_TRUE(e.deferred) << c.name;
      EXPECT_EQ(e.deferred->first_row(), y0);
      comparator.add_rows(e, frames[n].rows(y0, rows), y0);
    }
    EXPECT_EQ(json_of(comparator.finish()),
              json_of(compare::compare(c, everywhere, frames[n], t, 2)))
        << c.name << ", frame " << n << " in bands of " << band << " rows";
  }
  // Filled in, the allowance is the one computed at every pixel, bit for bit.
  complete_allowance(deferred, 2);
  EXPECT_FALSE(deferred.deferred);
  EXPECT_EQ(ref::expectation_digest(deferred), ref::expectation_digest(everywhere)) << c.name;
}

std::vector<Frame> frames_for(const Case& c, const Frame& reference) {
  return {driver_models::render(c, driver_models::Driver::llvmpipe),
          driver_models::render(c, driver_models::Driver::softpipe), planted(reference, 7)};
}

TEST(DeferredAllowance, EverySuiteCaseGetsTheSameResultsAsTheAllowanceAtEveryPixel) {
  for (const Case& c : suite_cases()) {
    const Frame reference = ref::render(c, CheckOptions{}.model, 8).frame;
    expect_same_results(c, frames_for(c, reference), CheckOptions{});
  }
}

TEST(DeferredAllowance, ALargeFrameGetsTheSameResultsAsTheAllowanceAtEveryPixel) {
  // Large enough for the comparator to guess its floors and to judge most runs by their
  // bounds alone (Comparator::add_whole_channel).
  for (unsigned seed : {1u, 2u}) {
    const Case c = quad(512, 2, seed);
    const Frame reference = ref::render(c, CheckOptions{}.model, 8).frame;
    expect_same_results(c, frames_for(c, reference), CheckOptions{});
    CheckOptions strict;
    strict.strict_coverage = true;
    expect_same_results(c, {driver_models::render(c, driver_models::Driver::llvmpipe)}, strict);
  }
}

// A frame compared band by band with its floors guessed from sample bands first
// (Comparator::add_floor_sample, guess_floors, as a streamed check does): the same results as
// the whole frame, when the stream bears the guess out; and floors_held() says when it does
// not, which a sample misleading on purpose shows (the floors are assumed, not a no-op).
TEST(DeferredAllowance, FloorsGuessedFromSampleBandsGiveTheWholeResults) {
  const Case c = quad(1024, 1, 5);
  const Frame gl = driver_models::render(c, driver_models::Driver::llvmpipe);
  for (const ToleranceMode mode :
       {ToleranceMode::spec, ToleranceMode::ulps, ToleranceMode::exact}) {
    SCOPED_TRACE(int(mode));
    CheckOptions o;
    o.tolerance = mode;
    const int bits = freedom_bits(o, 8);
    const Tolerance t = tolerance_for(c, o, 8);
    const std::string whole = json_of(compare::compare(c, expectation_for(c, o, 8), gl, t, 2));
    // Rows of the reference as a streamed check draws them: the allowance deferred under the
    // specification's, else none needed beyond the band's own.
    const auto band = [&](int y0, int rows) {
      return mode == ToleranceMode::spec ? ref::render_rows_deferred(c, o.model, bits, 2, y0, rows)
                                         : expectation_rows(c, o, 8, y0, rows);
    };
    // Sample bands of 16 rows, one in two (512 rows of 16 runs: over 4096 plain runs), then
    // the frame in bands of `height` rows.
    const auto sampled = [&](const Frame& sample_gl, int height = 100) {
      auto comparator = std::make_unique<compare::Comparator>(c, t, c.fb_width, c.fb_height, 2);
      for (int y0 = 8; y0 < c.fb_height; y0 += 32)
        comparator->add_floor_sample(band(y0, 16), sample_gl.rows(y0, 16));
      comparator->guess_floors();
      for (int y0 = 0; y0 < c.fb_height; y0 += height) {
        const int rows = std::min(height, c.fb_height - y0);
        comparator->add_rows(band(y0, rows), gl.rows(y0, rows), y0);
      }
      return comparator;
    };
    const auto guessed = sampled(gl);
    EXPECT_TRUE(guessed->floors_held());
    EXPECT_EQ(json_of(guessed->finish()), whole);
    // One band of the whole frame after the guess (which a whole frame makes of itself
    // otherwise, and only before any value).
    const auto one_band = sampled(gl, c.fb_height);
    EXPECT_TRUE(one_band->floors_held());
    EXPECT_EQ(json_of(one_band->finish()), whole);
    // Sampled from a frame with every error ten thousand times GL's: floors far above the
    // frame's hundredth largest errors, which the stream does not bear out.
    Frame misleading = gl;
    const Frame reference = ref::render(c, o.model, bits, 2).frame;
    for (size_t k = 0; k < gl.components.size(); ++k)
      for (size_t i = 0; i < gl.pixel_count(); ++i)
        misleading.components[k][i] =
            reference.components[k][i] + 1e4f * (gl.components[k][i] - reference.components[k][i]);
    EXPECT_FALSE(sampled(misleading)->floors_held());
    // Only before the first band.
    compare::Comparator late(c, t, c.fb_width, c.fb_height, 1);
    late.add_rows(band(0, 10), gl.rows(0, 10), 0);
    EXPECT_THROW(late.add_floor_sample(band(10, 10), gl.rows(10, 10)), std::logic_error);
  }
}

// A stand-in for GL (it tests check_streamed's logic, not a driver): draws `frame`, and gives
// the bands read before the first read of row 0 (a streamed check's sample bands) from
// `samples` instead.
class SampledRenderer : public gl::Renderer {
 public:
  SampledRenderer(Frame frame, Frame samples)
      : frame_(std::move(frame)), samples_(std::move(samples)) {
    info_.renderer = "frame and sample bands (test)";
    info_.subpixel_bits = 8;
  }
  const gl::GlInfo& info() const override { return info_; }
  Frame render(const Case&) override { return frame_; }
  void draw(const Case&) override { first_band_read_ = false; }
  Frame read_rows(const Case&, int y0, int rows) override {
    ++reads;
    first_band_read_ = first_band_read_ || y0 == 0;
    return (first_band_read_ ? frame_ : samples_).rows(y0, rows);
  }
  int reads = 0;

 private:
  gl::GlInfo info_;
  Frame frame_, samples_;
  bool first_band_read_ = false;
};

// A streamed check whose floors, guessed from its sample bands, the stream does not bear out
// (sample bands whose errors are a thousand times the frame's): its bands compared again
// without them, the whole check's result; and with honest sample bands, compared once.
TEST(DeferredAllowance, AStreamedCheckWhoseFloorsDoNotHoldIsComparedAgain) {
  // 2048x2048 (64 sample bands of two rows: 8192 runs), the noperspective pair and the flat
  // component; errors of 0 to 3 float steps in the pair, by pixel.
  const Case c = quad(2048, 0, 6);
  const Frame reference = ref::render_frame(c, CheckOptions{}.model, 2);
  Frame gl = reference, misleading = reference;
  for (size_t k = 0; k < 2; ++k)
    for (size_t i = 0; i < gl.pixel_count(); ++i) {
      float& v = gl.components[k][i];
      for (size_t step = (i * 2654435761u >> 7) % 4; step > 0; --step)
        v = std::nextafter(v, INFINITY);
      misleading.components[k][i] =
          reference.components[k][i] + 1e3f * (v - reference.components[k][i]);
    }
  CheckOptions whole;
  whole.deferred_allowance = true;
  whole.threads = 2;
  CheckOptions streamed = whole;
  streamed.whole_frame_bytes = 0;
  SampledRenderer honest(gl, gl), misled(gl, misleading);
  const Checked expected = check_with_frames(c, honest, whole);
  EXPECT_FALSE(expected.streamed);
  const int reads_before = honest.reads;
  const Checked once = check_with_frames(c, honest, streamed);
  const int honest_reads = honest.reads - reads_before;
  const Checked again = check_with_frames(c, misled, streamed);
  EXPECT_TRUE(once.streamed && again.streamed);
  EXPECT_EQ(json_of(once.result), json_of(expected.result));
  EXPECT_EQ(json_of(again.result), json_of(expected.result));
  EXPECT_EQ(once.result.gl_digest, ref::digest(gl));
  EXPECT_EQ(again.result.gl_digest, ref::digest(gl));
  // Each band read twice where the floors did not hold, once where they did (and the sample
  // bands once in both).
  const int bands = (c.fb_height + slice_rows(c, streamed) - 1) / slice_rows(c, streamed);
  EXPECT_GT(honest_reads, bands);
  EXPECT_EQ(misled.reads, honest_reads + bands);
}

// Every run of `length` pixels of one primitive in a row: lo <= each allowance <= hi, for the
// run's least and largest values; of every component, and of the depth where it is deferred.
size_t expect_ranges_hold(const Case& c, int length, double tightest_spread) {
  const CheckOptions o;
  const Expectation e = ref::render_deferred(c, o.model, freedom_bits(o, 8), 2);
  EXPECT_TRUE(e.deferred);
  if (!e.deferred) return 0;
  const Frame& f = e.frame;
  size_t runs = 0, tight = 0;
  for (const Channel k : e.deferred->channels(int(f.components.size())))
    for (int y = 0; y < f.height; ++y)
      for (int x0 = 0; x0 < f.width; x0 += length / 4) {
        const std::vector<float>& values = f.values(k);
        const int x1 = std::min(f.width, x0 + length) - 1;
        const int32_t p = f.primitive[f.index(x0, y)];
        bool one = p >= 0;
        float lo = INFINITY, hi = -INFINITY;
        for (int x = x0; x <= x1 && one; ++x) {
          const size_t i = f.index(x, y);
          one = f.primitive[i] == p && std::isfinite(values[i]);
          lo = std::min(lo, values[i]);
          hi = std::max(hi, values[i]);
        }
        if (!one) continue;
        const auto range = e.deferred->range(k, p, x0, x1, y, lo, hi);
        std::vector<float> allowed(size_t(x1 - x0 + 1));
        e.deferred->at(f, k, f.index(x0, y), x1 - x0 + 1, allowed.data());
        ++runs;
        for (float a : allowed) {
          EXPECT_LE(range[0], double(a)) << c.name << " channel " << k.slot() << " row " << y;
          EXPECT_LE(double(a), range[1]) << c.name << " channel " << k.slot() << " row " << y;
        }
        tight += range[1] <= tightest_spread * range[0];
      }
  // Most runs' bounds are within a factor of 2: a bound is only worth having if it decides.
  if (tightest_spread > 0) {
    EXPECT_GT(double(tight), 0.9 * double(runs)) << c.name << " " << tight << "/" << runs;
  }
  return runs;
}

TEST(DeferredAllowance, IsUsedWhereTrianglesAreLargeAndThereAreComponents) {
  CheckOptions o;
  o.deferred_allowance = true;
  const Case large = quad(256, 1, 4);
  EXPECT_TRUE(deferral_pays(large));
  EXPECT_TRUE(expectation_for(large, o, 8).deferred);
  o.deferred_allowance = false;
  EXPECT_FALSE(expectation_for(large, o, 8).deferred);
  // Many small triangles: every run of 64 pixels crosses several.
  Case small = large;
  small.fb_width = small.fb_height = 64;
  for (int n = 0; n < 2; ++n)
    small.triangles.push_back(small.triangles[0]);
  EXPECT_FALSE(deferral_pays(small));
  o.deferred_allowance = true;
  EXPECT_FALSE(expectation_for(small, o, 8).deferred);
  // No components: nothing to defer.
  Case plain = large;
  plain.varyings.clear();
  for (Vertex& v : plain.vertices)
    v.values.clear();
  EXPECT_FALSE(deferral_pays(plain));
}

TEST(DeferredAllowance, ARunsBoundsHoldEveryAllowanceOfIt) {
  // Twelve channels (2 vec4, the noperspective pair, the flat one, whose bounds are 0 and 0,
  // and the depth) of 256 rows, each of 13 runs, but those that cross the quad's diagonal.
  const Case large = quad(256, 2, 3);
  ASSERT_EQ(large.depth_func, DepthFunc::always);
  EXPECT_GT(expect_ranges_hold(large, 64, 2.0), 12 * 256u * 12u);
  size_t runs = 0;
  for (const Case& c : suite_cases())
    if (c.component_count() > 0) runs += expect_ranges_hold(c, 8, 0);
  EXPECT_GT(runs, 1000u);
}

// at_lanes of any lanes of a run gives each lane at()'s bits for the whole run and leaves the
// other lanes as they were: on the quad (runs crossing its diagonal hold two primitives) and on
// every suite case with components (pixels nothing draws, several triangles in a run).
void expect_lanes_give_the_runs_bits(const Case& c, std::mt19937& rng) {
  const CheckOptions o;
  const Expectation e = ref::render_deferred(c, o.model, freedom_bits(o, 8), 2);
  if (!e.deferred) return;
  const Frame& f = e.frame;
  for (const Channel k : e.deferred->channels(int(f.components.size())))
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x + 64 <= f.width; x += 64) {
        const size_t start = f.index(x, y);
        float whole[64], lanes[64];
        e.deferred->at(f, k, start, 64, whole);
        // Every lane, none, one, and sparse and dense random ones.
        const auto word = [&] { return uint64_t(rng()) | (uint64_t(rng()) << 32); };
        const uint64_t masks[] = {~uint64_t(0), 0, uint64_t(1) << (rng() % 64),
                                  word() & word() & word(), word()};
        for (const uint64_t mask : masks) {
          std::fill(std::begin(lanes), std::end(lanes), -7.0f);
          e.deferred->at_lanes(f, k, start, mask, lanes);
          for (int j = 0; j < 64; ++j)
            ASSERT_EQ(std::bit_cast<uint32_t>(lanes[j]),
                      std::bit_cast<uint32_t>((mask >> j) & 1 ? whole[j] : -7.0f))
                << c.name << " channel " << k.slot() << " pixel " << x + j << ", " << y;
        }
      }
}

TEST(DeferredAllowance, LanesGiveTheBitsOfTheirRun) {
  std::mt19937 rng(5);
  expect_lanes_give_the_runs_bits(quad(256, 1, 6), rng);
  for (const Case& c : suite_cases())
    if (c.component_count() > 0) expect_lanes_give_the_runs_bits(c, rng);
}

}  // namespace
}  // namespace glrc::check
