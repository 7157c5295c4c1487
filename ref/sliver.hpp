// Slivers: what a triangle of zero area may become. No pixel centre lies inside it (det = 0),
// but the vertices an implementation rasterizes may each lie up to `delta` pixels from the exact
// ones in x and in y (freedom.hpp), and then make a sliver that covers centres near the segment
// its window image is. The sliver lies in the convex hull of the moved vertices, so within the
// segment grown by the square [-delta, delta]²: any primitive and any fragment count at a centre
// there is what some conforming implementation draws (edge::unstable). A triangle through the
// eye (PositionFreedom::reaches_eye) has a vertex of undefined position: every centre. A thin
// piece of a clipped polygon that may turn over is one too.
#pragma once

#include <array>
#include <utility>

#include "ref/freedom.hpp"

namespace glrc::ref {

struct Sliver {
  // The ends are the farthest two of the freedom's sources: collinear in exact arithmetic, so
  // the segment between them holds every one; `delta` grows by the doubles' rounding of them.
  explicit Sliver(const PositionFreedom& freedom);
  // The centres a piece of a clipped polygon that may turn over covers, moved or turned
  // (PositionFreedom::turning_pieces): its farthest two vertices are the ends, and `delta` also
  // holds the third's distance from their segment, so the grown segment holds the piece's
  // hull grown by its vertices' freedom.
  explicit Sliver(const TurningPiece& piece);
  // The centres of row py (window coordinates) within the grown segment, as columns
  // [first, last] within [x0, x1]; first > last for none. Every column of [x0, x1] through the
  // eye.
  std::pair<int, int> row_span(int py, int x0, int x1) const;

  std::array<double, 2> a{}, b{};  // the segment's ends, window coordinates (pixels)
  double delta = 0;                // how far the sliver's vertices may lie from it, pixels
  bool anywhere = false;           // through the eye: every centre
};

}  // namespace glrc::ref
