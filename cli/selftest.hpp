// glrefcheck selftest: plants each fault of selftest/ on the GL side, runs the cases, and shows
// which cases catch it; and that no case fails without a fault.
#pragma once

#include "cli/session.hpp"

namespace glrc::cli {

int cmd_selftest(const Options& o);

}  // namespace glrc::cli
