#include "report/heatmap.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/error_scale.hpp"
#include "report/format.hpp"

namespace glrc::report {
namespace {

constexpr int kMargin = 12;
constexpr int kTitleHeight = 66;
constexpr int kMinWidth = 512;  // room for the legend even when the frame is large-pixelled
constexpr int kRampHeight = 16;
constexpr int kLegendHeight = 96;
constexpr Rgb kBackground{0.1f, 0.1f, 0.1f};
constexpr Rgb kText{0.92f, 0.92f, 0.92f};
constexpr Rgb kToleranceMark{1.0f, 0.3f, 0.3f};

std::string tick_text(int power_of_ten) {
  return power_of_ten <= 3 ? fmt::format("{}", int(std::pow(10, power_of_ten)))
                           : fmt::format("1e{}", power_of_ten);
}

// The colour ramp from 0 to scale.upper, ticks at 0 and the powers of ten, the upper end
// labelled, the tolerance marked where it falls on the ramp, and swatches for the colours that
// are not on the ramp.
void draw_legend(Canvas& canvas, const ErrorScale& scale, const ChannelError& error,
                 double tolerance_ulps, const std::optional<std::string>& font, int top) {
  const int x0 = kMargin + 8, x1 = canvas.width - kMargin - 8, ramp_top = top + 16;
  const auto x_of = [&](double ulps) {
    return x0 + int(std::lround(scale.position(ulps) * (x1 - x0)));
  };
  for (int x = x0; x <= x1; ++x)
    canvas.fill(x, ramp_top, 1, kRampHeight, viridis(double(x - x0) / (x1 - x0)));

  const int tick_top = ramp_top + kRampHeight, label_y = tick_top + 18;
  const auto tick = [&](int x, const std::string& label, Align align) {
    canvas.fill(x, tick_top, 1, 5, kText);
    draw_text(canvas, font, x, label_y, label, 13, kText, align);
  };
  tick(x0, "0", Align::left);
  const int end_label_width = 80;  // keeps power-of-ten labels off the end label
  int last_x = x0;
  for (int p = 0; std::pow(10.0, p) < scale.upper; ++p) {
    const int x = x_of(std::pow(10.0, p));
    if (x - last_x < 36 || x1 - x < end_label_width) continue;
    tick(x, tick_text(p), Align::centre);
    last_x = x;
  }
  tick(x1, ulps_text(scale.upper) + " " + error.unit, Align::right);

  if (tolerance_ulps <= scale.upper) {
    const int x = x_of(tolerance_ulps);
    canvas.fill(x - 1, ramp_top - 4, 3, kRampHeight + 4, kToleranceMark);
    draw_text(canvas, font, x, ramp_top - 5, "tolerance " + ulps_text(tolerance_ulps), 12,
              kToleranceMark,
              x - x0 < 60   ? Align::left
              : x1 - x < 60 ? Align::right
                            : Align::centre);
  }

  const int swatch_y = label_y + 14;
  canvas.fill(x0, swatch_y, 14, 14, kNotComparedColour);
  draw_text(canvas, font, x0 + 20, swatch_y + 12, "not compared (coverage differs or empty)", 13,
            kText);
  const int x_nan = x0 + (x1 - x0) * 2 / 3;
  canvas.fill(x_nan, swatch_y, 14, 14, kNonFiniteColour);
  draw_text(canvas, font, x_nan + 20, swatch_y + 12,
            fmt::format("NaN / Inf ({})", error.non_finite), 13, kText);
}

}  // namespace

Canvas render_heatmap(const ChannelError& error, double tolerance_ulps,
                      const std::optional<std::string>& font) {
  const int factor = upscale_factor(error.width, error.height);
  const int image_w = error.width * factor, image_h = error.height * factor;
  Canvas canvas(std::max(image_w, kMinWidth) + 2 * kMargin, kTitleHeight + image_h + kLegendHeight,
                kBackground);

  const ErrorScale scale(error.max_finite_ulps);
  size_t compared = 0, over = 0;
  for (size_t i = 0; i < error.ulps.size(); ++i) {
    if (!error.compared[i]) continue;
    ++compared;
    // Inf (NaN or Inf from GL) is over any tolerance, an infinite one included.
    const double limit = std::isnan(tolerance_ulps) ? error.allowed_ulps[i] : tolerance_ulps;
    over += std::isinf(error.ulps[i]) || !(error.ulps[i] <= limit);
  }
  const int text_width = canvas.width - 2 * kMargin;
  std::string title = fmt::format(
      "{}   max {} {}   tolerance {}", error.name, ulps_text(error.max_finite_ulps), error.unit,
      std::isnan(tolerance_ulps) ? std::string("per pixel (specification)")
                                 : ulps_text(tolerance_ulps) + " " + error.unit);
  if (error.non_finite > 0) title += fmt::format("   {} NaN/Inf", error.non_finite);
  draw_text(canvas, font, kMargin, 22, title, 16, kText, Align::left, text_width);
  draw_text(canvas, font, kMargin, 41,
            fmt::format("{}, log colour scale, {}x upscaled", error.quantity, factor), 12, kText,
            Align::left, text_width);
  draw_text(canvas, font, kMargin, 57,
            error.judged ? fmt::format("{} of {} compared pixels over tolerance", over, compared)
                         : fmt::format("{} compared pixels", compared),
            12, kText, Align::left, text_width);

  const int image_x = (canvas.width - image_w) / 2;
  paint_frame(canvas, image_x, kTitleHeight, factor, error.width, error.height, [&](int x, int y) {
    const size_t i = size_t(y) * error.width + x;
    return error.compared[i] ? scale.colour(error.ulps[i]) : kNotComparedColour;
  });
  draw_legend(canvas, scale, error, tolerance_ulps, font, kTitleHeight + image_h);
  return canvas;
}

}  // namespace glrc::report
