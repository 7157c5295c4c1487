// write_diff_images: the files a person opens to see where and how GL differs from the
// reference. PNGs to look at, EXRs to read exact values from.
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

// The channel's tolerance as the comparator applied it, or the case's when it has no stats.
double tolerance_of(const CaseResult& r, const std::string& channel, bool depth) {
  for (const auto& ch : r.channels)
    if (ch.name == channel) return ch.tolerance_ulps;
  return depth ? r.tolerance.depth_ulps : r.tolerance.varying_ulps;
}

}  // namespace

std::vector<std::filesystem::path> write_diff_images(const std::filesystem::path& dir,
                                                     const Case& c, const Frame& reference,
                                                     const std::vector<uint8_t>& edge_band,
                                                     const Frame& gl, const CaseResult& r) {
  check_frame(c, reference, reference, "reference");
  check_frame(c, gl, reference, "GL");
  std::filesystem::create_directories(dir);
  const auto font = find_font();

  std::vector<std::filesystem::path> written;
  for (int channel = compare::kDepth; channel < c.component_count(); ++channel) {
    const ChannelError e = channel_error(c, reference, gl, channel);
    const std::string stem = file_stem(e.name);
    const auto out = [&](const std::string& suffix) {
      written.push_back(dir / (stem + suffix));
      return written.back();
    };
    write_png(render_heatmap(e, tolerance_of(r, e.name, channel == compare::kDepth), font),
              out("_error.png"));
    write_exr(out("_error.exr"), e.width, e.height, e.signed_error,
              e.name + ": GL - reference, NaN where not covered by the same primitive in both");
    write_exr(out("_gl.exr"), e.width, e.height, e.gl, e.name + ": GL");
    write_exr(out("_ref.exr"), e.width, e.height, e.reference, e.name + ": reference");
  }
  written.push_back(dir / "coverage.png");
  write_png(render_coverage(reference, gl, edge_band, r.coverage, font), written.back());
  return written;
}

}  // namespace glrc::report
