// The run's options read back from JSON (the worker's from its runner, a run's from its journal)
// through the shared typed reader (typed_json/reader.hpp), each field checked as the command
// line checks it, in the options' wording: "<where>: options.jobs: expected a whole number from
// 0 to 2147483647, got -1" (an InputError: one line, exit 2).
#pragma once

#include <fmt/core.h>
#include <climits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/session.hpp"
#include "core/names.hpp"
#include "core/text.hpp"
#include "typed_json/reader.hpp"

namespace glrc::cli::option_fields {

using typed_json::path_key;
using typed_json::Reader;

// A reader for options from `where` ("journal.jsonl:1"): brief wording, InputError.
inline Reader reader(std::string where) {
  return Reader(std::move(where), typed_json::Wording::brief, &typed_json::raise_as<InputError>);
}

// Each reads the field `key` of the options object `j` at `path` ("options"); a missing field
// is `expected a field "key"`, and `j` must be an object (object()).
inline const nlohmann::json& object(const Reader& r, const nlohmann::json& j,
                                    const std::string& path) {
  if (!j.is_object()) r.fail(path, "an object");
  return j;
}
// A string; with `allowed`, one of them ("one of spec, exact, got "ulps"").
inline std::string text(const Reader& r, const nlohmann::json& j, const std::string& path,
                        const char* key, const std::vector<std::string>& allowed = {}) {
  const std::string& s = r.string(r.required(j, path, key), path_key(path, key));
  if (allowed.empty()) return s;
  std::string names;
  for (const std::string& a : allowed) {
    if (s == a) return s;
    names += names.empty() ? a : ", " + a;
  }
  r.fail(path_key(path, key), "one of " + names, "\"" + printable(s, 80) + "\"");
}
// One of enum E's names (core/names.hpp), or of `allowed` among them when given.
template <class E>
E named(const Reader& r, const nlohmann::json& j, const std::string& path, const char* key,
        const std::vector<std::string>& allowed = names_of<E>()) {
  return *from_name<E>(text(r, j, path, key, allowed));
}
inline bool flag(const Reader& r, const nlohmann::json& j, const std::string& path,
                 const char* key) {
  return r.boolean(r.required(j, path, key), path_key(path, key));
}
// An integer in [lo, hi]: "a whole number from 1 to 2, got 9", for a value of another type too.
inline int whole(const Reader& r, const nlohmann::json& j, const std::string& path, const char* key,
                 int lo, int hi = INT_MAX) {
  const nlohmann::json& v = r.required(j, path, key);
  const std::string what = fmt::format("a whole number from {} to {}", lo, hi);
  if (!v.is_number_integer()) r.fail(path_key(path, key), what, printable(v.dump(), 80));
  return int(r.integer(v, path_key(path, key), lo, hi, what));
}
// A number in [lo, hi]: "a number from 0.001 to 1e+06, got -5".
inline double number(const Reader& r, const nlohmann::json& j, const std::string& path,
                     const char* key, double lo, double hi) {
  const nlohmann::json& v = r.required(j, path, key);
  if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
    r.fail(path_key(path, key), fmt::format("a number from {:g} to {:g}", lo, hi),
           printable(v.dump(), 80));
  return v.get<double>();
}
// An array of strings (the message names the field, not the element).
inline std::vector<std::string> texts(const Reader& r, const nlohmann::json& j,
                                      const std::string& path, const char* key) {
  const nlohmann::json& v = r.required(j, path, key);
  std::vector<std::string> out;
  if (!v.is_array()) r.fail(path_key(path, key), "an array of strings");
  for (const nlohmann::json& e : v) {
    if (!e.is_string()) r.fail(path_key(path, key), "an array of strings");
    out.push_back(e.get<std::string>());
  }
  return out;
}

}  // namespace glrc::cli::option_fields
