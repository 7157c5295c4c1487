// write_diff_images on a hand-made 8x6 case: the files it writes, and the EXRs read back with
// one injected error at the right (vertically flipped) pixel.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "compare/compare.hpp"
#include "report/channel_error.hpp"
#include "report/coverage_image.hpp"
#include "report/report.hpp"
#include "tests/report/test_helpers.hpp"

namespace glrc::report::test {
namespace {

constexpr int kW = 8, kH = 6;
// The triangle's v values are 0.5, 1 and 2: scale 2, so one ulp is 2^-22.
constexpr float kUlp = 0x1p-22f;
constexpr int kErrX = 2, kErrY = 1;  // frame coordinates, row 0 at the bottom

Case one_triangle_case() {
  Case c;
  c.name = "synthetic";
  c.fb_width = kW;
  c.fb_height = kH;
  c.viewport = {0, 0, kW, kH};
  c.varyings = {{"v", 1, Interpolation::smooth}};
  c.vertices = {{{-1, -1, 0, 1}, {0.5f}}, {{1, -1, 0, 1}, {1.0f}}, {{0, 1, 0, 1}, {2.0f}}};
  c.triangles = {{0, 1, 2}};
  return c;
}

// The reference covers x < 6, y < 5 with primitive 0; v = x/4 + y/8, depth 0.5.
Frame reference_frame() {
  Frame f(kW, kH, 1);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 6; ++x) {
      f.primitive[f.index(x, y)] = 0;
      f.components[0][f.index(x, y)] = 0.25f * x + 0.125f * y;
      f.depth[f.index(x, y)] = 0.5f;
    }
  return f;
}

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;
  float at(int x, int y, int ch = 0) const {
    return pixels[(size_t(y) * width + x) * channels + ch];
  }
};

Image read_image(const std::filesystem::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  EXPECT_TRUE(in) << OIIO::geterror();
  Image image;
  if (!in) return image;
  image.width = in->spec().width;
  image.height = in->spec().height;
  image.channels = in->spec().nchannels;
  image.pixels.resize(size_t(image.width) * image.height * image.channels);
  EXPECT_TRUE(in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data()));
  return image;
}

// How many pixels of an 8-bit image have this colour (0..255 per channel, off by one at most).
size_t count_colour(const Image& png, int r, int g, int b) {
  size_t n = 0;
  for (size_t i = 0; i + 2 < png.pixels.size(); i += size_t(png.channels)) {
    const auto near = [](float v, int want) { return std::abs(std::lround(v * 255) - want) <= 1; };
    n += near(png.pixels[i], r) && near(png.pixels[i + 1], g) && near(png.pixels[i + 2], b);
  }
  return n;
}

// The legend has small swatches of these colours too; a frame pixel upscaled to >= 512 px width
// is a block of at least 64 x 64 here, far more than any swatch.
constexpr size_t kFramePixelArea = 64 * 64;
bool shows_frame_pixel_of(const Image& png, int r, int g, int b) {
  return count_colour(png, r, g, b) >= kFramePixelArea;
}

