// Whether an expectation belongs to a case, before a reproducer embeds it: the C file and the
// shader_test both index the frame, the edge bits, the allowance and the depth-test candidates
// by the case's pixels, components and triangles.
#pragma once

#include <string>

#include "core/case.hpp"
#include "core/expectation.hpp"

namespace glrc::reproducer {

// What is wrong with expectation `e` as one of case `c` under tolerance `t`, in a few words
// ("the expectation is not of this case's framebuffer and varyings"), or "" when nothing is:
// the frame's size and components, the edge bits, the allowance (under ToleranceMode::spec),
// the depth-test candidates (sorted by pixel, of this case's triangles), every vertex with every
// component, every triangle's vertices within the case's.
std::string expectation_shape_error(const Case& c, const Expectation& e, const Tolerance& t);

}  // namespace glrc::reproducer
