#include "ref/coverage.hpp"

#include <algorithm>
#include <cmath>

namespace glrc::ref {

namespace {

// The tie-break rule, from the inward normal (a, b) of the edge in window coordinates (y up):
// a > 0 is a left edge, a == 0 with b > 0 a bottom edge, with b < 0 a top edge.
bool tie_inside(int sign_a, int sign_b, TieBreak rule) {
  if (sign_a != 0) return sign_a > 0;
  return rule == TieBreak::bottom_left ? sign_b > 0 : sign_b < 0;
}

int sign128(int128 v) { return v > 0 ? 1 : v < 0 ? -1 : 0; }

}  // namespace

CoverageTest::CoverageTest(const TriangleSetup& t, const Model& m) : t_(t), clip_(depth_clip(t)) {
  for (int i = 0; i < 3; ++i) {
    if (t.path == CoveragePath::snapped) {
      const auto& e = t.snapped_edges[i];
      tie_inside_[i] = tie_inside(sign128(e.a), sign128(e.b), m.tie_break);
      inv_norm_[i] = 1.0 / std::hypot(double(e.a), double(e.b));
    } else {
      const auto& e = t.homogeneous_edges[i];
      edges_[i] = SignEvaluator(e);
      tie_inside_[i] = tie_inside(sgn(e.a), sgn(e.b), m.tie_break);
    }
  }
}

bool CoverageTest::covers(int px, int py) const {
  for (int i = 0; i < 3; ++i) {
    const int s = t_.path == CoveragePath::snapped ? sign128(t_.snapped_edges[i].at(px, py))
                                                   : edges_[i].sign(px, py);
    if (s < 0 || (s == 0 && !tie_inside_[i])) return false;
  }
  if (clip_.crosses_near && clip_.near.sign(px, py) < 0) return false;
  if (clip_.crosses_far && clip_.far.sign(px, py) < 0) return false;
  return true;
}

bool CoverageTest::near_boundary(int px, int py, double step) const {
  double nearest = INFINITY;
  auto consider = [&](double d) {
    nearest = std::min(nearest, d);
    return d >= -step;
  };
  for (int i = 0; i < 3; ++i) {
    const double d = t_.path == CoveragePath::snapped
                         ? double(t_.snapped_edges[i].at(px, py)) * inv_norm_[i]
                         : edges_[i].distance(px, py);
    if (!consider(d)) return false;
  }
  if (clip_.crosses_near && !consider(clip_.near.distance(px, py))) return false;
  if (clip_.crosses_far && !consider(clip_.far.distance(px, py))) return false;
  return nearest <= step;
}

}  // namespace glrc::ref
