// Coverage: is a pixel centre inside the (clipped) triangle, with a tie-break rule for centres
// exactly on an edge so that triangles sharing an edge cover each of its pixels exactly once.
#pragma once

#include <array>

#include "core/model.hpp"
#include "ref/clipping.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

class CoverageTest {
 public:
  CoverageTest(const TriangleSetup& t, const Model& m);
  bool covers(int px, int py) const;
  // Whether the centre lies within `step` pixels of the triangle's boundary (its edges, or the
  // near/far lines where the triangle crosses them): inside the triangle grown by `step`, and
  // not inside the triangle shrunk by it.
  bool near_boundary(int px, int py, double step) const;

 private:
  const TriangleSetup& t_;
  DepthClip clip_;
  std::array<SignEvaluator, 3> edges_;  // homogeneous path
  std::array<bool, 3> tie_inside_{};    // a centre exactly on edge i is covered
  std::array<double, 3> inv_norm_{};    // snapped path: 1 / |gradient| per pixel
};

}  // namespace glrc::ref
