// The coverage picture: which pixels each frame covers, and where they disagree, upright and
// upscaled with a legend. Mismatches are saturated colours on a dim background so that a single
// pixel stands out.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/frame.hpp"
#include "core/result.hpp"
#include "report/canvas.hpp"

namespace glrc::report {

// Whether mismatches the specification's freedom explains (exact ties, within snapping) count
// as failures under `t`, as compare counts them: with --strict-coverage or --tolerance exact.
bool explained_mismatches_fail(const Tolerance& t);

// Mismatches the specification's freedom explains (exact ties, within snapping) are drawn
// lighter; gaps and double hits on shared edges in colours of their own; the edge bands are a
// faint tint. Every failing pixel (a mismatch that counts against the verdict: all of them when
// `explained_fail`) gets a bright ring around it, so that a single one is found at a glance
// in a large frame.
Canvas render_coverage(const Expectation& expected, const Frame& gl, const CoverageStats& stats,
                       const std::optional<std::string>& font, bool explained_fail = false);

// The same picture of a width x height frame, painted band of rows by band of rows (in any
// order): render_coverage is one band of the whole frame. A frame of more than 2^20 pixels is
// shown shrunk by map_factor(width, height, 1) (channel_error.hpp), each pixel of the picture
// the most severe of its block (a gap or double hit, then a failing mismatch, then an explained
// one, then an agreeing pixel in an edge band, then any; the first in row order among equals),
// ringed when any pixel of the block fails; a band then starts on a row that is a multiple of
// that factor.
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
  Canvas canvas_;
  std::vector<std::pair<int, int>> failing_;  // shown pixels to ring
};

}  // namespace glrc::report
