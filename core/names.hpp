// One name table per enum: the names the command line takes, JSON holds and reports print,
// each written once, next to its enum (a specialisation of Names<E>). to_string and the
// *_from_string functions, CLI11's choices (cli/), the case loader's and the results reader's
// choices, and every JSON conversion are derived from these tables.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glrc {

// Specialised per enum: `static constexpr std::array<std::pair<E, std::string_view>, N>
// table`, every enumerator once, in the order choices are listed.
template <class E>
struct Names;

// The enumerator's name; "" for a value outside the table (never for a valid enumerator).
template <class E>
constexpr std::string_view name_of(E e) {
  for (const auto& [value, name] : Names<E>::table)
    if (value == e) return name;
  return {};
}

// The enumerator named `s` exactly (case matters); nullopt for anything else.
template <class E>
constexpr std::optional<E> from_name(std::string_view s) {
  for (const auto& [value, name] : Names<E>::table)
    if (name == s) return value;
  return std::nullopt;
}

// Every name, in the table's order: the choices of an option or a field.
template <class E>
std::vector<std::string> names_of() {
  std::vector<std::string> out;
  for (const auto& entry : Names<E>::table)
    out.emplace_back(entry.second);
  return out;
}

// The choices for a message: "a, b or c", each in double quotes.
template <class E>
std::string choices_text() {
  std::string out;
  const auto& t = Names<E>::table;
  for (size_t k = 0; k < t.size(); ++k)
    out += std::string(k == 0              ? ""
                       : k + 1 == t.size() ? " or "
                                           : ", ") +
           "\"" + std::string(t[k].second) + "\"";
  return out;
}

}  // namespace glrc
