// identify, finding 4: the provoking vertex on a context where glProvokingVertex was never
// called (GL's default is the last vertex). Triangles of both windings with a flat varying that
// differs at each vertex.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/model.hpp"

#include "identify/probes.hpp"

namespace glrc::identify {

struct ProvokingFinding {
  ProvokingVertex identified = ProvokingVertex::last, reported = ProvokingVertex::last;
  uint64_t pixels = 0, first = 0, last = 0, neither = 0;
};

// 16 triangles with a flat varying, a different value at each vertex, drawn from `rnd`.
Case provoking_triangles(Random& rnd);
// Which vertex GL's flat values come from; `reported` is GL_PROVOKING_VERTEX.
ProvokingFinding identify_provoking(const Probe& p, ProvokingVertex reported);

}  // namespace glrc::identify
