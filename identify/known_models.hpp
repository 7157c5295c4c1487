// What `glrefcheck identify` finds for Mesa's drivers (22.3.6 and 25.0.7, OSMesa and EGL alike;
// docs/findings.md), and the GL_SUBPIXEL_BITS each reports, which sets the specification's
// allowance: what `run` judges them by. For whoever must judge a case as a run on that driver
// would without GL at hand (`export --driver`); tests/gl checks the table against identify.
#pragma once

#include <span>
#include <string_view>

#include "core/model.hpp"

namespace glrc::identify {

struct KnownModel {
  std::string_view driver;     // Mesa's gallium driver: "llvmpipe", "softpipe", "zink"
  Model model;                 // what identify finds
  int reported_subpixel_bits;  // GL_SUBPIXEL_BITS as the driver reports it
};

std::span<const KnownModel> known_models();
// The driver's entry, or nullptr for a driver not in the table.
const KnownModel* known_model(std::string_view driver);

}  // namespace glrc::identify
