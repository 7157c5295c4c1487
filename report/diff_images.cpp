// write_diff_images: the files a person opens to see where and how GL differs from the
// reference. PNGs to look at, EXRs to read exact values from.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "compare/compare.hpp"
#include "report/channel_error.hpp"
#include "report/coverage_image.hpp"
#include "report/exr.hpp"
#include "report/heatmap.hpp"
#include "report/report.hpp"

namespace glrc::report {
namespace {

// Varying names come from case files; keep file names portable whatever they hold.
std::string file_stem(const std::string& channel) {
  std::string stem = channel;
  for (char& ch : stem) {
    const bool plain = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                       (ch >= '0' && ch <= '9') || ch == '.' || ch == '_' || ch == '-';
    if (!plain) ch = '_';
  }
  return stem;
}

void check_frame(const Case& c, const Frame& f, const Frame& reference, const char* which) {
  const size_t n = reference.pixel_count();
  bool fits = f.width == reference.width && f.height == reference.height &&
              f.primitive.size() == n && f.depth.size() == n &&
              f.components.size() == size_t(c.component_count());
  for (const auto& values : f.components)
    fits = fits && values.size() == n;
  if (!fits)
    throw std::runtime_error("diff images of " + c.name + ": the " + which +
                             " frame does not match the case's layout");
}

// Frames larger than this get pictures of their worst pixels instead of every pixel: a 4096 x
// 4096 case with 7 vec4 varyings would otherwise write ~200 full-size maps (1.2 GB) before the
// worker can move on.
constexpr size_t kFullResolutionPixels = size_t(1) << 20;
constexpr int kLargestMapSide = 1024, kTileSide = 256;

// The square of at most kTileSide pixels around pixel `centre`, inside the frame.
struct Tile {
  int x0, y0, width, height;
};
Tile tile_around(const ChannelError& e, long centre) {
  const int cx = int(centre % e.width), cy = int(centre / e.width);
  Tile t{0, 0, std::min(kTileSide, e.width), std::min(kTileSide, e.height)};
  t.x0 = std::clamp(cx - t.width / 2, 0, e.width - t.width);
  t.y0 = std::clamp(cy - t.height / 2, 0, e.height - t.height);
  return t;
}
template <typename T>
std::vector<T> cut(const std::vector<T>& v, int frame_width, const Tile& t) {
  std::vector<T> out;
  out.reserve(size_t(t.width) * size_t(t.height));
  for (int y = t.y0; y < t.y0 + t.height; ++y)
    for (int x = t.x0; x < t.x0 + t.width; ++x)
      out.push_back(v[size_t(y) * size_t(frame_width) + size_t(x)]);
  return out;
}

}  // namespace

std::vector<std::filesystem::path> write_diff_images(const std::filesystem::path& dir,
                                                     const Case& c, const Expectation& expected,
                                                     const Frame& gl, const CaseResult& r) {
  const Frame& reference = expected.frame;
  check_frame(c, reference, reference, "reference");
  check_frame(c, gl, reference, "GL");
  std::filesystem::create_directories(dir);
  const auto font = find_font();
  // A fixed threshold is marked on the legend; the specification's varies per pixel.
  const bool fixed = r.tolerance.mode != ToleranceMode::spec;

  // A large frame: maps only of the channels that fail, shrunk to kLargestMapSide showing each
  // block's worst pixel, and full-resolution EXRs of a tile around the worst pixel.
  const bool large = reference.pixel_count() > kFullResolutionPixels;
  const int factor =
      large ? (std::max(reference.width, reference.height) + kLargestMapSide - 1) / kLargestMapSide
            : 1;
  std::vector<std::filesystem::path> written;
  for (int channel = compare::kDepth; channel < c.component_count(); ++channel) {
    const std::string name =
        channel == compare::kDepth ? "depth" : component_names(c).at(size_t(channel));
    double tolerance = NAN;
    bool passes = false;
    for (const auto& ch : r.channels)
      if (ch.name == name) tolerance = fixed ? ch.tolerance_ulps : NAN, passes = ch.pass();
    if (large && passes) continue;
    const ChannelError e = channel_error(c, expected, gl, channel, r.tolerance);
    const std::string stem = file_stem(e.name);
    const auto out = [&](const std::string& suffix) {
      written.push_back(dir / (stem + suffix));
      return written.back();
    };
    ChannelError shown = downsampled(e, factor);
    if (factor > 1)
      shown.quantity += fmt::format(" (each pixel the worst of {}x{})", factor, factor);
    write_png(render_heatmap(shown, tolerance, font), out("_error.png"));
    write_png(render_heatmap(as_allowance_map(shown), NAN, font), out("_allowed.png"));
    write_png(render_heatmap(as_ratio_map(shown), 1.0, font), out("_ratio.png"));
    if (!large) {
      write_exr(out("_error.exr"), e.width, e.height, e.signed_error,
                e.name + ": GL - reference, NaN where not covered by the same primitive in both");
      write_exr(out("_allowed.exr"), e.width, e.height, e.allowed,
                e.name + ": allowed |GL - reference|, NaN where not compared");
      write_exr(out("_gl.exr"), e.width, e.height, e.gl, e.name + ": GL");
      write_exr(out("_ref.exr"), e.width, e.height, e.reference, e.name + ": reference");
      continue;
    }
    const long worst = worst_pixel(e);
    if (worst < 0) continue;
    const Tile t = tile_around(e, worst);
    const std::string where =
        fmt::format(", pixels ({}, {}) to ({}, {}) around the worst ({}, {})", t.x0, t.y0,
                    t.x0 + t.width - 1, t.y0 + t.height - 1, worst % e.width, worst / e.width);
    write_exr(
        out("_error_tile.exr"), t.width, t.height, cut(e.signed_error, e.width, t),
        e.name + ": GL - reference, NaN where not covered by the same primitive in both" + where);
    write_exr(out("_allowed_tile.exr"), t.width, t.height, cut(e.allowed, e.width, t),
              e.name + ": allowed |GL - reference|, NaN where not compared" + where);
    write_exr(out("_gl_tile.exr"), t.width, t.height, cut(e.gl, e.width, t),
              e.name + ": GL" + where);
    write_exr(out("_ref_tile.exr"), t.width, t.height, cut(e.reference, e.width, t),
              e.name + ": reference" + where);
  }
  written.push_back(dir / "coverage.png");
  write_png(render_coverage(expected, gl, r.coverage, font, explained_mismatches_fail(r.tolerance)),
            written.back());
  return written;
}

}  // namespace glrc::report
