// Reading options back from JSON with the command line's checks (cli/session.cpp, cli/journal.cpp).
#pragma once

#include <fmt/core.h>
#include <climits>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/session.hpp"
#include "core/text.hpp"

namespace glrc::cli {

// Options read back from JSON (the worker's from its runner, a run's from its journal), each
// field checked as the command line checks it: InputError naming `where` and the field.
class OptionsReader {
 public:
  OptionsReader(const nlohmann::json& j, std::string where) : j_(j), where_(std::move(where)) {
    if (!j_.is_object()) bad("options", "an object");
  }
  std::string text(const char* key, const std::vector<std::string>& allowed = {}) const {
    const nlohmann::json& v = at(key);
    if (!v.is_string()) bad(key, "a string");
    const auto s = v.get<std::string>();
    if (allowed.empty()) return s;
    std::string names;
    for (const std::string& a : allowed) {
      if (s == a) return s;
      names += names.empty() ? a : ", " + a;
    }
    bad(key, "one of " + names + ", got \"" + printable(s, 80) + "\"");
  }
  // One of enum E's names (core/names.hpp), or of `allowed` among them when given.
  template <class E>
  E named(const char* key, const std::vector<std::string>& allowed = names_of<E>()) const {
    return *from_name<E>(text(key, allowed));
  }
  bool flag(const char* key) const {
    const nlohmann::json& v = at(key);
    if (!v.is_boolean()) bad(key, "true or false");
    return v.get<bool>();
  }
  int whole(const char* key, int lo, int hi = INT_MAX) const {
    const nlohmann::json& v = at(key);
    // Parsed, a number >= 0 is unsigned, and may be beyond int64_t.
    const bool ok = v.is_number_integer() &&
                    (v.is_number_unsigned() ? v.get<uint64_t>() <= uint64_t(hi) &&
                                                  (lo <= 0 || v.get<uint64_t>() >= uint64_t(lo))
                                            : v.get<int64_t>() >= lo && v.get<int64_t>() <= hi);
    if (!ok)
      bad(key,
          fmt::format("a whole number from {} to {}, got {}", lo, hi, printable(v.dump(), 80)));
    return v.get<int>();
  }
  double number(const char* key, double lo, double hi) const {
    const nlohmann::json& v = at(key);
    if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
      bad(key, fmt::format("a number from {:g} to {:g}, got {}", lo, hi, printable(v.dump(), 80)));
    return v.get<double>();
  }
  std::vector<std::string> texts(const char* key) const {
    const nlohmann::json& v = at(key);
    std::vector<std::string> out;
    if (!v.is_array()) bad(key, "an array of strings");
    for (const nlohmann::json& e : v) {
      if (!e.is_string()) bad(key, "an array of strings");
      out.push_back(e.get<std::string>());
    }
    return out;
  }
  bool has(const char* key) const { return j_.contains(key); }

 private:
  const nlohmann::json& at(const char* key) const {
    if (!j_.contains(key)) bad(key, "a field \"" + std::string(key) + "\"");
    return j_[key];
  }
  [[noreturn]] void bad(const std::string& key, const std::string& expected) const {
    throw InputError(where_ + ": options." + key + ": expected " + expected);
  }
  const nlohmann::json& j_;
  std::string where_;
};

// The options `options_json` writes (the worker's), from `r`.
Options options_from_json(const OptionsReader& r);

}  // namespace glrc::cli
