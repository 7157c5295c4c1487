// Model: the choices the GL specification leaves to an implementation, which the reference
// takes as parameters instead of guessing one.
#pragma once

#include <string>

#include "core/names.hpp"

namespace glrc {

// Which pixel centres exactly on an edge belong to the triangle. Named in GL window
// coordinates (y up): bottom_left takes centres on left edges (inward normal towards +x) and on
// bottom horizontal edges (llvmpipe rendering into an FBO does this); top_left takes left and
// top horizontal edges. The right rules take right edges (inward normal towards -x) instead of
// left ones, with bottom or top horizontal edges (softpipe takes right edges).
enum class TieBreak { bottom_left, top_left, bottom_right, top_right };

// Whether attribute planes (barycentrics) come from the snapped window positions used for
// coverage, or from the exact, unsnapped ones. Mesa's llvmpipe and softpipe use unsnapped
// positions; an NVIDIA GPU was measured using snapped ones.
enum class Planes { unsnapped, snapped };

template <>
struct Names<TieBreak> {
  static constexpr std::array<std::pair<TieBreak, std::string_view>, 4> table{{
      {TieBreak::bottom_left, "bottom-left"},
      {TieBreak::top_left, "top-left"},
      {TieBreak::bottom_right, "bottom-right"},
      {TieBreak::top_right, "top-right"},
  }};
};
template <>
struct Names<Planes> {
  static constexpr std::array<std::pair<Planes, std::string_view>, 2> table{{
      {Planes::unsnapped, "unsnapped"},
      {Planes::snapped, "snapped"},
  }};
};

// "bottom-left", "top-left", "bottom-right", "top-right": the names the command line takes.
const char* to_string(TieBreak t);
const char* to_string(Planes p);  // "unsnapped", "snapped"

struct Model {
  int subpixel_bits = 8;  // 0: no snapping, coverage from exact positions
  Planes planes = Planes::unsnapped;
  TieBreak tie_break = TieBreak::bottom_left;

  std::string describe() const;  // e.g. "subpixel_bits=8 planes=unsnapped tie=bottom-left"
};

}  // namespace glrc
