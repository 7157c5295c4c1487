// The coverage picture: which pixels each frame covers, and where they disagree, upright and
// upscaled with a legend. Each mismatch is painted by its verdict label (compare::coverage_label),
// in saturated colours on a dim background so that a single pixel stands out; the legend gives
// each label's count, the numbers the text report prints.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/expectation.hpp"
#include "core/result.hpp"
#include "report/canvas.hpp"

namespace glrc::report {

// Whether mismatches the specification's freedom explains (exact ties, within snapping) count
// as failures under `t`, as compare counts them: with --strict-coverage or --tolerance exact.
bool explained_mismatches_fail(const Tolerance& t);

// The name of a coverage label as every report prints it: "exact tie", "within snapping",
// "fill-rule error", "gap on a shared edge", "double hit on a shared edge".
const char* label_text(CoverageStats::Label l);
// How many pixels `stats` counts under label l.
uint64_t label_count(const CoverageStats& stats, CoverageStats::Label l);
// The colour of a pixel labelled l: one hue per label, lightened for the labels the
// specification's freedom explains (compare::explained).
Rgb label_colour(CoverageStats::Label l);

// One entry of the picture's legend: a label, its colour and its count in the CoverageStats the
// picture is drawn with; `text` is what the legend writes, "fill-rule error: 3".
struct LegendEntry {
  CoverageStats::Label label;
  Rgb colour;
  uint64_t count = 0;
  std::string text;
};
// The legend's entries for `stats`, one per label, the failures before the explained ones.
std::vector<LegendEntry> coverage_legend(const CoverageStats& stats);

// Each pixel in the colour of its label (label_colour); agreeing pixels in a dim grey per
// primitive, with a faint tint in the edge bands. Where both frames cover a mismatching pixel with
// different primitives, or only one covers it, a small mark inside the pixel says which (when a
// frame pixel is drawn at least 8 canvas pixels wide); a mismatch of fragment counts alone, both
// frames naming the same primitive, has none. Every failing pixel (a mismatch that counts against
// the verdict: the explained ones too when `explained_fail`) gets a bright ring around it, so that
// a single one is found at a glance in a large frame. `stats` gives the legend's counts.
Canvas render_coverage(const Expectation& expected, const Frame& gl, const CoverageStats& stats,
                       const std::optional<std::string>& font, bool explained_fail = false);

// The same picture of a width x height frame, painted slice of rows by slice of rows (in any
// order): render_coverage is one slice of the whole frame. A frame of more than 2^20 pixels is
// shown shrunk by map_factor(width, height, 1) (channel_error.hpp), each pixel of the picture
// the most severe of its block (a gap or double hit, then a fill-rule error, then an explained
// mismatch that fails, then an allowed one, then an agreeing pixel in an edge band, then any; the
// first in row order among equals), ringed when any pixel of the block fails; a slice then starts
// on a row that is a multiple of that factor.
class CoverageCanvas {
 public:
  CoverageCanvas(int width, int height, const CoverageStats& stats,
                 const std::optional<std::string>& font, bool explained_fail = false);
  // Rows [y0, y0 + expected.frame.height) of both frames, as compare::Comparator takes them.
  void add_rows(const Expectation& expected, const Frame& gl, int y0);
  Canvas finish();  // once

 private:
  int width_, height_;
  int shrink_;                      // frame pixels per picture pixel, each way
  int shown_width_, shown_height_;  // the frame as shown: shrunk
  int factor_, image_x_;            // canvas pixels per shown pixel; where the frame starts
  bool explained_fail_;
  std::optional<std::string> font_;
  std::vector<LegendEntry> legend_;
  // The pixels whose labels the fragment traces decided (CoverageStats::traced_failures).
  std::map<std::pair<int, int>, CoverageStats::Label> traced_;
  Canvas canvas_;
  std::vector<std::pair<int, int>> failing_;  // shown pixels to ring
};

}  // namespace glrc::report
