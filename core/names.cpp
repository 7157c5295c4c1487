#include "core/case.hpp"
#include "core/model.hpp"
#include "core/result.hpp"

namespace glrc {

std::vector<std::string> component_names(const Case& c) {
  static const char* kSuffix[] = {"x", "y", "z", "w"};
  std::vector<std::string> names;
  for (const auto& v : c.varyings)
    for (int i = 0; i < v.size; ++i)
      names.push_back(v.name + "." + kSuffix[i]);
  return names;
}

std::vector<int> component_varying(const Case& c) {
  std::vector<int> owner;
  for (size_t k = 0; k < c.varyings.size(); ++k)
    for (int i = 0; i < c.varyings[k].size; ++i)
      owner.push_back(int(k));
  return owner;
}

const char* to_string(TieBreak t) {
  switch (t) {
    case TieBreak::bottom_left:
      return "bottom-left";
    case TieBreak::top_left:
      return "top-left";
    case TieBreak::bottom_right:
      return "bottom-right";
    case TieBreak::top_right:
      return "top-right";
  }
  return "bottom-left";
}

std::string Model::describe() const {
  return "subpixel_bits=" + std::to_string(subpixel_bits) +
         " planes=" + (planes == Planes::snapped ? "snapped" : "unsnapped") +
         " tie=" + to_string(tie_break);
}

const char* to_string(ToleranceMode m) {
  switch (m) {
    case ToleranceMode::spec:
      return "spec";
    case ToleranceMode::ulps:
      return "ulps";
    case ToleranceMode::exact:
      return "exact";
  }
  return "spec";
}

const char* to_string(Status s) {
  switch (s) {
    case Status::pass:
      return "Pass";
    case Status::fail:
      return "Fail";
    case Status::expected_fail:
      return "ExpectedFail";
    case Status::unexpected_pass:
      return "UnexpectedPass";
    case Status::skip:
      return "Skip";
    case Status::error:
      return "Error";
    case Status::crash:
      return "Crash";
    case Status::timeout:
      return "Timeout";
    case Status::flake:
      return "Flake";
  }
  return "Error";
}

std::optional<Status> status_from_string(std::string_view s) {
  for (Status st : {Status::pass, Status::fail, Status::expected_fail, Status::unexpected_pass,
                    Status::skip, Status::error, Status::crash, Status::timeout, Status::flake})
    if (s == to_string(st)) return st;
  return std::nullopt;
}

}  // namespace glrc
