// The messages between `run` and its workers (cli/workers/workers.hpp has the protocol), written
// and read in one place so the two sides cannot drift: GL's description in the worker's hello, a
// job line, and the result a case gets when its worker gave none.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/case.hpp"
#include "core/model.hpp"
#include "core/result.hpp"
#include "gl_harness/gl_harness.hpp"

namespace glrc::gl {

// Every GlInfo field, by its own name (nlohmann's ADL conversions). from_json throws
// nlohmann::json::exception for a missing field or one of the wrong type.
void to_json(nlohmann::json& j, const GlInfo& info);
void from_json(const nlohmann::json& j, GlInfo& info);

}  // namespace glrc::gl

namespace glrc::cli {

// {"hello": {GlInfo's fields, "driver_files": [paths]}}.
nlohmann::json hello_message(const gl::GlInfo& info, const std::vector<std::string>& driver_files);

// The job line for case `index`: the case whole (casefile/wire.hpp), whether heatmaps follow a
// failure, and the model that judges it.
std::string job_line(size_t index, const Case& c, bool images, const Model& model);

// Case `index`'s result line, its CaseResult already JSON (report::case_result_json) and
// spliced in, not parsed again: {"index":N,"result":{...}}, with "images":true before "result"
// when heatmaps follow. No newline.
std::string result_line(size_t index, const std::string& result_json, bool images);
// A line in result_line's form, taken apart without parsing the result, which the runner's
// report reader then reads once; nothing for any other line (the runner parses those whole).
struct ResultLine {
  size_t index = 0;
  bool images = false;
  std::string_view result;  // into the line
};
std::optional<ResultLine> read_result_line(std::string_view line);

// The result of a case whose worker gave none (Crash, Timeout): its status and why.
CaseResult unfinished_result(const Case& c, Status status, const std::string& message,
                             double seconds);

}  // namespace glrc::cli