TEST_F(ReportTest, DiffImagesWritesEveryChannelAndCoverage) {
  const Case c = one_triangle_case();
  const Frame ref = reference_frame();
  Frame gl = ref;
  gl.components[0][gl.index(kErrX, kErrY)] += 3 * kUlp;
  gl.primitive[gl.index(6, 0)] = 0;  // a GL-only pixel
  CaseResult r;
  r.name = c.name;
  // The specification's allowance: 2 ulp for v.x everywhere, 1 ulp of 1.0 for depth.
  Frame allowed(kW, kH, 1);
  allowed.primitive = ref.primitive;
  for (auto& v : allowed.components[0])
    v = 2 * kUlp;
  for (auto& v : allowed.depth)
    v = 0x1p-23f;

  const auto files = write_diff_images(
      dir_ / "diff", c, Expectation{ref, std::vector<uint8_t>(kW * kH, 0), allowed}, gl, r);
  std::vector<std::string> names;
  for (const auto& f : files) {
    EXPECT_TRUE(std::filesystem::is_regular_file(f)) << f;
    EXPECT_EQ(f.parent_path(), dir_ / "diff");
    names.push_back(f.filename().string());
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{
                       "coverage.png", "depth_allowed.exr", "depth_allowed.png", "depth_error.exr",
                       "depth_error.png", "depth_gl.exr", "depth_ratio.png", "depth_ref.exr",
                       "v.x_allowed.exr", "v.x_allowed.png", "v.x_error.exr", "v.x_error.png",
                       "v.x_gl.exr", "v.x_ratio.png", "v.x_ref.exr"}));
  // The allowance as the comparator used it, in value units, where values are compared.
  const Image allowance = read_image(dir_ / "diff" / "v.x_allowed.exr");
  EXPECT_EQ(allowance.at(kErrX, kH - 1 - kErrY), 2 * kUlp);
  EXPECT_TRUE(std::isnan(allowance.at(7, kH - 1)));
  // 3 ulp of error against 2 allowed: the ratio map's bright end, over 1.
  EXPECT_TRUE(shows_frame_pixel_of(read_image(dir_ / "diff" / "v.x_ratio.png"), 0xfd, 0xe7, 0x25));

  const Image error = read_image(dir_ / "diff" / "v.x_error.exr");
  ASSERT_EQ(error.width, kW);
  ASSERT_EQ(error.height, kH);
  ASSERT_EQ(error.channels, 1);
  // Frame row y is image row kH - 1 - y.
  EXPECT_EQ(error.at(kErrX, kH - 1 - kErrY), 3 * kUlp);
  EXPECT_EQ(error.at(kErrX, kErrY), 0.0f);       // frame row 4: compared, no error
  EXPECT_TRUE(std::isnan(error.at(7, kH - 1)));  // frame (7, 0): covered by neither
  EXPECT_TRUE(std::isnan(error.at(6, kH - 1)));  // frame (6, 0): GL only, not compared

  const Image reference = read_image(dir_ / "diff" / "v.x_ref.exr");
  const Image got = read_image(dir_ / "diff" / "v.x_gl.exr");
  EXPECT_EQ(reference.at(kErrX, kH - 1 - kErrY), 0.625f);
  EXPECT_EQ(got.at(kErrX, kH - 1 - kErrY), 0.625f + 3 * kUlp);
  const Image depth = read_image(dir_ / "diff" / "depth_ref.exr");
  EXPECT_EQ(depth.at(0, kH - 1), 0.5f);
  EXPECT_EQ(depth.at(7, 0), 1.0f);

  const Image heatmap = read_image(dir_ / "diff" / "v.x_error.png");
  EXPECT_GE(heatmap.width, 512);
  EXPECT_GT(heatmap.height, 512 * kH / kW);  // the frame upscaled, plus title and legend
  EXPECT_TRUE(
      shows_frame_pixel_of(heatmap, 0xfd, 0xe7, 0x25));  // the largest error: viridis' bright end
  EXPECT_TRUE(shows_frame_pixel_of(heatmap, 0x44, 0x01, 0x54));  // zero error: viridis' dark end
  EXPECT_TRUE(shows_frame_pixel_of(heatmap, 128, 128, 128));     // not compared
  EXPECT_FALSE(shows_frame_pixel_of(heatmap, 255, 0, 255));      // no NaN

  const Image coverage = read_image(dir_ / "diff" / "coverage.png");
  EXPECT_GE(coverage.width, 512);
}

// Canvas pixels of exactly the failing-pixel ring's colour in rows [0, rows), and where they lie.
struct RingPixels {
  size_t count = 0;
  int min_x = 1 << 30, max_x = -1, min_y = 1 << 30, max_y = -1;
};
RingPixels ring_pixels(const Canvas& canvas, int rows) {
  RingPixels r;
  for (int y = 0; y < std::min(rows, canvas.height); ++y)
    for (int x = 0; x < canvas.width; ++x) {
      const float* p = &canvas.rgb[(size_t(y) * canvas.width + x) * 3];
      if (p[0] != 0.3f || p[1] != 1.0f || p[2] != 0.2f) continue;
      ++r.count;
      r.min_x = std::min(r.min_x, x), r.max_x = std::max(r.max_x, x);
      r.min_y = std::min(r.min_y, y), r.max_y = std::max(r.max_y, y);
    }
  return r;
}

// The same, in the size x size square at (x0, y0).
RingPixels ring_pixels_in(const Canvas& canvas, int x0, int y0, int size) {
  RingPixels r;
  for (int y = y0; y < y0 + size; ++y)
    for (int x = x0; x < x0 + size; ++x) {
      const float* p = &canvas.rgb[(size_t(y) * canvas.width + x) * 3];
      r.count += p[0] == 0.3f && p[1] == 1.0f && p[2] == 0.2f;
    }
  return r;
}

