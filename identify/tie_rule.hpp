// identify, finding 3: the tie-break rule, which pixel centres exactly on an edge belong to the
// triangle. One triangle per 8x8 cell with exactly one edge through pixel centres, edge kinds in
// turn, positions on the quarter-pixel grid that every grid of 2 bits or more keeps.
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

enum EdgeKind { left_vertical, left_slanted, right_vertical, right_slanted, bottom, top, kKinds };
const char* const kKindNames[kKinds] = {"left, vertical", "left, slanted", "right, vertical",
                                        "right, slanted", "bottom",        "top"};

struct TieCentre {
  size_t probe = 0, pixel = 0;
  int32_t primitive = 0;
  int kind = 0;
};

// Probe `index` (the `probe`-th frame), drawn from `rnd`; appends its tie centres to `centres`.
Case tie_triangles(Random& rnd, int index, size_t probe, std::vector<TieCentre>& centres);

struct TieCandidate {
  TieBreak rule = TieBreak::bottom_left;
  uint64_t wrong_centres = 0;  // tie centres where the rule and GL disagree
  uint64_t mismatches = 0;     // coverage mismatches in the whole probe frames
};

struct TieFinding {
  TieBreak identified = TieBreak::bottom_left;
  bool explains_all = false;
  uint64_t centres = 0;
  std::array<uint64_t, kKinds> per_kind{}, taken{};
  std::vector<TieCandidate> candidates;
};

// The rule that explains which triangle GL gave each tie centre, with `bits` subpixel bits.
TieFinding identify_ties(const std::vector<Probe>& probes, const std::vector<TieCentre>& centres,
                         int bits);

}  // namespace glrc::identify
