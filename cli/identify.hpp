// glrefcheck identify: which Model explains an implementation best, with the evidence.
#pragma once

#include "cli/session.hpp"
#include "core/model.hpp"
#include "gl_harness/gl_harness.hpp"

namespace glrc::cli {

int cmd_identify(const Options& o);

// The subpixel bits, attribute planes and tie-break rule `identify` finds on `renderer` (the
// same probes, without printing): about 0.5 s on llvmpipe. Throws InputError when GL cannot
// draw a probe.
Model identify_model(gl::Renderer& renderer);

// The model that judges cases on `renderer` in this process (diff, selftest): the command
// line's (model_from_command_line), else the identified one, from the cache when it holds this
// implementation, else identified now and cached. An identification that fails gives the fixed
// default model, its source saying why.
ModelChoice choose_model(const Options& o, gl::Renderer& renderer);

}  // namespace glrc::cli
