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

}  // namespace glrc::report
