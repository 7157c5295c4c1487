// Fragment traces: which triangles' fragments reached a pixel, and which sets of triangles a
// conforming implementation may rasterize there. Near an outer edge (or a triangle that may turn
// over) the fragment count alone is free, and a count cannot say whose fragment an extra one is:
// a double hit on an edge two triangles share looks like a third triangle's fragment in its
// snapping band. The trace tells them apart. GL's counting pass (gl_harness) sums, besides 1
// per fragment, each fragment's p + 1 and fragment_hash(p) (p its gl_PrimitiveID); the
// reference (ref::fragment_choices) says, per pixel, which triangles surely cover it, which may,
// and which shared edges give the pixel to one side or the other; admitted() lists every trace a
// conforming implementation can give, and a trace outside the list fails (compare/).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace glrc {

// A pixel's fragments, as three exact sums over them. GL's counting pass adds them in float32
// (blending), exact while every sum stays below 2^24 (FragmentTrace::exact_in_float).
struct FragmentTrace {
  uint32_t count = 0;     // fragments
  uint32_t id_sum = 0;    // the sum of p + 1 over them, p each one's primitive
  uint32_t hash_sum = 0;  // the sum of fragment_hash(p)
  bool operator==(const FragmentTrace&) const = default;
  // Whether float32 sums of these (each term added in turn) are exact: every partial sum of a
  // sum below 2^24 is below 2^24 too (the terms are positive), where float32 holds every integer.
  bool exact_in_float() const { return id_sum < (1u << 24) && hash_sum < (1u << 24); }
  FragmentTrace& operator+=(const FragmentTrace& o) {
    count += o.count, id_sum += o.id_sum, hash_sum += o.hash_sum;
    return *this;
  }
};

// A second label of primitive p, in [1, 4096]: with the sum of p + 1 it tells apart sets of
// primitives of equal size and equal id sum, which the id sum alone confuses ({1, 4} and {2, 3}).
// The top 12 bits of an integer mixer of p (Wellons' "lowbias32": xor-shifts and odd
// multipliers, a bijection of 32-bit words whose output bits each depend on every input bit).
// Not a multiplicative hash: p·c mod 2^32 is linear in p, so its sums over sets of equal id sum
// differ only by wraps (of the 4,096 subsets of primitives 0 to 11 it told 1,050 apart; this
// one, all 4,096). The GLSL of the counting pass (gl_harness/shaders.cpp) computes the same with
// uint arithmetic.
constexpr uint32_t fragment_hash(int32_t p) {
  uint32_t x = uint32_t(p);
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return (x >> 20) + 1;
}
// The trace of one fragment of primitive p.
constexpr FragmentTrace fragment_trace(int32_t p) {
  return {1, uint32_t(p) + 1, fragment_hash(p)};
}

// What a conforming implementation may rasterize at one pixel: the triangles that surely cover
// it (`sure`), and the others within reach of it, each covering or not as the position freedom
// allows (ref/fragment_choices.hpp derives them).
struct FragmentChoices {
  // A triangle that may cover the pixel. It covers only where, for every shared edge in
  // `sides`, the pixel goes to the triangle's side of it; then surely, unless `free`. A
  // triangle with no sides is free (it would be sure otherwise).
  struct Member {
    int32_t primitive = -1;
    bool free = false;
    // (index into `edges`, side: true for the edge's first side).
    std::vector<std::pair<uint32_t, bool>> sides;
    // A clipped polygon's: where it covers, it may cover twice (its fan folding within the
    // clipper's rounding). Twice at most is assumed, not derived: a third cover would need two
    // folded fan triangles over one centre.
    bool folds = false;
  };
  FragmentTrace sure;
  std::vector<Member> members;
  // How many shared edges the pixel lies within the band of: each gives the pixel to one of its
  // two sides, the same side for every user of it (they rasterize one edge alike).
  uint32_t edges = 0;
  // No trace is decided here (reaching the eye, or more choices than admitted() enumerates).
  bool anything = false;
};

// How many sets of choices admitted() enumerates at most (2^sides · 2^free members): beyond it
// the pixel's trace is not judged (an excused count, as without a trace).
inline constexpr uint64_t kMostTraceChoices = uint64_t(1) << 12;
// Every trace a conforming implementation may give at a pixel, sorted (count, then id_sum,
// then hash_sum) and without repeats; nothing when choices.anything, or when the choices number
// more than kMostTraceChoices.
std::optional<std::vector<FragmentTrace>> admitted(const FragmentChoices& choices);

// admitted()'s list at one pixel (a window index x + y·width), for a reproducer to carry.
struct AdmittedTraces {
  size_t pixel = 0;
  std::vector<FragmentTrace> traces;
};

}  // namespace glrc