// A frame over 2^20 pixels: maps of the failing channel only, shrunk to at most 1024 pixels on
// the long side with the failing pixel kept, and full-resolution EXR tiles around it; nothing
// of the passing channel. (A 4096 x 4096 case with 7 vec4 varyings wrote 204 files and 1.2 GB
// before; now 7.3 MB.)
TEST_F(ReportTest, LargeFramesGetShrunkMapsOfFailingChannelsAndTilesAroundTheWorstPixel) {
  constexpr int w = 1100, h = 1000, bad_x = 1001, bad_y = 77;
  Case c;
  c.name = "large";
  c.fb_width = w, c.fb_height = h;
  c.viewport = {0, 0, w, h};
  c.varyings = {{"v", 2, Interpolation::smooth}};
  c.vertices = {{{-1, -1, 0, 1}, {1, 1}}, {{3, -1, 0, 1}, {1, 1}}, {{-1, 3, 0, 1}, {1, 1}}};
  c.triangles = {{0, 1, 2}};
  Frame ref(w, h, 2);
  ref.primitive.assign(ref.pixel_count(), 0);
  ref.depth.assign(ref.pixel_count(), 0.5f);
  for (auto& component : ref.components)
    component.assign(ref.pixel_count(), 1.0f);
  Frame allowed(w, h, 2);
  allowed.primitive = ref.primitive;
  allowed.depth.assign(ref.pixel_count(), 0x1p-20f);
  for (auto& component : allowed.components)
    component.assign(ref.pixel_count(), 0x1p-20f);
  Frame gl = ref;
  gl.components[0][gl.index(bad_x, bad_y)] = 1.5f;
  CaseResult r;
  r.name = c.name;
  r.channels.resize(3);
  r.channels[0].name = "depth", r.channels[1].name = "v.x", r.channels[2].name = "v.y";
  r.channels[1].over_tolerance = 1;

  const auto files = write_diff_images(
      dir_ / "large", c, Expectation{ref, std::vector<uint8_t>(size_t(w) * h, 0), allowed}, gl, r);
  std::vector<std::string> names;
  for (const auto& f : files)
    names.push_back(f.filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names,
            (std::vector<std::string>{"coverage.png", "v.x_allowed.png", "v.x_allowed_tile.exr",
                                      "v.x_error.png", "v.x_error_tile.exr", "v.x_gl_tile.exr",
                                      "v.x_ratio.png", "v.x_ref_tile.exr"}));
  const Image tile = read_image(dir_ / "large" / "v.x_error_tile.exr");
  ASSERT_EQ(tile.width, 256);
  ASSERT_EQ(tile.height, 256);
  // Centred on the bad pixel, kept inside the frame: x from 1100 - 256 = 844 (1001 - 128 would
  // pass the right side), y from 0 (77 - 128 would pass the bottom); rows flipped as in every
  // EXR.
  const int x0 = w - 256, y0 = 0;
  EXPECT_EQ(tile.at(bad_x - x0, 255 - (bad_y - y0)), 0.5f);
  EXPECT_EQ(tile.at(bad_x - x0 + 1, 255 - (bad_y - y0)), 0.0f);
  const Image map = read_image(dir_ / "large" / "v.x_error.png");
  EXPECT_LE(map.width, 1024 + 200);  // 550 x 500 pixels of frame, and the margins and legend
}

