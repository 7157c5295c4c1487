// Blocks of pixels: render.cpp draws a triangle's covered pixels kRowBlock at a time, and the
// stages' block forms (ComponentValues::values, Anchors::distances, Allowance::at, round_up)
// take that many at once. A fixed count, so that their loops over the lanes are vectorized at
// any optimization level; each lane's arithmetic is the single pixel's, the same operations in
// the same order, so every bit is the same as one pixel at a time.
#pragma once

#include "core/vector_clones.hpp"

namespace glrc::ref {

inline constexpr int kRowBlock = 8;

// On the definitions of the block forms: GLRC_VECTOR_CLONES (core/vector_clones.hpp), an AVX2
// copy beside the baseline one. The lanes' operations are the same IEEE operations either way,
// so both copies give the same bits. (Built with FMA in the base flags, -march=native say, both
// copies may fuse, each its own way: the frames stay the same, their fast paths' bounds holding
// fused or not, which the -O3 -march=native -ffp-contract=fast digest test checks; allowances
// may then differ in the last bits, as they would without the copies.)
#define GLRC_BLOCK_FORM GLRC_VECTOR_CLONES

}  // namespace glrc::ref
