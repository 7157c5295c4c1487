// The exact CPU reference of GL's triangle pipeline: clip -> divide -> viewport -> snap ->
// rasterize -> v/w and 1/w interpolated per pixel -> depth. Every value is the float32 nearest
// (ties to even) to the exact rational value the Model defines; no result depends on compiler,
// flags or CPU.
#pragma once

#include <cstdint>
#include <vector>

#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/model.hpp"

namespace glrc::ref {

struct Reference {
  Frame frame;
  // 1 where the pixel centre lies within one subpixel step (Euclidean, window pixels) of an
  // edge of some drawn triangle, of a near/far clip boundary, or of a vertex: there, legal
  // implementations may disagree about coverage. Not part of the digest.
  std::vector<uint8_t> edge_band;
};

Reference render(const Case& c, const Model& m);

// SHA-256 (hex) of the frame's bits: width, height, then per pixel primitive, depth and every
// component, little-endian. Identical bits give identical digests on any machine.
std::string digest(const Frame& f);

}  // namespace glrc::ref