// A streamed case's pictures, made band by band from the rows alone, are the very files the
// whole frames give: the same names, the same bytes.
TEST_F(ReportTest, StreamedPicturesAreTheWholeFramesPictures) {
  constexpr int w = 1100, h = 1000;
  Case c;
  c.name = "large";
  c.fb_width = w, c.fb_height = h;
  c.viewport = {0, 0, w, h};
  c.varyings = {{"v", 2, Interpolation::smooth}};
  c.vertices = {{{-1, -1, 0, 1}, {1, 1}}, {{3, -1, 0, 1}, {1, 1}}, {{-1, 3, 0, 1}, {1, 1}}};
  c.triangles = {{0, 1, 2}};
  Frame ref(w, h, 2), allowed(w, h, 2);
  ref.primitive.assign(ref.pixel_count(), 0);
  allowed.primitive = ref.primitive;
  for (size_t i = 0; i < ref.pixel_count(); ++i) {
    ref.depth[i] = 0.5f, allowed.depth[i] = 0x1p-20f;
    for (int k = 0; k < 2; ++k)
      ref.components[size_t(k)][i] = float(i % 977) / 977.0f + float(k),
      allowed.components[size_t(k)][i] = 0x1p-18f * float(1 + i % 7);
  }
  Frame gl = ref;
  for (size_t i = 0; i < gl.pixel_count(); i += 4093)
    gl.components[0][i] += 0x1p-17f * float(i % 5);       // some within, some over the allowance
  gl.components[0][gl.index(700, 901)] = 9.0f;            // the worst, near the top
  gl.primitive[gl.index(10, 500)] = Frame::kNoPrimitive;  // a coverage failure
  std::vector<uint8_t> edges(size_t(w) * h, 0);
  const Expectation expected{ref, edges, allowed};
  Tolerance t;

  gl.components[1][gl.index(3, 3)] = -1.0f;  // a second failing channel
  const CaseResult r = compare::compare(c, expected, gl, t);
  ASSERT_EQ(r.status, Status::fail);
  const auto whole = write_diff_images(dir_ / "whole", c, expected, gl, r);
  int calls = 0;
  const auto streamed =
      write_streamed_diff_images(dir_ / "streamed", c, r, 37, [&](int y0, int rows) {
        ++calls;
        EXPECT_LE(rows, 37);
        Expectation e{ref.rows(y0, rows), {}, allowed.rows(y0, rows)};
        e.edges.assign(size_t(w) * size_t(rows), 0);
        return std::pair{e, gl.rows(y0, rows)};
      });
  // Every band once for the maps, then the rows of the two tiles (256 rows each, apart): the
  // bands are read at most twice.
  EXPECT_GE(calls, (1000 + 36) / 37 + 2 * 256 / 37);
  EXPECT_LE(calls, 2 * ((1000 + 36) / 37));
  ASSERT_EQ(streamed.size(), whole.size());
  auto bytes = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(streamed[i].filename(), whole[i].filename());
    if (whole[i].extension() != ".exr") {
      EXPECT_TRUE(bytes(streamed[i]) == bytes(whole[i])) << whole[i].filename();
      continue;
    }
    // An EXR holds the second it was written (capDate): its size, description and pixels.
    const Image a = read_image(streamed[i]), b = read_image(whole[i]);
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_TRUE(std::equal(
        a.pixels.begin(), a.pixels.end(), b.pixels.begin(), b.pixels.end(),
        [](float x, float y) { return std::bit_cast<uint32_t>(x) == std::bit_cast<uint32_t>(y); }))
        << whole[i].filename();
    auto comments = [](const std::filesystem::path& f) {
      auto in = OIIO::ImageInput::open(f.string());
      return in ? std::string(in->spec().get_string_attribute("ImageDescription"))
                : std::string("?");
    };
    EXPECT_EQ(comments(streamed[i]), comments(whole[i]));
  }
}

// The maps of a large frame shrink further when many channels fail, so that all of them are
// made in one pass within their 128 MiB: 4096 x 4096 keeps 1024 x 1024 maps up to 7 channels.
TEST(ChannelErrorMap, MapsShrinkToFitEveryChannelInOnePass) {
  EXPECT_EQ(map_factor(1024, 1024, 29), 1);  // 2^20 pixels: full resolution
  EXPECT_EQ(map_factor(1100, 1000, 1), 2);
  EXPECT_EQ(map_factor(4096, 4096, 1), 4);
  EXPECT_EQ(map_factor(4096, 4096, 7), 4);
  EXPECT_EQ(map_factor(4096, 4096, 8), 8);
  EXPECT_EQ(map_factor(4096, 4096, 29), 8);
  EXPECT_EQ(map_factor(4096, 4096, 200), 32);
  EXPECT_EQ(map_factor(16384, 16384, 29), 32);
  for (const size_t channels : {1, 7, 29, 200}) {
    const int f = map_factor(8000, 3000, channels);
    const size_t map_pixels = size_t((8000 + f - 1) / f) * size_t((3000 + f - 1) / f);
    EXPECT_LE(map_pixels * 17 * channels, size_t(128) << 20) << channels;
    EXPECT_LE(8000 / f, 1024) << channels;
  }
}

// Downsampling keeps each block's worst pixel: the one failing pixel of a million survives.
TEST(ChannelErrorMap, DownsampledKeepsTheWorstPixelOfEachBlock) {
  ChannelError e;
  e.name = "v.x";
  e.width = 10, e.height = 7;
  const size_t n = 70;
  e.reference.assign(n, 1), e.gl.assign(n, 1), e.signed_error.assign(n, 0), e.allowed.assign(n, 1);
  e.ulps.assign(n, 1), e.allowed_ulps.assign(n, 2), e.compared.assign(n, true);
  e.ulps[size_t(6 * 10 + 9)] = 3;  // over its allowance, in the last (partial) block
  e.ulps[size_t(0 * 10 + 1)] = 1.5;
  const ChannelError d = downsampled(e, 4);
  ASSERT_EQ(d.width, 3);
  ASSERT_EQ(d.height, 2);
  EXPECT_EQ(d.ulps[size_t(1 * 3 + 2)], 3);
  EXPECT_EQ(d.ulps[0], 1.5);
  EXPECT_EQ(d.ulps[1], 1);
  EXPECT_EQ(worst_pixel(e), 69);
}

