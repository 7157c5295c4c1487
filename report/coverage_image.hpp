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

// edge_band: the reference's "centre within a subpixel step of an edge" mask, one byte per
// pixel; a mismatch there is a boundary mismatch. An empty mask marks nothing.
Canvas render_coverage(const Frame& reference, const Frame& gl,
                       const std::vector<uint8_t>& edge_band, const CoverageStats& stats,
                       const std::optional<std::string>& font);

}  // namespace glrc::report
