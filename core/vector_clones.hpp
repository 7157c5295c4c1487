// A function whose loops want wider vectors than x86-64's baseline: GLRC_VECTOR_CLONES on its
// definition makes GCC build a second copy of it for AVX2 (four doubles per instruction, SSE2
// has two; and 64-bit integer comparisons, which SSE2 lacks, so that a loop counting double
// comparisons or taking a maximum of 64-bit keys is vectorized at all), chosen at load time
// when the processor has it. Both copies run the same IEEE operations: AVX2 brings no fused
// multiply-add (that is FMA, not asked for), so they give the same bits.
//
// GCC only: GCC makes the function's own name the load-time choice, so a caller in another
// file, which sees a plain declaration, gets the right copy. Clang 14 names the choice apart
// (".ifunc") and leaves the plain name undefined, so that such a caller does not link; and with
// the attribute on the declarations too, GCC calls the other file's copies by names it never
// defines. Built with clang, such functions are the default copy alone.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(GLRC_NO_BLOCK_CLONES)
#define GLRC_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define GLRC_VECTOR_CLONES
#endif
