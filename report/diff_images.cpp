// write_diff_images: the files a person opens to see where and how GL differs from the
// reference. PNGs to look at, EXRs to read exact values from.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <utility>

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

// Frames of more than 2^20 pixels (map_factor > 1) get pictures of their worst pixels instead
// of every pixel: a 4096 x 4096 case with 7 vec4 varyings would otherwise write ~200 full-size
// maps (1.2 GB) before the worker can move on.
constexpr int kTileSide = 256;

// The square of at most kTileSide pixels around pixel `centre` of a width x height frame,
// inside it.
struct Tile {
  int x0, y0, width, height;
};
Tile tile_around(int width, int height, long centre) {
  const int cx = int(centre % width), cy = int(centre / width);
  Tile t{0, 0, std::min(kTileSide, width), std::min(kTileSide, height)};
  t.x0 = std::clamp(cx - t.width / 2, 0, width - t.width);
  t.y0 = std::clamp(cy - t.height / 2, 0, height - t.height);
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

// The channels a picture is made of, with the fixed tolerance marked on the legend (NaN for
// the specification's, which varies per pixel): every one, or of a large frame the failing ones.
struct Shown {
  Channel channel;
  std::string name;
  double tolerance;
};
std::vector<Shown> shown_channels(const Case& c, const CaseResult& r, bool large) {
  const bool fixed = r.tolerance.mode != ToleranceMode::spec;
  std::vector<Shown> out;
  for (Channel channel : channels_of(c.component_count())) {
    const std::string name = channel_name(c, channel);
    double tolerance = NAN;
    bool passes = false;
    for (const auto& ch : r.channels)
      if (ch.name == name) tolerance = fixed ? ch.tolerance_ulps : NAN, passes = ch.pass();
    if (!(large && passes)) out.push_back({channel, name, tolerance});
  }
  return out;
}

// Writes one channel's three PNG maps from `shown` (already shrunk by `factor`).
void write_maps(const ChannelError& shown, int factor, double tolerance,
                const std::optional<std::string>& font,
                const std::function<std::filesystem::path(const std::string&)>& out) {
  // Each map says it is shrunk (as_allowance_map and as_ratio_map set their own quantity).
  auto shrunk = [&](ChannelError map) {
    if (factor > 1) map.quantity += fmt::format(" (each pixel the worst of {}x{})", factor, factor);
    return map;
  };
  write_png(render_heatmap(shrunk(shown), tolerance, font), out("_error.png"));
  write_png(render_heatmap(shrunk(as_allowance_map(shown)), NAN, font), out("_allowed.png"));
  write_png(render_heatmap(shrunk(as_ratio_map(shown)), 1.0, font), out("_ratio.png"));
}

// The tile's pixels of one channel, as four value planes.
struct TileValues {
  std::vector<float> signed_error, allowed, gl, reference;
};

// Writes the full-resolution EXRs of tile t around pixel `worst` of a frame `width` wide.
void write_tile(const std::string& name, const TileValues& v, const Tile& t, long worst, int width,
                const std::function<std::filesystem::path(const std::string&)>& out) {
  const std::string where =
      fmt::format(", pixels ({}, {}) to ({}, {}) around the worst ({}, {})", t.x0, t.y0,
                  t.x0 + t.width - 1, t.y0 + t.height - 1, worst % width, worst / width);
  write_exr(out("_error_tile.exr"), t.width, t.height, v.signed_error,
            name + ": GL - reference, NaN where not covered by the same primitive in both" + where);
  write_exr(out("_allowed_tile.exr"), t.width, t.height, v.allowed,
            name + ": allowed |GL - reference|, NaN where not compared" + where);
  write_exr(out("_gl_tile.exr"), t.width, t.height, v.gl, name + ": GL" + where);
  write_exr(out("_ref_tile.exr"), t.width, t.height, v.reference, name + ": reference" + where);
}

}  // namespace

