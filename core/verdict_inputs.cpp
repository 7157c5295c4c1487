#include "core/verdict_inputs.hpp"

namespace glrc {

std::optional<VerdictInputDifference> verdict_input_difference(
    const std::map<std::string, std::string>& mine,
    const std::map<std::string, std::string>& other) {
  const auto shown = [](const std::map<std::string, std::string>& m, const std::string& name) {
    const auto it = m.find(name);
    return it == m.end()        ? std::string("nothing recorded")
           : it->second.empty() ? std::string("none")
                                : it->second;
  };
  std::optional<std::string> first;
  for (const auto* m : {&mine, &other})
    for (const auto& [name, value] : *m) {
      const auto a = mine.find(name), b = other.find(name);
      const bool same = a != mine.end() && b != other.end() && a->second == b->second;
      if (!same && (!first || name < *first)) first = name;
    }
  if (!first) return std::nullopt;
  return VerdictInputDifference{*first, shown(mine, *first), shown(other, *first)};
}

}  // namespace glrc