TEST(CoverageImage, RingsEveryFailingPixelAndOnlyThose) {
  const Frame ref = reference_frame();
  Frame gl = ref;
  gl.primitive[gl.index(6, 2)] = 0;  // GL only, far from every edge: a fill-rule error
  gl.primitive[gl.index(0, 4)] = Frame::kNoPrimitive;  // reference only, but an exact tie
  std::vector<uint8_t> edges(kW * kH, 0);
  edges[ref.index(0, 4)] = edge::tie | edge::snapping;
  const Expectation expected{ref, edges, Frame()};
  const int factor = upscale_factor(kW, kH);
  ASSERT_EQ(factor, 64);
  constexpr int kTitle = 50;  // the frame's image starts below the title
  const int image_end = kTitle + kH * factor;

  const Canvas canvas = render_coverage(expected, gl, CoverageStats{}, std::nullopt);
  const RingPixels rings = ring_pixels(canvas, image_end);
  // One ring of radius about 0.75 x 64 and 8 px wide: about pi (57.5^2 - 49.5^2) = 2,690
  // canvas pixels, none clipped.
  EXPECT_GT(rings.count, 2400u);
  EXPECT_LT(rings.count, 3000u);
  // Centred on frame pixel (6, 2): image column 6, image row 6 - 1 - 2 = 3.
  const int x0 = (canvas.width - kW * factor) / 2;
  const int cx = x0 + 6 * factor + factor / 2, cy = kTitle + 3 * factor + factor / 2;
  EXPECT_NEAR((rings.min_x + rings.max_x) / 2.0, cx, 1.0);
  EXPECT_NEAR((rings.min_y + rings.max_y) / 2.0, cy, 1.0);
  // Around the pixel, not on it: no ring colour anywhere in the pixel's 64 x 64 block, corners
  // included (the ring's inner radius, 49.5, is past the half diagonal, 45.3).
  EXPECT_GT(rings.max_x - rings.min_x, 2 * 49);
  const RingPixels block = ring_pixels_in(canvas, cx - factor / 2, cy - factor / 2, factor);
  EXPECT_EQ(block.count, 0u);
  // The legend explains the ring with a swatch of its own: a 14 x 14 square with an 8 x 8 hole.
  EXPECT_EQ(ring_pixels(canvas, canvas.height).count, rings.count + 14 * 14 - 8 * 8);

  // The exact tie fails only where ties count (--strict-coverage, --tolerance exact): a second
  // ring, cut by the image's left edge.
  EXPECT_GT(
      ring_pixels(render_coverage(expected, gl, CoverageStats{}, std::nullopt, true), image_end)
          .count,
      rings.count + 1000);
  // Nothing fails: no ring.
  EXPECT_EQ(
      ring_pixels(render_coverage(expected, ref, CoverageStats{}, std::nullopt), image_end).count,
      0u);
}