std::vector<std::string> diff_image_names(const Case& c) {
  std::vector<std::string> names;
  for (Channel channel : channels_of(c.component_count())) {
    const std::string stem = file_stem(channel_name(c, channel));
    for (const char* suffix :
         {"_error.png", "_allowed.png", "_ratio.png", "_error.exr", "_allowed.exr", "_gl.exr",
          "_ref.exr", "_error_tile.exr", "_allowed_tile.exr", "_gl_tile.exr", "_ref_tile.exr"})
      names.push_back(stem + suffix);
  }
  names.push_back("coverage.png");
  return names;
}

std::vector<std::filesystem::path> write_diff_images(const std::filesystem::path& dir,
                                                     const Case& c, const Expectation& expected,
                                                     const Frame& gl, const CaseResult& r,
                                                     const BeforeWrite& before_write) {
  const Frame& reference = expected.frame;
  check_frame(c, reference, reference, "reference");
  check_frame(c, gl, reference, "GL");
  std::filesystem::create_directories(dir);
  const auto font = find_font();
  // A large frame: maps only of the channels that fail, shrunk by map_factor showing each
  // block's worst pixel, and full-resolution EXRs of a tile around the worst pixel.
  const bool large = map_factor(c.fb_width, c.fb_height, 1) > 1;
  const std::vector<Shown> all = shown_channels(c, r, large);
  const int factor = map_factor(c.fb_width, c.fb_height, all.size());
  std::vector<std::filesystem::path> written;
  for (const Shown& shown : all) {
    const ChannelError e = channel_error(c, expected, gl, shown.channel, r.tolerance);
    const std::string stem = file_stem(e.name);
    const auto out = [&](const std::string& suffix) {
      written.push_back(dir / (stem + suffix));
      if (before_write) before_write(written.back());
      return written.back();
    };
    write_maps(downsampled(e, factor), factor, shown.tolerance, font, out);
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
    const Tile t = tile_around(e.width, e.height, worst);
    write_tile(e.name,
               {cut(e.signed_error, e.width, t), cut(e.allowed, e.width, t), cut(e.gl, e.width, t),
                cut(e.reference, e.width, t)},
               t, worst, e.width, out);
  }
  written.push_back(dir / "coverage.png");
  if (before_write) before_write(written.back());
  write_png(render_coverage(expected, gl, r.coverage, font, explained_mismatches_fail(r.tolerance)),
            written.back());
  return written;
}

