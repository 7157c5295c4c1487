#include "report/channel_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "compare/compare.hpp"

namespace glrc::report {

ChannelError channel_error(const Case& c, const Frame& reference, const Frame& gl, int channel) {
  const bool depth = channel < 0;
  ChannelError e;
  e.name = depth ? "depth" : component_names(c).at(size_t(channel));
  e.width = reference.width;
  e.height = reference.height;
  e.reference = depth ? reference.depth : reference.components.at(size_t(channel));
  e.gl = depth ? gl.depth : gl.components.at(size_t(channel));

  const size_t n = reference.pixel_count();
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  e.signed_error.assign(n, kNaN);
  e.ulps.assign(n, std::numeric_limits<double>::quiet_NaN());
  e.compared.assign(n, false);
  const double depth_ulp = compare::ulp_of_scale(1.0);

  for (size_t i = 0; i < n; ++i) {
    const int32_t prim = reference.primitive[i];
    if (prim == Frame::kNoPrimitive || gl.primitive[i] != prim) continue;
    e.compared[i] = true;
    const double ref = e.reference[i], got = e.gl[i];
    // Both values are float32, so the difference is exact in double.
    const double diff = got - ref;
    e.signed_error[i] = float(diff);
    const double ulp =
        depth ? depth_ulp : compare::ulp_of_scale(compare::attribute_scale(c, prim, channel));
    // The same infinity in both frames is no error; any other non-finite value is one.
    const double ulps = (got == ref) ? 0.0 : std::fabs(diff) / ulp;
    e.ulps[i] = std::isnan(ulps) ? std::numeric_limits<double>::infinity() : ulps;
    if (std::isfinite(ulps))
      e.max_finite_ulps = std::max(e.max_finite_ulps, ulps);
    else
      ++e.non_finite;
  }
  return e;
}

}  // namespace glrc::report
