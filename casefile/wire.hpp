// A loaded Case as one JSON value, for `run` to hand each case to a worker process
// (cli/workers/workers.hpp): the runner reads and validates every case file once, and the worker
// takes the result instead of parsing the file again (a 50 MB case was parsed twice per run). Every
// float travels as its bits, so the worker's case is the runner's, bit for bit. Not a case file
// format: it changes with Case.
#pragma once

#include <nlohmann/json.hpp>

#include "core/case.hpp"

namespace glrc::casefile {

nlohmann::json to_wire(const Case& c);
// Throws std::runtime_error for a value to_wire did not make.
Case from_wire(const nlohmann::json& j);

}  // namespace glrc::casefile
