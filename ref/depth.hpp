// Depth: z_w is linear in window coordinates (glDepthRange applied to z_n = z_c / w_c), and the
// depth test compares the float32 values, as a 32F depth buffer does.
#pragma once

#include "core/case.hpp"
#include "ref/interpolation.hpp"

namespace glrc::ref {

Plane depth_plane(const TriangleSetup& t, const Barycentrics& b);

}  // namespace glrc::ref
