#include "report/coverage_image.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "compare/compare.hpp"
#include "report/channel_error.hpp"
#include "report/format.hpp"

namespace glrc::report {
namespace {

constexpr int kMargin = 12;
constexpr int kTitleHeight = 50;
constexpr int kMinWidth = 512;
constexpr int kLegendHeight = 144;
constexpr Rgb kBackground{0.1f, 0.1f, 0.1f};
constexpr Rgb kText{0.92f, 0.92f, 0.92f};

constexpr Rgb kNeither{0.03f, 0.03f, 0.03f};
constexpr Rgb kReferenceOnly{0.9f, 0.1f, 0.1f};
constexpr Rgb kGlOnly{0.15f, 0.35f, 1.0f};
constexpr Rgb kOtherPrimitive{1.0f, 0.55f, 0.0f};
constexpr Rgb kWhite{1, 1, 1};
constexpr Rgb kGap{0.0f, 0.9f, 0.9f};          // cyan: no fragment where a mesh needs one
constexpr Rgb kDoubleHit{0.95f, 0.0f, 0.95f};  // magenta: two fragments on a shared edge
// Rings around failing pixels: a hue no pixel colour uses.
constexpr Rgb kFailRing{0.3f, 1.0f, 0.2f};
// The edge band only hints where boundary mismatches would be allowed, so it is a faint tint.
constexpr Rgb kEdgeTint{0.85f, 0.8f, 0.25f};
constexpr float kEdgeTintAmount = 0.22f;
// Boundary mismatches are the forgivable kind: the same hue, lighter.
constexpr float kBoundaryLightening = 0.55f;

// Agreeing pixels: dim grey, a shade per primitive so that triangle edges remain visible.
Rgb same_primitive(int32_t primitive) {
  const float grey = 0.24f + 0.07f * float(primitive % 4);
  return {grey, grey, grey};
}

Rgb pixel_colour(int32_t ref, int32_t gl, bool in_edge_band,
                 std::optional<CoverageStats::Label> label) {
  using Label = CoverageStats::Label;
  if (label == Label::gap) return kGap;
  if (label == Label::double_hit) return kDoubleHit;
  if (!label) {
    const Rgb base = ref == Frame::kNoPrimitive ? kNeither : same_primitive(ref);
    return in_edge_band ? mix(base, kEdgeTint, kEdgeTintAmount) : base;
  }
  const Rgb hue = gl == Frame::kNoPrimitive    ? kReferenceOnly
                  : ref == Frame::kNoPrimitive ? kGlOnly
                                               : kOtherPrimitive;
  return compare::explained(*label) ? mix(hue, kWhite, kBoundaryLightening) : hue;
}

void swatch(Canvas& canvas, const std::optional<std::string>& font, int x, int y, Rgb colour,
            const std::string& label) {
  canvas.fill(x, y, 14, 14, colour);
  draw_text(canvas, font, x + 20, y + 12, label, 13, kText);
}

void draw_legend(Canvas& canvas, const std::optional<std::string>& font, int top) {
  const int x0 = kMargin + 8, column = (canvas.width - 2 * x0) / 2;
  const int row1 = top + 14, row2 = row1 + 24, row3 = row2 + 24;
  swatch(canvas, font, x0, row1, same_primitive(0), "same primitive (shade per id)");
  swatch(canvas, font, x0 + column, row1, kReferenceOnly, "reference only");
  swatch(canvas, font, x0, row2, kGlOnly, "GL only");
  swatch(canvas, font, x0 + column, row2, kOtherPrimitive, "other primitive");
  // The three lighter tints side by side stand for "boundary" of each kind.
  int x = x0;
  for (Rgb hue : {kReferenceOnly, kGlOnly, kOtherPrimitive}) {
    canvas.fill(x, row3, 8, 14, mix(hue, kWhite, kBoundaryLightening));
    x += 8;
  }
  draw_text(canvas, font, x + 6, row3 + 12, "lighter: tie or within snapping", 13, kText);
  swatch(canvas, font, x0 + column, row3, mix(same_primitive(0), kEdgeTint, kEdgeTintAmount),
         "edge band (reference)");
  const int row4 = row3 + 24;
  swatch(canvas, font, x0, row4, kGap, "gap on a shared edge");
  swatch(canvas, font, x0 + column, row4, kDoubleHit, "double hit on a shared edge");
  const int row5 = row4 + 24;
  canvas.fill(x0, row5, 14, 14, kFailRing);
  canvas.fill(x0 + 3, row5 + 3, 8, 8, kBackground);
  draw_text(canvas, font, x0 + 20, row5 + 12, "ring: a failing pixel (counts against the verdict)",
            13, kText);
}

// A ring of the upscaled frame pixel (x, y) at (x0, y0) with `factor`: clear of the pixel's
// corners, at least 5 canvas pixels out so that it shows at factor 1, and drawn only inside the
// frame's image (never over title or legend).
void draw_ring(Canvas& canvas, int x0, int y0, int factor, int frame_width, int frame_height, int x,
               int y) {
  const double cx = x0 + (x + 0.5) * factor, cy = y0 + (frame_height - 1 - y + 0.5) * factor;
  const double inner = std::max(0.75 * factor + 1.5, 5.0);
  const double outer = inner + std::max(2.0, factor / 8.0);
  const int reach = int(outer) + 1;
  const int x_end = x0 + frame_width * factor, y_end = y0 + frame_height * factor;
  for (int py = int(cy) - reach; py <= int(cy) + reach; ++py)
    for (int px = int(cx) - reach; px <= int(cx) + reach; ++px) {
      if (px < x0 || py < y0 || px >= x_end || py >= y_end) continue;
      const double d = std::hypot(px + 0.5 - cx, py + 0.5 - cy);
      if (d >= inner && d <= outer) canvas.fill(px, py, 1, 1, kFailRing);
    }
}

}  // namespace

bool explained_mismatches_fail(const Tolerance& t) {
  return !t.allow_boundary || t.mode == ToleranceMode::exact;
}

CoverageCanvas::CoverageCanvas(int width, int height, const CoverageStats& stats,
                               const std::optional<std::string>& font, bool explained_fail)
    : width_(width),
      height_(height),
      shrink_(map_factor(width, height, 1)),
      shown_width_((width + shrink_ - 1) / shrink_),
      shown_height_((height + shrink_ - 1) / shrink_),
      factor_(upscale_factor(shown_width_, shown_height_)),
      image_x_(0),
      explained_fail_(explained_fail),
      font_(font),
      canvas_(std::max(shown_width_ * factor_, kMinWidth) + 2 * kMargin,
              kTitleHeight + shown_height_ * factor_ + kLegendHeight, kBackground) {
  const int text_width = canvas_.width - 2 * kMargin;
  draw_text(canvas_, font, kMargin, 22,
            fmt::format("coverage   {}   ties {}   within snapping {}   fill-rule {}"
                        "   gaps {}   double hits {}",
                        count_text(stats.failures, "failure", "failures"), stats.exact_tie,
                        stats.within_snapping, stats.fill_rule, stats.gaps, stats.double_hits),
            16, kText, Align::left, text_width);
  std::string counts =
      fmt::format("both {}   reference only {}   GL only {}   other primitive {}", stats.both,
                  stats.reference_only, stats.gl_only, stats.other_primitive);
  if (shrink_ > 1)
    counts += fmt::format("   (each pixel the most severe of {}x{})", shrink_, shrink_);
  draw_text(canvas_, font, kMargin, 42, counts, 12, kText, Align::left, text_width);
  image_x_ = (canvas_.width - shown_width_ * factor_) / 2;
}

void CoverageCanvas::add_rows(const Expectation& expected, const Frame& gl, int y0) {
  const Frame& reference = expected.frame;
  const std::vector<uint8_t>& edge_band = expected.edges;
  const bool has_band = edge_band.size() == reference.pixel_count();
  if (y0 % shrink_ != 0 || y0 < 0 || y0 + reference.height > height_ || reference.width != width_)
    throw std::invalid_argument("coverage picture: rows [" + std::to_string(y0) + ", " +
                                std::to_string(y0 + reference.height) + ") of a frame " +
                                std::to_string(reference.width) + " wide are not whole blocks of " +
                                std::to_string(shrink_) + " rows of a " + std::to_string(width_) +
                                " x " + std::to_string(height_) + " frame");
  // Frame row y0 + y lands on shown row (y0 + y) / shrink_, image block row shown_height_ - 1
  // minus that: the band's shown rows are the blocks from shown_height_ - y0 / shrink_ - rows
  // down.
  const int first = y0 / shrink_;
  const int rows = (reference.height + shrink_ - 1) / shrink_;
  paint_frame(canvas_, image_x_, kTitleHeight + (shown_height_ - first - rows) * factor_, factor_,
              shown_width_, rows, [&](int bx, int by) {
                // The block's most severe pixel: 4 a gap or double hit, 3 another failing
                // mismatch, 2 an explained one, 1 an agreeing pixel in an edge band, 0 any.
                int worst = -1, failing = 0;
                Rgb colour;
                for (int y = by * shrink_; y < std::min(reference.height, (by + 1) * shrink_); ++y)
                  for (int x = bx * shrink_; x < std::min(width_, (bx + 1) * shrink_); ++x) {
                    const size_t i = reference.index(x, y);
                    const auto label =
                        has_band ? compare::coverage_label(expected, gl, i) : std::nullopt;
                    const bool band = has_band && edge_band[i] != 0;
                    const bool fails = label && (explained_fail_ || !compare::explained(*label));
                    const int severity = !label ? (band ? 1 : 0)
                                         : (*label == CoverageStats::Label::gap ||
                                            *label == CoverageStats::Label::double_hit)
                                             ? 4
                                         : fails ? 3
                                                 : 2;
                    failing += fails;
                    if (severity > worst)
                      worst = severity,
                      colour = pixel_colour(reference.primitive[i], gl.primitive[i], band, label);
                  }
                if (failing > 0) failing_.emplace_back(bx, first + by);
                return colour;
              });
}

Canvas CoverageCanvas::finish() {
  // After every pixel is painted: a ring overlaps its neighbours.
  for (const auto& [x, y] : failing_)
    draw_ring(canvas_, image_x_, kTitleHeight, factor_, shown_width_, shown_height_, x, y);
  draw_legend(canvas_, font_, kTitleHeight + shown_height_ * factor_);
  return std::move(canvas_);
}

Canvas render_coverage(const Expectation& expected, const Frame& gl, const CoverageStats& stats,
                       const std::optional<std::string>& font, bool explained_fail) {
  CoverageCanvas canvas(expected.frame.width, expected.frame.height, stats, font, explained_fail);
  canvas.add_rows(expected, gl, 0);
  return canvas.finish();
}

}  // namespace glrc::report