std::vector<std::filesystem::path> write_streamed_diff_images(const std::filesystem::path& dir,
                                                              const Case& c, const CaseResult& r,
                                                              int slice_rows,
                                                              const SliceSource& slice) {
  const int width = c.fb_width, height = c.fb_height;
  const bool large = map_factor(width, height, 1) > 1;
  if (!large) {
    // Full-resolution pictures need whole frames, and a small frame's are small: stacked.
    std::pair<Expectation, Frame> whole = slice(0, height);
    return write_diff_images(dir, c, whole.first, whole.second, r);
  }
  std::filesystem::create_directories(dir);
  const auto font = find_font();
  const std::vector<Shown> channels = shown_channels(c, r, large);
  const int factor = map_factor(width, height, channels.size());
  // Slices of whole blocks, so that each block of the maps lies in one slice.
  const int rows = std::max(1, slice_rows / factor) * factor;

  // First pass: every channel's shrunk map (within kMapBytes together), its worst pixel, and
  // coverage.png, slice by slice.
  struct Worst {
    long pixel = -1;
    std::array<double, 4> badness{};
  };
  std::vector<ChannelError> maps(channels.size());
  std::vector<Worst> worst(channels.size());
  CoverageCanvas coverage(width, height, r.coverage, font, explained_mismatches_fail(r.tolerance));
  // Each map's storage taken once (growing it slice by slice would hold twice as much at times).
  const size_t map_pixels =
      size_t((width + factor - 1) / factor) * size_t((height + factor - 1) / factor);
  auto append = [&](ChannelError& to, const ChannelError& rows_of) {
    if (to.height == 0) {
      to.name = rows_of.name, to.quantity = rows_of.quantity, to.unit = rows_of.unit;
      to.judged = rows_of.judged, to.width = rows_of.width;
      to.ulps.reserve(map_pixels), to.allowed_ulps.reserve(map_pixels);
      to.compared.reserve(map_pixels);
    }
    to.height += rows_of.height;
    auto add = [](auto& a, const auto& b) { a.insert(a.end(), b.begin(), b.end()); };
    add(to.ulps, rows_of.ulps), add(to.allowed_ulps, rows_of.allowed_ulps);
    add(to.compared, rows_of.compared);
    to.max_finite_ulps = std::max(to.max_finite_ulps, rows_of.max_finite_ulps);
    to.non_finite += rows_of.non_finite;
  };
  for (int y0 = 0; y0 < height; y0 += rows) {
    const auto [expected, gl] = slice(y0, std::min(rows, height - y0));
    coverage.add_rows(expected, gl, y0);
    for (size_t k = 0; k < channels.size(); ++k) {
      const ChannelError e = channel_error(c, expected, gl, channels[k].channel, r.tolerance);
      append(maps[k], downsampled(e, factor));
      // The first of the worst pixels in row order, as worst_pixel picks it on a whole frame.
      if (const long w = worst_pixel(e); w >= 0) {
        const auto b = badness(e, size_t(w));
        if (worst[k].pixel < 0 || b > worst[k].badness) worst[k] = {long(y0) * width + w, b};
      }
    }
  }
  std::vector<std::vector<std::filesystem::path>> files(channels.size());
  for (size_t k = 0; k < channels.size(); ++k) {
    const auto out = [&](const std::string& suffix) {
      files[k].push_back(dir / (file_stem(channels[k].name) + suffix));
      return files[k].back();
    };
    write_maps(maps[k], factor, channels[k].tolerance, font, out);
    maps[k] = ChannelError();
  }
  std::filesystem::path coverage_png = dir / "coverage.png";
  write_png(coverage.finish(), coverage_png);

  // Second pass: the tiles around the worst pixels, all of them in one pass over the rows any
  // of them covers.
  std::vector<Tile> tiles(channels.size());
  std::vector<TileValues> values(channels.size());
  std::vector<std::pair<int, int>> spans;  // rows [first, last) some tile needs, merged
  for (size_t k = 0; k < channels.size(); ++k) {
    if (worst[k].pixel < 0) continue;
    tiles[k] = tile_around(width, height, worst[k].pixel);
    spans.push_back({tiles[k].y0, tiles[k].y0 + tiles[k].height});
  }
  std::sort(spans.begin(), spans.end());
  std::vector<std::pair<int, int>> merged;
  for (const auto& span : spans)
    if (!merged.empty() && span.first <= merged.back().second)
      merged.back().second = std::max(merged.back().second, span.second);
    else
      merged.push_back(span);
  for (const auto& [first, last] : merged)
    for (int y0 = first; y0 < last; y0 += rows) {
      const int n = std::min(rows, last - y0);
      const auto [expected, gl] = slice(y0, n);
      for (size_t k = 0; k < channels.size(); ++k) {
        const Tile& t = tiles[k];
        const int from = std::max(y0, t.y0), to = std::min(y0 + n, t.y0 + t.height);
        if (worst[k].pixel < 0 || from >= to) continue;
        const ChannelError e = channel_error(c, expected, gl, channels[k].channel, r.tolerance);
        const Tile part{t.x0, from - y0, t.width, to - from};
        auto add = [&](std::vector<float>& into, const std::vector<float>& from_slice) {
          const std::vector<float> piece = cut(from_slice, e.width, part);
          into.insert(into.end(), piece.begin(), piece.end());
        };
        add(values[k].signed_error, e.signed_error), add(values[k].allowed, e.allowed);
        add(values[k].gl, e.gl), add(values[k].reference, e.reference);
      }
    }
  std::vector<std::filesystem::path> written;
  for (size_t k = 0; k < channels.size(); ++k) {
    if (worst[k].pixel >= 0) {
      const auto out = [&](const std::string& suffix) {
        files[k].push_back(dir / (file_stem(channels[k].name) + suffix));
        return files[k].back();
      };
      write_tile(channels[k].name, values[k], tiles[k], worst[k].pixel, width, out);
      values[k] = TileValues();
    }
    written.insert(written.end(), files[k].begin(), files[k].end());
  }
  written.push_back(coverage_png);
  return written;
}

}  // namespace glrc::report
