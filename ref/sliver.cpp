#include "ref/sliver.hpp"

#include <algorithm>
#include <cmath>

namespace glrc::ref {

Sliver::Sliver(const PositionFreedom& freedom) : anywhere(freedom.reaches_eye()) {
  const auto& points = freedom.sliver_sources();
  double farthest = -1, magnitude = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    magnitude = std::max({magnitude, std::fabs(points[i][0]), std::fabs(points[i][1])});
    for (size_t j = i; j < points.size(); ++j) {
      const double d = std::hypot(points[j][0] - points[i][0], points[j][1] - points[i][1]);
      if (d > farthest) farthest = d, a = points[i], b = points[j];
    }
  }
  delta = freedom.largest() + std::ldexp(1 + magnitude, -30);
}

Sliver::Sliver(const TurningPiece& piece) {
  const auto& q = piece.p;
  double farthest = -1, magnitude = 0;
  size_t third = 0;
  for (size_t i = 0; i < 3; ++i) {
    magnitude = std::max({magnitude, std::fabs(q[i][0]), std::fabs(q[i][1])});
    const size_t j = (i + 1) % 3;
    const double d = std::hypot(q[j][0] - q[i][0], q[j][1] - q[i][1]);
    if (d > farthest) farthest = d, a = q[i], b = q[j], third = (i + 2) % 3;
  }
  // The third vertex's distance from the segment is its distance from their line: the foot of
  // the altitude onto a triangle's longest side lies on that side (both angles beside it are
  // acute).
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const auto& r = q[third];
  const double off = farthest > 0 ? std::fabs(dx * (r[1] - a[1]) - dy * (r[0] - a[0])) / farthest
                                  : std::hypot(r[0] - a[0], r[1] - a[1]);
  delta = piece.delta + off + std::ldexp(1 + magnitude, -30);
}

std::pair<int, int> Sliver::row_span(int py, int x0, int x1) const {
  const std::pair<int, int> none{x0, x0 - 1};
  if (anywhere) return {x0, x1};
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double y = py + 0.5;
  // The part of the segment within delta of the row, a + t·(b - a) for t in [t0, t1].
  double t0 = 0, t1 = 1;
  if (dy != 0) {
    t0 = (y - delta - a[1]) / dy, t1 = (y + delta - a[1]) / dy;
    if (t0 > t1) std::swap(t0, t1);
    t0 = std::max(t0, 0.0), t1 = std::min(t1, 1.0);
    if (!(t0 <= t1)) return none;
  } else if (!(std::fabs(y - a[1]) <= delta)) {
    return none;
  }
  const double xa = a[0] + t0 * dx, xb = a[0] + t1 * dx;
  const double lo = std::min(xa, xb) - delta - 0.5, hi = std::max(xa, xb) + delta - 0.5;
  const int first = std::max(x0, int(std::clamp(std::ceil(lo), -1e9, 1e9)));
  const int last = std::min(x1, int(std::clamp(std::floor(hi), -1e9, 1e9)));
  return {first, last};
}

}  // namespace glrc::ref
