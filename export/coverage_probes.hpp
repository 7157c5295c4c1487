// A shader_test's coverage probes: `probe rect` lines that read, from the resolve draw's texture
// (fragments, kept triangle or -1, verdict, 1), the reference's fragment count and kept triangle
// wherever the plan decides them (shader_test_plan.hpp), as rectangles of equal expectation.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/frame.hpp"
#include "export/shader_test_plan.hpp"

namespace glrc::reproducer {

struct CoverageProbes {
  std::string text;           // the [test] section's lines, each group after a blank line
  size_t probes = 0;          // `probe rect` lines
  size_t pixels_decided = 0;  // pixels whose fragments or triangle they check
};

// The probes of frame f (the reference's: its fragment counts, empty when not counted, and
// primitives) where `decided` (per pixel) says. Either in three groups by what is decided
// (fragments and triangle, fragments only, triangle only), or as two grids (fragments where
// decided, triangle where decided), whichever takes fewer probes: one triangle needs half as
// many in groups, a mesh with pixel centres on its shared edges (where only the count is
// decided) far fewer in grids.
CoverageProbes coverage_probes(const Frame& f, const std::vector<Decided>& decided);

}  // namespace glrc::reproducer
