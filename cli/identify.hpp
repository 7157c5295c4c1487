// glrefcheck identify: which Model explains an implementation best, with the evidence.
#pragma once

#include "cli/session.hpp"

namespace glrc::cli {

int cmd_identify(const Options& o);

}  // namespace glrc::cli
