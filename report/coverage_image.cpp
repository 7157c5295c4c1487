#include "report/coverage_image.hpp"

#include <algorithm>
#include <cmath>
#include <map>
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
constexpr int kLegendHeight = 190;
constexpr Rgb kBackground{0.1f, 0.1f, 0.1f};
constexpr Rgb kText{0.92f, 0.92f, 0.92f};

constexpr Rgb kNeither{0.03f, 0.03f, 0.03f};
constexpr Rgb kWhite{1, 1, 1};
// One hue per label. The failures are saturated; the explained labels are lightened, so that
// what the specification allows reads as the milder kind at a glance.
constexpr Rgb kFillRule{0.9f, 0.1f, 0.1f};          // red: the fill rule or the count is wrong
constexpr Rgb kGap{0.0f, 0.9f, 0.9f};               // cyan: no fragment where a mesh needs one
constexpr Rgb kDoubleHit{0.95f, 0.0f, 0.95f};       // magenta: two fragments on a shared edge
constexpr Rgb kExactTie{1.0f, 0.55f, 0.0f};         // orange, lightened
constexpr Rgb kWithinSnapping{0.15f, 0.35f, 1.0f};  // blue, lightened
constexpr float kExplainedLightening = 0.55f;
// Rings around failing pixels: a hue no pixel colour uses.
constexpr Rgb kFailRing{0.3f, 1.0f, 0.2f};
// The edge band only hints where boundary mismatches would be allowed, so it is a faint tint.
constexpr Rgb kEdgeTint{0.85f, 0.8f, 0.25f};
constexpr float kEdgeTintAmount = 0.22f;
// The primitive relation is secondary to the label: a small mark inside the pixel, drawn only
// where a frame pixel is large enough to hold one beside its label's colour.
constexpr int kMarkMinFactor = 8;
constexpr Rgb kMarkBorder{0.03f, 0.03f, 0.03f};
constexpr Rgb kMarkGlNone = kMarkBorder;  // GL covers nothing: an empty (dark) mark
constexpr Rgb kMarkReferenceNone = kWhite;
constexpr Rgb kMarkOtherPrimitive{0.55f, 0.55f, 0.55f};

using Label = CoverageStats::Label;

// Agreeing pixels: dim grey, a shade per primitive so that triangle edges remain visible.
Rgb same_primitive(int32_t primitive) {
  const float grey = 0.24f + 0.07f * float(primitive % 4);
  return {grey, grey, grey};
}

// The mark of a mismatch where the frames name different primitives, or none where they name
// the same one (only the fragment count differs).
std::optional<Rgb> relation_mark(int32_t ref, int32_t gl) {
  if (ref == gl) return std::nullopt;
  if (gl == Frame::kNoPrimitive) return kMarkGlNone;
  if (ref == Frame::kNoPrimitive) return kMarkReferenceNone;
  return kMarkOtherPrimitive;
}

// A square mark with a dark border, centred in the size x size square at (x, y): the border
// keeps a white mark visible on the light colours of explained labels.
void draw_mark(Canvas& canvas, int x, int y, int size, Rgb colour) {
  const int side = std::max(4, size / 4), at = (size - side) / 2;
  canvas.fill(x + at, y + at, side, side, kMarkBorder);
  canvas.fill(x + at + 1, y + at + 1, side - 2, side - 2, colour);
}

// How a block of a shrunk picture picks the pixel it shows: the highest wins (see
// CoverageCanvas).
int severity(std::optional<Label> label, bool in_edge_band, bool fails) {
  if (!label) return in_edge_band ? 1 : 0;
  if (*label == Label::gap || *label == Label::double_hit) return 5;
  if (*label == Label::fill_rule) return 4;
  return fails ? 3 : 2;
}

Rgb pixel_colour(int32_t ref, bool in_edge_band, std::optional<Label> label) {
  if (label) return label_colour(*label);
  const Rgb base = ref == Frame::kNoPrimitive ? kNeither : same_primitive(ref);
  return in_edge_band ? mix(base, kEdgeTint, kEdgeTintAmount) : base;
}

