#include "report/channel_error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "compare/compare.hpp"

namespace glrc::report {

ChannelError channel_error(const Case& c, const Expectation& expected, const Frame& gl,
                           Channel channel, const Tolerance& tolerance) {
  const Frame& reference = expected.frame;
  const compare::ChannelAllowance allowance(c, expected, tolerance, channel);
  ChannelError e;
  e.name = channel_name(c, channel);
  e.width = reference.width;
  e.height = reference.height;
  e.reference = reference.values(channel);
  e.gl = gl.values(channel);

  const size_t n = reference.pixel_count();
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  e.signed_error.assign(n, kNaN);
  e.ulps.assign(n, std::numeric_limits<double>::quiet_NaN());
  e.compared.assign(n, false);
  e.allowed_ulps.assign(n, std::numeric_limits<double>::quiet_NaN());
  e.allowed.assign(n, kNaN);
  const compare::UlpTable ulp_table(c);

  for (size_t i = 0; i < n; ++i) {
    const compare::Judged judged = compare::judged_against(c, expected, gl, i, tolerance);
    if (!judged.compared) continue;
    // Where GL kept another fragment that may win the depth test, that is the expectation.
    const float expectation = judged.value(expected, i, channel);
    // Not judged where the specification determines no value, as compare counts it.
    if (!compare::value_determined(expectation, tolerance)) continue;
    e.compared[i] = true;
    e.reference[i] = expectation;
    // Both values are float32, so the difference is exact in double.
    e.signed_error[i] = float(double(e.gl[i]) - double(e.reference[i]));
    const double ulp = ulp_table.ulp(judged.primitive(expected, i), channel);
    const compare::PixelError pe = compare::pixel_error(e.reference[i], e.gl[i], ulp);
    e.ulps[i] = pe.ulps;
    const double allowed = judged.allowed(allowance, i, ulp, channel);
    e.allowed[i] = float(allowed);
    e.allowed_ulps[i] = allowed / ulp;
    if (std::isfinite(pe.ulps))
      e.max_finite_ulps = std::max(e.max_finite_ulps, pe.ulps);
    else
      ++e.non_finite;
  }
  return e;
}

namespace {

// A map of another per-pixel quantity over the same compared pixels.
ChannelError with_values(const ChannelError& e, std::vector<double> values, std::string quantity,
                         std::string unit) {
  ChannelError m = e;
  m.ulps = std::move(values);
  m.quantity = std::move(quantity);
  m.unit = std::move(unit);
  m.max_finite_ulps = 0;
  m.non_finite = 0;
  for (size_t i = 0; i < m.ulps.size(); ++i) {
    if (!m.compared[i]) continue;
    if (std::isfinite(m.ulps[i]))
      m.max_finite_ulps = std::max(m.max_finite_ulps, m.ulps[i]);
    else
      ++m.non_finite;
  }
  return m;
}

}  // namespace

ChannelError as_allowance_map(const ChannelError& e) {
  ChannelError m = with_values(e, e.allowed_ulps,
                               "allowed |GL - reference| in ulp of the attribute scale", "ulp");
  m.name = e.name + " allowed";
  m.judged = false;
  return m;
}

ChannelError as_ratio_map(const ChannelError& e) {
  std::vector<double> ratio(e.ulps.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t i = 0; i < ratio.size(); ++i)
    if (e.compared[i])
      ratio[i] = e.ulps[i] == 0                                      ? 0.0
                 : e.allowed_ulps[i] > 0 && std::isfinite(e.ulps[i]) ? e.ulps[i] / e.allowed_ulps[i]
                                                                     : INFINITY;
  ChannelError m = with_values(
      e, std::move(ratio), "|GL - reference| / allowed: share of the allowance used", "x allowed");
  m.name = e.name + " actual/allowed";
  m.allowed_ulps.assign(m.ulps.size(), 1.0);  // over 1 fails
  return m;
}

std::array<double, 4> badness(const ChannelError& e, size_t i) {
  if (!e.compared[i]) return {0, 0, 0, 0};
  const double ulps = e.ulps[i], allowed = e.allowed_ulps[i];
  const bool finite = std::isfinite(ulps);
  double share = finite ? (allowed > 0 ? ulps / allowed : (ulps > 0 ? INFINITY : 0)) : INFINITY;
  if (std::isnan(share)) share = INFINITY;
  return {1, finite ? 0.0 : 1.0, share, finite ? ulps : 0.0};
}

namespace {

constexpr size_t kFullResolutionPixels = size_t(1) << 20;
constexpr int kLargestMapSide = 1024;
// A shrunk map keeps, per pixel, the error and the allowance in ulps (doubles) and whether it
// was compared (downsampled); all the maps of a case together stay within kMapBytes.
constexpr size_t kMapPixelBytes = 2 * sizeof(double) + 1;
constexpr size_t kMapBytes = size_t(128) << 20;

}  // namespace

int map_factor(int width, int height, size_t channels) {
  if (size_t(width) * size_t(height) <= kFullResolutionPixels) return 1;
  // At most kLargestMapSide on the long side; then larger blocks until the maps of every
  // channel shown fit in kMapBytes together, so that a frame with many failing channels makes
  // all its maps in one pass over its rows.
  int factor = (std::max(width, height) + kLargestMapSide - 1) / kLargestMapSide;
  auto bytes = [&](int f) {
    const size_t pixels = size_t((width + f - 1) / f) * size_t((height + f - 1) / f);
    return pixels * kMapPixelBytes * std::max<size_t>(channels, 1);
  };
  while (bytes(factor) > kMapBytes && factor < std::max(width, height))
    factor *= 2;
  return factor;
}

ChannelError downsampled(const ChannelError& e, int factor) {
  if (factor <= 1) return e;
  ChannelError d;
  d.name = e.name, d.quantity = e.quantity, d.unit = e.unit, d.judged = e.judged;
  d.width = (e.width + factor - 1) / factor;
  d.height = (e.height + factor - 1) / factor;
  d.max_finite_ulps = e.max_finite_ulps;
  d.non_finite = e.non_finite;
  const size_t n = size_t(d.width) * size_t(d.height);
  // What the maps show only: the values themselves are read from tiles (diff_images.cpp).
  d.ulps.resize(n), d.allowed_ulps.resize(n), d.compared.resize(n);
  for (int by = 0; by < d.height; ++by)
    for (int bx = 0; bx < d.width; ++bx) {
      size_t pick = size_t(by * factor) * size_t(e.width) + size_t(bx * factor);
      std::array<double, 4> worst = badness(e, pick);
      for (int y = by * factor; y < std::min(e.height, (by + 1) * factor); ++y)
        for (int x = bx * factor; x < std::min(e.width, (bx + 1) * factor); ++x) {
          const size_t i = size_t(y) * size_t(e.width) + size_t(x);
          const auto b = badness(e, i);
          if (b > worst) worst = b, pick = i;
        }
      const size_t o = size_t(by) * size_t(d.width) + size_t(bx);
      d.ulps[o] = e.ulps[pick], d.allowed_ulps[o] = e.allowed_ulps[pick];
      d.compared[o] = e.compared[pick];
    }
  return d;
}

long worst_pixel(const ChannelError& e) {
  long pick = -1;
  std::array<double, 4> worst{0, 0, 0, 0};
  for (size_t i = 0; i < e.compared.size(); ++i) {
    const auto b = badness(e, i);
    if (b[0] > 0 && (pick < 0 || b > worst)) worst = b, pick = long(i);
  }
  return pick;
}

}  // namespace glrc::report
