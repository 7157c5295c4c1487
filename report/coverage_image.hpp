// The coverage picture: which pixels each frame covers, and where they disagree, upright and
// upscaled with a legend. Mismatches are saturated colours on a dim background so that a single
// pixel stands out.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/frame.hpp"
#include "core/result.hpp"
#include "report/canvas.hpp"

namespace glrc::report {

// Mismatches the specification's freedom explains (exact ties, within snapping) are drawn
// lighter; gaps and double hits on shared edges in white and black-outlined colours of their
// own; the edge bands are a faint tint.
Canvas render_coverage(const Expectation& expected, const Frame& gl, const CoverageStats& stats,
                       const std::optional<std::string>& font);

}  // namespace glrc::report