// A large frame's coverage picture shrinks as its maps do, and a single failing pixel among
// 1.1 million still shows: its block takes the failing colour and is ringed; band by band
// (blocks whole) it is the same picture.
TEST(CoverageImage, ALargeFrameIsShrunkAndKeepsItsOneFailingPixel) {
  constexpr int w = 1100, h = 1000;
  ASSERT_EQ(map_factor(w, h, 1), 2);
  Frame ref(w, h, 0);
  ref.primitive.assign(ref.pixel_count(), 0);
  Frame gl = ref;
  gl.primitive[gl.index(801, 333)] = Frame::kNoPrimitive;  // reference only: a fill-rule error
  const std::vector<uint8_t> edges(ref.pixel_count(), 0);
  const Expectation expected{ref, edges, Frame()};
  const Canvas canvas = render_coverage(expected, gl, CoverageStats{}, std::nullopt);
  ASSERT_EQ(upscale_factor(550, 500), 1);
  EXPECT_EQ(canvas.width, 550 + 2 * 12);
  constexpr int kTitle = 50;
  EXPECT_EQ(canvas.height, kTitle + 500 + 190);
  // Shown pixel (400, 166), image row 500 - 1 - 166: the fill-rule red, ringed around.
  const int x = (canvas.width - 550) / 2 + 400, y = kTitle + 500 - 1 - 166;
  const float* p = &canvas.rgb[(size_t(y) * size_t(canvas.width) + size_t(x)) * 3];
  EXPECT_EQ(p[0], 0.9f);
  EXPECT_EQ(p[1], 0.1f);
  EXPECT_EQ(p[2], 0.1f);
  const RingPixels rings = ring_pixels(canvas, kTitle + 500);
  EXPECT_GT(rings.count, 0u);
  EXPECT_NEAR((rings.min_x + rings.max_x) / 2.0, x + 0.5, 1.0);
  EXPECT_NEAR((rings.min_y + rings.max_y) / 2.0, y + 0.5, 1.0);
  // The other pixels agree: one shade of grey, in the frame's image.
  const float* agree = &canvas.rgb[(size_t(kTitle + 10) * size_t(canvas.width) + 30) * 3];
  EXPECT_EQ(agree[0], 0.24f);

  CoverageCanvas bands(w, h, CoverageStats{}, std::nullopt);
  for (int y0 = 0; y0 < h; y0 += 38) {
    const int rows = std::min(38, h - y0);
    bands.add_rows(Expectation{ref.rows(y0, rows), std::vector<uint8_t>(size_t(w) * rows, 0), {}},
                   gl.rows(y0, rows), y0);
  }
  const Canvas banded = bands.finish();
  EXPECT_TRUE(banded.rgb == canvas.rgb);
  // A band that splits a block is refused.
  CoverageCanvas odd(w, h, CoverageStats{}, std::nullopt);
  EXPECT_THROW(odd.add_rows(Expectation{ref.rows(3, 2), std::vector<uint8_t>(size_t(w) * 2, 0), {}},
                            gl.rows(3, 2), 3),
               std::invalid_argument);
}

// The colour of canvas pixel (x, y), and how many pixels of the w x h rectangle at (x0, y0)
// have exactly that colour.
Rgb colour_at(const Canvas& canvas, int x, int y) {
  const float* p = &canvas.rgb[(size_t(y) * size_t(canvas.width) + size_t(x)) * 3];
  return {p[0], p[1], p[2]};
}
bool same_colour(Rgb a, Rgb b) {
  return a.r == b.r && a.g == b.g && a.b == b.b;
}
int pixels_of_colour(const Canvas& canvas, int x0, int y0, int w, int h, Rgb colour) {
  int n = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      n += same_colour(colour_at(canvas, x, y), colour);
  return n;
}

