// Finding 6: the precision with which GL takes a fractional viewport's bounds
// (glViewportIndexedf). GL_VIEWPORT_SUBPIXEL_BITS lets an implementation round them to
// 2^-bits (OpenGL 4.6 section 13.6.1; Mesa reports 0, whole pixels); the allowance takes that
// freedom at 0 (ref/viewport.hpp). This says what GL does: the coverage of triangles in a
// fractional viewport against the exact rendering of the floats, and of the bounds rounded down
// and to the nearest whole pixel.
#pragma once

#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/model.hpp"
#include "identify/probes.hpp"

namespace glrc::identify {

struct ViewportCandidate {
  std::string name;  // "float", "nearest", "floor"
  Viewport viewport;
  size_t mismatches = 0;  // pixels whose primitive differs from GL's
};

struct ViewportFinding {
  bool available = false;  // GL has glViewportIndexedf (else nothing was drawn)
  int reported = -1;       // GL_VIEWPORT_SUBPIXEL_BITS (-1: not available)
  std::string identified;  // the candidate with the fewest mismatches ("" when not available)
  size_t pixels = 0;       // pixels GL covered
  std::vector<ViewportCandidate> candidates;
};

// Triangles of random float positions in a viewport whose bounds are quarter pixels.
Case viewport_triangles(Random& rnd);
// The candidate viewports' coverage against GL's frame of `p`, rendered with model `m`.
ViewportFinding identify_viewport(const Probe& p, const Model& m, int reported);

}  // namespace glrc::identify
