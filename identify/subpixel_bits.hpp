// identify, finding 1: the subpixel bits of GL's snapping grid. Thin triangles at random float
// positions and targeted probes whose edges cross a pixel centre on one side exactly and on the
// other once rounded to a grid of 2^-bits pixel; each candidate grid renders them on the exact
// reference, and the one whose coverage matches GL's is identified.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"
#include "core/model.hpp"

#include "identify/probes.hpp"

namespace glrc::identify {

struct BitsCandidate {
  int bits = 0;
  uint64_t mismatches = 0, ties_skipped = 0;
};

struct BitsFinding {
  int identified = 0, reported = 0;
  std::vector<BitsCandidate> candidates;
  size_t triangles = 0;
  bool distinct = true;  // no other candidate has as few mismatches
};

// The probe cases, drawn from `rnd`.
std::vector<Case> subpixel_probes(Random& rnd);
// The grid that explains GL's coverage of `probes`; `reported` is GL_SUBPIXEL_BITS.
BitsFinding identify_bits(const std::vector<Probe>& probes, int reported);

}  // namespace glrc::identify