void swatch(Canvas& canvas, const std::optional<std::string>& font, int x, int y, Rgb colour,
            const std::string& label, int max_width) {
  canvas.fill(x, y, 14, 14, colour);
  draw_text(canvas, font, x + 20, y + 12, label, 13, kText, Align::left, max_width - 20);
}

void draw_legend(Canvas& canvas, const std::optional<std::string>& font, int top,
                 const std::vector<LegendEntry>& entries, bool explained_fail, bool marks) {
  const int x0 = kMargin + 8, column = (canvas.width - 2 * x0) / 2, text_width = column - 8;
  int row = top + 14;
  // The labels two to a row, then what else the picture shows.
  for (size_t k = 0; k < entries.size(); ++k) {
    swatch(canvas, font, x0 + int(k % 2) * column, row, entries[k].colour, entries[k].text,
           text_width);
    if (k % 2 == 1) row += 24;
  }
  const int x_free = x0 + int(entries.size() % 2) * column;
  swatch(canvas, font, x_free, row, same_primitive(0), "agreeing (shade per primitive)",
         text_width);
  if (entries.size() % 2 == 1) row += 24;
  swatch(canvas, font, x0, row, mix(same_primitive(0), kEdgeTint, kEdgeTintAmount),
         "agreeing in an edge band", text_width);
  draw_text(canvas, font, x0 + column, row + 12,
            explained_fail ? "lighter: GL's freedom, failing (strict)"
                           : "lighter: allowed by GL's freedom",
            13, kText, Align::left, text_width);
  row += 24;
  canvas.fill(x0, row, 14, 14, kFailRing);
  canvas.fill(x0 + 3, row + 3, 8, 8, kBackground);
  draw_text(canvas, font, x0 + 20, row + 12, "ring: a failing pixel (counts against the verdict)",
            13, kText, Align::left, 2 * column - 20);
  if (!marks) return;
  // The marks, each shown on the fill-rule colour as a frame pixel would show it, as large as
  // in a frame pixel 32 wide (centred in the swatch: 3 of its pixels on each side).
  const auto mark_swatch = [&](int x, int y, Rgb mark, const std::string& text) {
    canvas.fill(x, y, 14, 14, kFillRule);
    draw_mark(canvas, x - 9, y - 9, 32, mark);
    draw_text(canvas, font, x + 20, y + 12, text, 13, kText, Align::left, text_width - 20);
  };
  row += 24;
  mark_swatch(x0, row, kMarkGlNone, "mark: GL covers nothing");
  mark_swatch(x0 + column, row, kMarkReferenceNone, "mark: reference covers nothing");
  row += 24;
  mark_swatch(x0, row, kMarkOtherPrimitive, "mark: another primitive");
  canvas.fill(x0 + column, row, 14, 14, kFillRule);
  draw_text(canvas, font, x0 + column + 20, row + 12, "no mark: same primitive in both", 13, kText,
            Align::left, text_width - 20);
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

const char* label_text(Label l) {
  switch (l) {
    case Label::exact_tie:
      return "exact tie";
    case Label::within_snapping:
      return "within snapping";
    case Label::fill_rule:
      return "fill-rule error";
    case Label::gap:
      return "gap on a shared edge";
    case Label::double_hit:
      return "double hit on a shared edge";
  }
  return "mismatch";
}

uint64_t label_count(const CoverageStats& stats, Label l) {
  switch (l) {
    case Label::exact_tie:
      return stats.exact_tie;
    case Label::within_snapping:
      return stats.within_snapping;
    case Label::fill_rule:
      return stats.fill_rule;
    case Label::gap:
      return stats.gaps;
    case Label::double_hit:
      return stats.double_hits;
  }
  return 0;
}

Rgb label_colour(Label l) {
  const Rgb hue = l == Label::fill_rule    ? kFillRule
                  : l == Label::gap        ? kGap
                  : l == Label::double_hit ? kDoubleHit
                  : l == Label::exact_tie  ? kExactTie
                                           : kWithinSnapping;
  return compare::explained(l) ? mix(hue, kWhite, kExplainedLightening) : hue;
}

std::vector<LegendEntry> coverage_legend(const CoverageStats& stats) {
  std::vector<LegendEntry> entries;
  for (const Label l : {Label::fill_rule, Label::gap, Label::double_hit, Label::exact_tie,
                        Label::within_snapping}) {
    const uint64_t n = label_count(stats, l);
    entries.push_back({l, label_colour(l), n, fmt::format("{}: {}", label_text(l), n)});
  }
  return entries;
}

namespace {

// CoverageStats::traced_failures by pixel.
std::map<std::pair<int, int>, CoverageStats::Label> traced_labels(const CoverageStats& stats) {
  std::map<std::pair<int, int>, CoverageStats::Label> out;
  for (const CoverageStats::Pixel& p : stats.traced_failures)
    out[{p.x, p.y}] = p.label;
  return out;
}

}  // namespace

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
      legend_(coverage_legend(stats)),
      traced_(traced_labels(stats)),
      canvas_(std::max(shown_width_ * factor_, kMinWidth) + 2 * kMargin,
              kTitleHeight + shown_height_ * factor_ + kLegendHeight, kBackground) {
  const int text_width = canvas_.width - 2 * kMargin;
  draw_text(canvas_, font, kMargin, 22,
            "coverage   " + count_text(stats.failures, "failure", "failures"), 16, kText,
            Align::left, text_width);
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
  // minus that: the slice's shown rows are the blocks from shown_height_ - y0 / shrink_ - rows
  // down.
  const int first = y0 / shrink_;
  const int rows = (reference.height + shrink_ - 1) / shrink_;
  const int top = kTitleHeight + (shown_height_ - first - rows) * factor_;
  // The marks of the slice's shown pixels, drawn once their pixels are painted.
  std::vector<std::pair<std::pair<int, int>, Rgb>> marks;
  paint_frame(canvas_, image_x_, top, factor_, shown_width_, rows, [&](int bx, int by) {
    int worst = -1, failing = 0;
    Rgb colour;
    std::optional<Rgb> mark;
    for (int y = by * shrink_; y < std::min(reference.height, (by + 1) * shrink_); ++y)
      for (int x = bx * shrink_; x < std::min(width_, (bx + 1) * shrink_); ++x) {
        const size_t i = reference.index(x, y);
        // A count the traces failed: its own label, not the excused one coverage_label gives.
        const auto traced = traced_.find({x, y0 + y});
        const auto label = traced != traced_.end() ? std::optional(traced->second)
                           : has_band              ? compare::coverage_label(expected, gl, i)
                                                   : std::nullopt;
        const bool band = has_band && edge_band[i] != 0;
        const bool fails = label && (explained_fail_ || !compare::explained(*label));
        failing += fails;
        if (const int s = severity(label, band, fails); s > worst) {
          worst = s;
          colour = pixel_colour(reference.primitive[i], band, label);
          mark = label ? relation_mark(reference.primitive[i], gl.primitive[i]) : std::nullopt;
        }
      }
    if (failing > 0) failing_.emplace_back(bx, first + by);
    if (mark && factor_ >= kMarkMinFactor) marks.push_back({{bx, by}, *mark});
    return colour;
  });
  // paint_frame's block row by of the slice is image block row rows - 1 - by from `top`.
  for (const auto& [at, mark] : marks)
    draw_mark(canvas_, image_x_ + at.first * factor_, top + (rows - 1 - at.second) * factor_,
              factor_, mark);
}

Canvas CoverageCanvas::finish() {
  // After every pixel is painted: a ring overlaps its neighbours.
  for (const auto& [x, y] : failing_)
    draw_ring(canvas_, image_x_, kTitleHeight, factor_, shown_width_, shown_height_, x, y);
  draw_legend(canvas_, font_, kTitleHeight + shown_height_ * factor_, legend_, explained_fail_,
              factor_ >= kMarkMinFactor);
  return std::move(canvas_);
}

Canvas render_coverage(const Expectation& expected, const Frame& gl, const CoverageStats& stats,
                       const std::optional<std::string>& font, bool explained_fail) {
  CoverageCanvas canvas(expected.frame.width, expected.frame.height, stats, font, explained_fail);
  canvas.add_rows(expected, gl, 0);
  return canvas.finish();
}

}  // namespace glrc::report
