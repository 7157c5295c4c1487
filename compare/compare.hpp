// The comparator: per pixel, coverage and every value of a GL frame against the reference.
// Knows nothing of GL: two Frames in the same layout, the Case for the attribute scales.
#pragma once

#include <cstdint>
#include <vector>

#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/result.hpp"

namespace glrc::compare {

// edge_band: the reference's per-pixel "centre within one subpixel step of an edge" mask.
// Sets status to pass or fail (never anything else) and fills the statistics.
CaseResult compare(const Case& c, const Frame& reference, const std::vector<uint8_t>& edge_band,
                   const Frame& gl, const Tolerance& tolerance);

// The scale of component k at a pixel covered by triangle `primitive`: the largest |v_i| of
// that triangle's three vertices. Depth is component kDepth, of scale 1.0. Errors are counted in
// ULPs of the scale. Flat components are held to 0 ULPs: they are copied, never computed.
inline constexpr int kDepth = -1;
double attribute_scale(const Case& c, int primitive, int component);
// ulp of a positive scale: 2^(floor(log2 scale) - 23); the smallest normal ulp for 0.
double ulp_of_scale(double scale);

}  // namespace glrc::compare
