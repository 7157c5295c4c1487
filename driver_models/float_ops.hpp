// The float32 operations the drivers' code performs, spelled out so that each rounding is the
// driver's. This module is compiled with -ffp-contract=off: a*b+c is two roundings unless
// written as fma32().
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

namespace glrc::driver_models {

inline float fma32(float a, float b, float c) {
  return std::fma(a, b, c);
}

// llvm.fmuladd: one rounding where the JIT targets FMA, two otherwise.
inline float fmuladd(float a, float b, float c, bool fused) {
  return fused ? std::fma(a, b, c) : a * b + c;
}

// llvmpipe runs fragment shaders with MXCSR FTZ and DAZ set (lp_rast.c): subnormal inputs
// read as zero and subnormal results are flushed, keeping the sign.
inline float ftz(float x) {
  return std::fpclassify(x) == FP_SUBNORMAL ? std::copysign(0.0f, x) : x;
}

// cvtps2dq (round to nearest even); NaN and out-of-range give INT32_MIN, as on x86.
inline int32_t cvt_rne_i32(float x) {
  if (!(x >= -2147483648.0f && x < 2147483648.0f)) return std::numeric_limits<int32_t>::min();
  return int32_t(std::nearbyint(x));
}

// C's (int)x on x86 (cvttss2si): truncation; NaN and out-of-range give INT32_MIN.
inline int32_t cvt_trunc_i32(float x) {
  if (!(x > -2147483649.0f && x < 2147483648.0f)) return std::numeric_limits<int32_t>::min();
  return int32_t(x);
}

inline bool is_inf_or_nan(float x) {
  return !std::isfinite(x);
}

}  // namespace glrc::driver_models
