// ErrorScale: how an error in ULPs becomes a colour in the heatmaps. Logarithmic, because
// errors of interest span from 1 ulp to millions; perceptually ordered (viridis), so brighter
// always means larger, also in greyscale print.
#pragma once

#include "report/canvas.hpp"

namespace glrc::report {

inline constexpr Rgb kNotComparedColour{0.5f, 0.5f, 0.5f};  // neutral, outside viridis
inline constexpr Rgb kNonFiniteColour{1.0f, 0.0f, 1.0f};    // magenta: NaN or Inf

struct ErrorScale {
  double upper = 1;  // ulps at the bright end: the largest finite error, at least 1

  explicit ErrorScale(double max_finite_ulps);
  // 0 for 0 ulp, 1 for `upper`: log(1 + ulps) / log(1 + upper), so 0 ulp has a place.
  double position(double ulps) const;
  // The colour of a finite error; kNonFiniteColour for an infinite or NaN one.
  Rgb colour(double ulps) const;
};

// The viridis colour map at t in [0, 1] (clamped): dark purple at 0, yellow at 1.
Rgb viridis(double t);

}  // namespace glrc::report
