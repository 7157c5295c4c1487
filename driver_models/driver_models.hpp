// driver_models: bit-exact CPU models of Mesa 22.3.6's llvmpipe and softpipe as glrefcheck's
// GL harness drives them (user FBO, RGBA32F varyings, R32I primitive id, 32F depth). They sit
// beside the exact reference in ref/, never in its place: the reference says what GL asks for,
// these say what one driver does, bit for bit, so a difference between a driver and the
// reference can be traced to the driver step that makes it.
#pragma once

#include <optional>
#include <string_view>

#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/names.hpp"

namespace glrc::driver_models {

enum class Driver { llvmpipe, softpipe };
}  // namespace glrc::driver_models
namespace glrc {
template <>
struct Names<driver_models::Driver> {
  static constexpr std::array<std::pair<driver_models::Driver, std::string_view>, 2> table{{
      {driver_models::Driver::llvmpipe, "llvmpipe"},
      {driver_models::Driver::softpipe, "softpipe"},
  }};
};
}  // namespace glrc
namespace glrc::driver_models {
const char* to_string(Driver d);  // "llvmpipe", "softpipe"
std::optional<Driver> driver_from_string(std::string_view s);

// Whether llvmpipe on this CPU fuses its llvm.fmuladd calls (viewport transform, attribute
// evaluation): Mesa's util_cpu_caps.has_fma, i.e. CPUID FMA and AVX with the OS saving YMM,
// unless GALLIUM_OVERRIDE_CPU_CAPS or GALLIUM_NOSSE turns AVX off, as Mesa reads them.
bool llvmpipe_uses_fma();

struct Options {
  bool fma = llvmpipe_uses_fma();  // llvmpipe only; softpipe never fuses
};

// The frame the driver produces for the case: primitive id, depth and every varying component
// per pixel, with NaN where the driver gives NaN.
Frame render(const Case& c, Driver d, const Options& o = {});

}  // namespace glrc::driver_models
