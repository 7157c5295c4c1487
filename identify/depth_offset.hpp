// Finding 7: the polygon offset GL adds (glPolygonOffset, OpenGL 4.6 section 14.6.5) to a 32F
// depth buffer, where GL leaves two choices: the slope m, max(|∂z/∂x|, |∂z/∂y|) (equation
// 14.12) or their length (14.11) or anything between, and nothing in r, which is 2^(e − 23)
// (e the exponent of the primitive's largest |z_w|). The allowance takes both slopes
// (ref/depth_offset.hpp); this says which one GL takes, and how many r it adds per unit.
// Triangles with w_c = 1 on a plane that rises as fast along x as along y (where the two slopes
// differ most, by √2), depths in [1/2, 3/4] (e = -1), drawn without an offset, with
// glPolygonOffset(1, 0) and with glPolygonOffset(0, 65536): the offset is the difference of the
// depths GL stores.
#pragma once

#include <string>
#include <vector>

#include "core/case.hpp"
#include "identify/probes.hpp"

namespace glrc::identify {

struct DepthOffsetFinding {
  bool available = false;  // the three probes were drawn
  size_t pixels = 0;       // pixels covered in all three
  // Median over the pixels of the offset glPolygonOffset(1, 0) added, over the plane's
  // max(|∂z/∂x|, |∂z/∂y|): 1 for (14.12), √2 for (14.11).
  double slope_ratio = 0;
  std::string slope;  // "max", "length", or "other"
  // Median of the offset glPolygonOffset(0, 65536) added, over 65536·2^(e − 23): 1 is GL's r.
  double units_ratio = 0;
  std::string units;  // "r", "2r" or "other"
};

// The three probes: the same triangles without an offset, with glPolygonOffset(1, 0), and with
// glPolygonOffset(0, 65536).
std::vector<Case> depth_offset_cases(Random& rnd);
// The finding from GL's frames of depth_offset_cases, in that order.
DepthOffsetFinding identify_depth_offset(const std::vector<Probe>& probes);

}  // namespace glrc::identify