// A count-only mismatch (both frames name primitive 0, GL wrote 2 fragments where the reference
// wrote 1) is painted in its label's colour: fill rule away from every edge, double hit beside a
// shared edge; it is no "other primitive" (orange, the colour these pixels had when the picture
// was painted by which frame covered what), and has no mark, while a GL-only pixel has one.
TEST(CoverageImage, ACountOnlyMismatchIsPaintedInItsLabelsColour) {
  const Case c = one_triangle_case();
  Frame ref = reference_frame();
  ref.fragments.assign(ref.pixel_count(), 0);
  for (size_t i = 0; i < ref.pixel_count(); ++i)
    ref.fragments[i] = ref.primitive[i] == Frame::kNoPrimitive ? 0 : 1;
  Frame allowed(kW, kH, 1);
  allowed.primitive = ref.primitive;
  allowed.components[0].assign(allowed.pixel_count(), 2 * kUlp);
  allowed.depth.assign(allowed.pixel_count(), 0x1p-23f);
  // Two frame pixels apart at least, so that no pixel's ring reaches another's block.
  std::vector<uint8_t> edges(kW * kH, 0);
  edges[ref.index(4, 1)] = edge::shared;
  edges[ref.index(1, 3)] = edge::shared;
  Frame gl = ref;
  gl.fragments[gl.index(1, 1)] = 2;  // no edge bit: a fill-rule error
  gl.fragments[gl.index(4, 1)] = 2;  // beside a shared edge: a double hit
  gl.fragments[gl.index(1, 3)] = 0;  // beside a shared edge: a gap
  gl.primitive[gl.index(6, 3)] = 0, gl.fragments[gl.index(6, 3)] = 1;  // GL only: fill rule
  const Expectation expected{ref, edges, allowed};
  const Tolerance t;
  const CaseResult r = compare::compare(c, expected, gl, t);
  ASSERT_EQ(r.coverage.fill_rule, 2u);
  ASSERT_EQ(r.coverage.double_hits, 1u);
  ASSERT_EQ(r.coverage.gaps, 1u);
  ASSERT_EQ(r.coverage.exact_tie + r.coverage.within_snapping, 0u);

  const Canvas canvas = render_coverage(expected, gl, r.coverage, std::nullopt);
  const int factor = upscale_factor(kW, kH);
  constexpr int kTitle = 50;
  const int x0 = (canvas.width - kW * factor) / 2;
  // Frame pixel (x, y)'s block: image row kH - 1 - y.
  const auto block_x = [&](int x) { return x0 + x * factor; };
  const auto block_y = [&](int y) { return kTitle + (kH - 1 - y) * factor; };
  const Rgb red{0.9f, 0.1f, 0.1f}, magenta{0.95f, 0.0f, 0.95f}, cyan{0.0f, 0.9f, 0.9f};
  const Rgb other_primitive{1.0f, 0.55f, 0.0f};
  EXPECT_TRUE(same_colour(label_colour(CoverageStats::Label::fill_rule), red));
  // Every pixel of each count-only block in its label's colour: no mark.
  const auto block_pixels = [&](int x, int y, Rgb colour) {
    return pixels_of_colour(canvas, block_x(x), block_y(y), factor, factor, colour);
  };
  EXPECT_EQ(block_pixels(1, 1, red), factor * factor);
  EXPECT_EQ(block_pixels(1, 1, other_primitive), 0);
  EXPECT_EQ(block_pixels(4, 1, magenta), factor * factor);
  EXPECT_EQ(block_pixels(1, 3, cyan), factor * factor);
  // The GL-only pixel: red around a white mark in its centre (GL covers what the reference
  // does not).
  EXPECT_TRUE(same_colour(colour_at(canvas, block_x(6) + 2, block_y(3) + 2), red));
  EXPECT_TRUE(same_colour(colour_at(canvas, block_x(6) + factor / 2, block_y(3) + factor / 2),
                          Rgb{1, 1, 1}));
  EXPECT_LT(block_pixels(6, 3, red), factor * factor);
  // An agreeing pixel keeps its primitive's grey.
  EXPECT_EQ(block_pixels(3, 3, Rgb{0.24f, 0.24f, 0.24f}), factor * factor);

  // The legend's counts are the comparison's.
  for (const LegendEntry& e : coverage_legend(r.coverage)) {
    EXPECT_EQ(e.count, label_count(r.coverage, e.label));
    EXPECT_TRUE(same_colour(e.colour, label_colour(e.label)));
  }
}

// A shrunk picture shows each block's most severe label: a double hit beside a fill-rule error
// and an exact tie in one 2 x 2 block.
TEST(CoverageImage, AShrunkBlockShowsItsMostSevereLabel) {
  constexpr int w = 1100, h = 1000;
  ASSERT_EQ(map_factor(w, h, 1), 2);
  Frame ref(w, h, 0);
  ref.primitive.assign(ref.pixel_count(), 0);
  ref.fragments.assign(ref.pixel_count(), 1);
  Frame gl = ref;
  std::vector<uint8_t> edges(ref.pixel_count(), 0);
  gl.fragments[gl.index(800, 332)] = 2;  // a fill-rule error, first in row order
  gl.fragments[gl.index(801, 333)] = 2;  // a double hit
  edges[ref.index(801, 333)] = edge::shared;
  gl.primitive[gl.index(800, 333)] = Frame::kNoPrimitive;  // an exact tie
  edges[ref.index(800, 333)] = edge::tie;
  const Expectation expected{ref, edges, Frame()};
  ASSERT_EQ(compare::coverage_label(expected, gl, ref.index(800, 332)),
            CoverageStats::Label::fill_rule);
  ASSERT_EQ(compare::coverage_label(expected, gl, ref.index(801, 333)),
            CoverageStats::Label::double_hit);
  ASSERT_EQ(compare::coverage_label(expected, gl, ref.index(800, 333)),
            CoverageStats::Label::exact_tie);
  const Canvas canvas = render_coverage(expected, gl, CoverageStats{}, std::nullopt);
  constexpr int kTitle = 50;
  const int x = (canvas.width - 550) / 2 + 400, y = kTitle + 500 - 1 - 166;
  EXPECT_TRUE(same_colour(colour_at(canvas, x, y), Rgb{0.95f, 0.0f, 0.95f}));
}

