// glrefcheck identify: which Model explains an implementation best, with the evidence (the
// probes and findings are identify/'s; this prints them).
#pragma once

#include "cli/session.hpp"
#include "gl_harness/gl_harness.hpp"

namespace glrc::cli {

int cmd_identify(const Options& o);

// The model that judges cases on `renderer` in this process (diff, selftest):
// identify::choose_model with the command line's model (model_from_command_line) and the fixed
// default of the options (model_of) as the fallback.
ModelChoice choose_model(const Options& o, gl::Renderer& renderer);

}  // namespace glrc::cli
