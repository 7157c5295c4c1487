// Blocks of pixels: render.cpp draws a triangle's covered pixels kRowBlock at a time, and the
// stages' block forms (ComponentValues::values, Anchors::distances, Allowance::at, round_up)
// take that many at once. A fixed count, so that their loops over the lanes are vectorized at
// any optimization level; each lane's arithmetic is the single pixel's, the same operations in
// the same order, so every bit is the same as one pixel at a time.
#pragma once

namespace glrc::ref {

inline constexpr int kRowBlock = 8;

// On the definitions of the block forms: on x86-64, a second copy of the function for AVX2
// (four doubles per instruction, SSE2 has two), chosen at load time when the processor has
// it. The lanes' operations are the same IEEE operations either way, and AVX2 alone brings no
// fused multiply-add (that is FMA, not asked for), so both copies give the same bits. (Built
// with FMA in the base flags, -march=native say, both copies may fuse, each its own way: the
// frames stay the same, their fast paths' bounds holding fused or not, which the -O3
// -march=native -ffp-contract=fast digest test checks; allowances may then differ in the
// last bits, as they would without the copies.)
//
// GCC only: GCC makes the function's own name the load-time choice, so a caller in another
// file, which sees a plain declaration, gets the right copy. Clang 14 names the choice apart
// (".ifunc") and leaves the plain name undefined, so that such a caller does not link; and with
// the attribute on the declarations too, GCC calls the other file's copies by names it never
// defines. Built with clang, the block forms are the default copies alone.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(GLRC_NO_BLOCK_CLONES)
#define GLRC_BLOCK_FORM __attribute__((target_clones("avx2", "default")))
#else
#define GLRC_BLOCK_FORM
#endif

}  // namespace glrc::ref
