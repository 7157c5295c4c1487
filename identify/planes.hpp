// identify, finding 2: whether attribute planes come from snapped or unsnapped window
// positions. Perspective triangles with smooth and noperspective attributes: planes from
// snapped positions move every value by about the gradient times the snapping, far more than
// the float arithmetic does.
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

struct PlanesCandidate {
  Planes planes = Planes::unsnapped;
  double max_ulps = 0, mean_ulps = 0;
  uint64_t compared = 0, non_finite = 0;
};

struct PlanesFinding {
  Planes identified = Planes::unsnapped;
  bool distinguishable = true;  // false without snapping: both candidates are one model
  std::vector<PlanesCandidate> candidates;
};

// Perspective triangles at random float positions (probe `index`), drawn from `rnd`.
Case plane_triangles(Random& rnd, int index);
// The planes that explain GL's values in `probes`, with `bits` subpixel bits of snapping.
PlanesFinding identify_planes(const std::vector<Probe>& probes, int bits);

}  // namespace glrc::identify
