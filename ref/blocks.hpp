// Blocks of pixels: render.cpp draws a triangle's covered pixels kRowBlock at a time, and the
// stages' block forms (ComponentValues::values, Anchors::distances, Allowance::at, round_up)
// take that many at once. A fixed count, so that their loops over the lanes are vectorized at
// any optimization level; each lane's arithmetic is the single pixel's, the same operations in
// the same order, so every bit is the same as one pixel at a time.
#pragma once

namespace glrc::ref {

inline constexpr int kRowBlock = 8;

}  // namespace glrc::ref
