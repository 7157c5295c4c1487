// The exact CPU reference of GL's triangle pipeline: clip -> divide -> viewport -> snap ->
// rasterize -> v/w and 1/w interpolated per pixel -> depth. Every value is the float32 nearest
// (ties to even) to the exact rational value the Model defines; no result depends on compiler,
// flags or CPU.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/model.hpp"

namespace glrc::ref {

// The frame, its edge bits (core/frame.hpp edge::) and, when asked for, the allowance.
using Reference = Expectation;

// Renders the case under model m. With `freedom_bits` (the GL_SUBPIXEL_BITS an implementation
// reports, at least 4 taken), also the specification's allowance per pixel and channel
// (allowance.hpp), and edge bands as wide as that position freedom; without, no allowance and
// bands one model subpixel step wide. Neither is part of the digest.
// `threads`: how many threads draw it (ref/tiles.hpp), 0 for every core this process may use;
// every bit of the result is the same for any number.
Reference render(const Case& c, const Model& m, std::optional<int> freedom_bits = std::nullopt,
                 int threads = 1);

// SHA-256 (hex) of the frame's bits: width, height, then per pixel primitive, depth and every
// component, little-endian. Identical bits give identical digests on any machine.
std::string digest(const Frame& f);
// SHA-256 (hex) of everything render() gives: the frame's digest, then per pixel the edge bits
// and the allowance's primitive, depth and components (when computed), then every candidate
// (pixel, primitive, depth, allowed depth, values, allowed values). A faster reference must keep
// it (tests/expectation_digests.txt), not only the frame's.
std::string expectation_digest(const Reference& r);

}  // namespace glrc::ref
