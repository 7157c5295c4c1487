// Where two runs' verdict inputs (RunInfo::verdict_inputs) differ, as a person reads it: merge
// refuses shards judged otherwise, and says by which input.
#pragma once

#include <map>
#include <optional>
#include <string>

namespace glrc {

struct VerdictInputDifference {
  std::string name;   // the input, as RunInfo::verdict_inputs names it ("strict_coverage", ...)
  std::string value;  // each side's value: "none" where not given, "nothing recorded" where the
  std::string other;  // results hold no such input (written before it was recorded)
};

// The first input, by name, in which `mine` and `other` differ; nullopt when they are the same.
std::optional<VerdictInputDifference> verdict_input_difference(
    const std::map<std::string, std::string>& mine,
    const std::map<std::string, std::string>& other);

}  // namespace glrc
