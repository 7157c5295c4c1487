// Depth: z_w is linear in window coordinates (glDepthRange applied to z_n = z_c / w_c), and the
// depth test compares the float32 values, as a 32F depth buffer does.
#pragma once

#include "core/case.hpp"
#include "ref/interpolation.hpp"

namespace glrc::ref {

// The exact plane of z_w over triangle t, with `offset` (a polygon offset o, z_w units; null:
// none) added to every point of it: z_w + o is the same ratio with o·β_i added to each α_i
// (Σ λ_i (α_i + o·β_i) / Σ λ_i β_i), so it is evaluated, and rounded, once.
Plane depth_plane(const TriangleSetup& t, const Barycentrics& b, const mpq_class* offset = nullptr);

}  // namespace glrc::ref
