// write_diff_images: the files a person opens to see where and how GL differs from the
// reference. PNGs to look at, EXRs to read exact values from.
#include <cmath>
#include <stdexcept>

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

  std::vector<std::filesystem::path> written;
  for (int channel = compare::kDepth; channel < c.component_count(); ++channel) {
    const ChannelError e = channel_error(c, expected, gl, channel, r.tolerance);
    const std::string stem = file_stem(e.name);
    const auto out = [&](const std::string& suffix) {
      written.push_back(dir / (stem + suffix));
      return written.back();
    };
    double tolerance = NAN;
    if (fixed)
      for (const auto& ch : r.channels)
        if (ch.name == e.name) tolerance = ch.tolerance_ulps;
    write_png(render_heatmap(e, tolerance, font), out("_error.png"));
    const ChannelError allowed = as_allowance_map(e);
    write_png(render_heatmap(allowed, NAN, font), out("_allowed.png"));
    write_png(render_heatmap(as_ratio_map(e), 1.0, font), out("_ratio.png"));
    write_exr(out("_error.exr"), e.width, e.height, e.signed_error,
              e.name + ": GL - reference, NaN where not covered by the same primitive in both");
    write_exr(out("_allowed.exr"), e.width, e.height, e.allowed,
              e.name + ": allowed |GL - reference|, NaN where not compared");
    write_exr(out("_gl.exr"), e.width, e.height, e.gl, e.name + ": GL");
    write_exr(out("_ref.exr"), e.width, e.height, e.reference, e.name + ": reference");
  }
  written.push_back(dir / "coverage.png");
  write_png(render_coverage(expected, gl, r.coverage, font, explained_mismatches_fail(r.tolerance)),
            written.back());
  return written;
}

}  // namespace glrc::report