// The legend lists every label once with its count from CoverageStats, as "fill-rule error: 3",
// in the label's colour.
TEST(CoverageImage, TheLegendGivesEachLabelsCount) {
  CoverageStats stats;
  stats.exact_tie = 1, stats.within_snapping = 2, stats.fill_rule = 3, stats.gaps = 4;
  stats.double_hits = 5;
  const std::vector<LegendEntry> legend = coverage_legend(stats);
  std::vector<std::string> texts;
  for (const LegendEntry& e : legend) {
    texts.push_back(e.text);
    EXPECT_EQ(e.count, label_count(stats, e.label));
    EXPECT_TRUE(same_colour(e.colour, label_colour(e.label)));
  }
  EXPECT_EQ(texts, (std::vector<std::string>{"fill-rule error: 3", "gap on a shared edge: 4",
                                             "double hit on a shared edge: 5", "exact tie: 1",
                                             "within snapping: 2"}));
  // One colour per label, the explained ones lighter (a larger sum of channels) than any
  // failure's.
  for (size_t a = 0; a < legend.size(); ++a)
    for (size_t b = a + 1; b < legend.size(); ++b)
      EXPECT_FALSE(same_colour(legend[a].colour, legend[b].colour)) << a << " " << b;
  const auto lightness = [](Rgb c) { return c.r + c.g + c.b; };
  for (const LegendEntry& e : legend)
    for (const LegendEntry& f : legend)
      if (compare::explained(e.label) && !compare::explained(f.label)) {
        EXPECT_GT(lightness(e.colour), lightness(f.colour)) << e.text << " " << f.text;
      }

  // Each label's swatch is in the picture's legend, below the frame.
  const Frame ref = reference_frame();
  const Canvas canvas = render_coverage(Expectation{ref, std::vector<uint8_t>(kW * kH, 0), {}}, ref,
                                        stats, std::nullopt);
  const int legend_top = 50 + kH * upscale_factor(kW, kH);
  for (const LegendEntry& e : legend)
    EXPECT_GE(
        pixels_of_colour(canvas, 0, legend_top, canvas.width, canvas.height - legend_top, e.colour),
        14 * 14)
        << e.text;
}

TEST_F(ReportTest, DiffImagesShowNonFiniteValuesInMagenta) {
  const Case c = one_triangle_case();
  const Frame ref = reference_frame();
  Frame gl = ref;
  gl.components[0][gl.index(1, 1)] = std::numeric_limits<float>::quiet_NaN();
  write_diff_images(dir_, c, Expectation{ref, {}, Frame()}, gl, CaseResult{});

  EXPECT_TRUE(shows_frame_pixel_of(read_image(dir_ / "v.x_error.png"), 255, 0, 255));
  EXPECT_FALSE(shows_frame_pixel_of(read_image(dir_ / "depth_error.png"), 255, 0, 255));
  EXPECT_TRUE(std::isnan(read_image(dir_ / "v.x_gl.exr").at(1, kH - 2)));
}

TEST_F(ReportTest, DiffImagesRejectFramesOfAnotherSize) {
  const Case c = one_triangle_case();
  EXPECT_THROW(write_diff_images(dir_, c, Expectation{reference_frame(), {}, Frame()},
                                 Frame(4, 4, 1), CaseResult{}),
               std::runtime_error);
}

TEST(ChannelError, APixelWonByAnotherFragmentIsJudgedByThatFragment) {
  Case c = one_triangle_case();
  c.depth_func = DepthFunc::less;
  c.triangles = {{0, 1, 2}, {0, 1, 2}};
  Expectation e{reference_frame(), std::vector<uint8_t>(size_t(kW) * kH, 0), Frame()};
  const size_t i = e.frame.index(kErrX, kErrY);
  e.edges[i] = edge::depth_order;
  // The second triangle's fragment at that pixel may win: its value is 7.
  e.candidates.push_back({i, 1, 0.5f, 1e-6f, {7.0f}, {1e-6f}});
  Frame gl = e.frame;
  gl.primitive[i] = 1;
  gl.components[0][i] = 7.0f;
  const ChannelError err =
      channel_error(c, e, gl, Channel::component(0), Tolerance{ToleranceMode::ulps});
  EXPECT_TRUE(err.compared[i]);
  EXPECT_EQ(err.reference[i], 7.0f);
  EXPECT_EQ(err.signed_error[i], 0.0f);
  // Where GL names a triangle that is neither the winner nor a candidate, nothing is compared.
  gl.primitive[e.frame.index(0, 0)] = 1;
  EXPECT_FALSE(channel_error(c, e, gl, Channel::component(0), Tolerance{ToleranceMode::ulps})
                   .compared[e.frame.index(0, 0)]);
}

}  // namespace
}  // namespace glrc::report::test
