#include "report/error_scale.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace glrc::report {

ErrorScale::ErrorScale(double max_finite_ulps) : upper(std::max(1.0, max_finite_ulps)) {}

double ErrorScale::position(double ulps) const {
  return std::clamp(std::log1p(std::max(0.0, ulps)) / std::log1p(upper), 0.0, 1.0);
}

Rgb ErrorScale::colour(double ulps) const {
  if (!std::isfinite(ulps)) return kNonFiniteColour;
  return viridis(position(ulps));
}

Rgb viridis(double t) {
  // matplotlib's viridis sampled at ten even steps (#440154 ... #FDE725); linear in between
  // is indistinguishable from the full table at heatmap sizes.
  static constexpr Rgb kStops[] = {
      {0x44 / 255.f, 0x01 / 255.f, 0x54 / 255.f}, {0x48 / 255.f, 0x28 / 255.f, 0x78 / 255.f},
      {0x3e / 255.f, 0x4a / 255.f, 0x89 / 255.f}, {0x31 / 255.f, 0x68 / 255.f, 0x8e / 255.f},
      {0x26 / 255.f, 0x82 / 255.f, 0x8e / 255.f}, {0x1f / 255.f, 0x9e / 255.f, 0x89 / 255.f},
      {0x35 / 255.f, 0xb7 / 255.f, 0x79 / 255.f}, {0x6d / 255.f, 0xcd / 255.f, 0x59 / 255.f},
      {0xb4 / 255.f, 0xde / 255.f, 0x2c / 255.f}, {0xfd / 255.f, 0xe7 / 255.f, 0x25 / 255.f}};
  constexpr int kLast = int(std::size(kStops)) - 1;
  const double s = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * kLast;
  const int i = std::min(int(s), kLast - 1);
  return mix(kStops[i], kStops[i + 1], float(s - i));
}

}  // namespace glrc::report
