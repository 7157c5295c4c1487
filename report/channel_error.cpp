#include "report/channel_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "compare/compare.hpp"

namespace glrc::report {

ChannelError channel_error(const Case& c, const Frame& reference, const Frame& gl, int channel) {
  const bool depth = channel == compare::kDepth;
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
  const compare::UlpTable ulp_table(c);

  for (size_t i = 0; i < n; ++i) {
    const int32_t prim = reference.primitive[i];
    if (!compare::same_primitive(c, prim, gl.primitive[i])) continue;
    e.compared[i] = true;
    // Both values are float32, so the difference is exact in double.
    e.signed_error[i] = float(double(e.gl[i]) - double(e.reference[i]));
    const compare::PixelError pe = compare::pixel_error(
        e.reference[i], e.gl[i], ulp_table.ulp(prim, depth ? compare::kDepth : channel));
    e.ulps[i] = pe.ulps;
    if (std::isfinite(pe.ulps))
      e.max_finite_ulps = std::max(e.max_finite_ulps, pe.ulps);
    else
      ++e.non_finite;
  }
  return e;
}

}  // namespace glrc::report
