// The error heatmap of one channel: the frame upright and upscaled, coloured by error on the
// ErrorScale, with a title and a legend that make the picture readable on its own.
#pragma once

#include <optional>
#include <string>

#include "report/canvas.hpp"
#include "report/channel_error.hpp"

namespace glrc::report {

// tolerance_ulps: a single tolerance to mark on the legend, or NaN when it varies per pixel
// (error.allowed_ulps then says which pixels are over).
Canvas render_heatmap(const ChannelError& error, double tolerance_ulps,
                      const std::optional<std::string>& font);

}  // namespace glrc::report
