// A typed reader of parsed JSON: each accessor returns the value a field must hold or throws one
// line naming the source, the field's path and what was expected, so that a typo in a file of
// thousands of fields points at its place at once. Shared by the case loader (casefile/), the
// results reader (report/) and the options a run hands its workers and journal (cli/).
//
// The accessors are templates on the nlohmann::basic_json type: the case loader reads a
// document of its own allocator (typed_json/arena.hpp), the others plain nlohmann::json.
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/names.hpp"
#include "typed_json/error.hpp"
#include "typed_json/text.hpp"

namespace glrc::typed_json {

// How a reader words its messages. Each is pinned by tests and read by people's scripts, so
// the two wordings in use stay as they were.
enum class Wording {
  // Case files: every message says what came ("got 3", "got nothing (the field is required)").
  full,
  // results.json and the run's options: what was expected only, except that a number out of
  // its range says what came; a missing field is named (`expected a field "jobs"`).
  brief,
};

// A value of float32 magnitude this or more rounds to infinity (half-way between FLT_MAX and
// 2^128, ties to even); anything below it to a finite float.
inline constexpr double kFloatOverflow = 0x1.ffffffp127;

class Reader {
 public:
  // Throws the message as the caller's error type (raise_as<E>); must not return.
  using Raise = void (*)(const std::string& message);

  // `source` starts every message (a file name, "journal.jsonl:3"); "" for none.
  explicit Reader(std::string source, Wording wording = Wording::full,
                  Raise raise = &raise_as<Error>)
      : source_(std::move(source)), wording_(wording), raise_(raise) {}

  const std::string& source() const { return source_; }
  Wording wording() const { return wording_; }

  // Throws "<source>: <shown_path(path)>: expected <expected>, got <got>" through `raise`: no
  // "<path>: " for an empty path, no ", got ..." for an empty got; the whole made printable(),
  // one line whatever a file name or key holds.
  [[noreturn]] void fail(const std::string& path, const std::string& expected,
                         const std::string& got = {}) const;

  // What a JSON value is, for a message: null, true, "text" (json_quoted), 1.5, "an empty
  // array", "an array of 3", "an object".
  template <class J>
  static std::string describe(const J& v);
  // The "got" of a value of the wrong type: describe(v), or "" with Wording::brief.
  template <class J>
  std::string got(const J& v) const {
    return wording_ == Wording::full ? describe(v) : std::string();
  }

  // ---- Objects -------------------------------------------------------------------------------

  // `v` if it is an object; else fails with "an object".
  template <class J>
  const J& object(const J& v, const std::string& path) const {
    if (!v.is_object()) fail(path, "an object", got(v));
    return v;
  }
  // Fails at the first key of the object `obj` not in `allowed` ("one of the keys a, b, got
  // unknown key "c""): a misspelt optional field would otherwise silently take its default.
  template <class J>
  void check_keys(const J& obj, const std::string& path,
                  std::initializer_list<std::string_view> allowed) const;
  // The field `key` of `obj`, or null when absent (or `obj` is no object).
  template <class J>
  static const J* find(const J& obj, std::string_view key) {
    if (!obj.is_object()) return nullptr;
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }
  // The field `key` of `obj`. Absent: Wording::full fails at path.key with `what` it should
  // hold, "got nothing (the field is required)"; Wording::brief with `a field "key"` (also when
  // `obj` is no object).
  template <class J>
  const J& required(const J& obj, const std::string& path, std::string_view key,
                    const std::string& what = {}) const {
    if (const J* v = find(obj, key)) return *v;
    if (wording_ == Wording::brief)
      fail(path_key(path, key), "a field \"" + std::string(key) + "\"");
    fail(path_key(path, key), what, "nothing (the field is required)");
  }

  // ---- Scalars -------------------------------------------------------------------------------

  // true or false.
  template <class J>
  bool boolean(const J& v, const std::string& path) const {
    if (!v.is_boolean()) fail(path, "true or false", got(v));
    return v.template get<bool>();
  }
  // A string (`what` names it in the message).
  template <class J>
  const std::string& string(const J& v, const std::string& path,
                            const std::string& what = "a string") const {
    if (!v.is_string()) fail(path, what, got(v));
    return v.template get_ref<const typename J::string_t&>();
  }
  // An integer in [lo, hi], `what` in the message (for a value of another type too). Parsed,
  // a number >= 0 is unsigned and may be beyond int64_t: 2^64 - 1 is out of range, never -1.
  // A value out of range always says what came.
  template <class J>
  long long integer(const J& v, const std::string& path, long long lo, long long hi,
                    const std::string& what) const;
  // A count: an integer from 0 to 2^64 - 1 ("a count (an integer >= 0)").
  template <class J>
  uint64_t count(const J& v, const std::string& path) const {
    if (!v.is_number_unsigned()) fail(path, "a count (an integer >= 0)", got(v));
    return v.template get<uint64_t>();
  }
  // A JSON number in [lo, hi] (never NaN), `what` in the message.
  template <class J>
  double number(const J& v, const std::string& path, double lo, double hi,
                const std::string& what) const {
    if (!v.is_number() || !(v.template get<double>() >= lo && v.template get<double>() <= hi))
      fail(path, what, got(v));
    return v.template get<double>();
  }
  // A double, or a string "nan", "inf", "-inf": results.json writes a non-finite number so
  // (report/format.hpp, json_number), since JSON has none and null would read as "missing".
  template <class J>
  double number_or_nonfinite(const J& v, const std::string& path) const;
  // A number rounded to float32 once: a JSON number goes through double (as the parser reads
  // it) and is then rounded to the nearest float, ties to even (beyond FLT_MAX but below
  // kFloatOverflow to FLT_MAX; at or beyond it fails, "overflows float32"); a string holding a
  // C99 hex float or a decimal is read by strtof in the C locale, for exact bits (no leading
  // space, nothing after it; infinite or NaN fails).
  template <class J>
  float float32(const J& v, const std::string& path) const;
  // A JSON number float32() takes as it is, or nullopt (anything else, including a number it
  // would refuse or round from beyond FLT_MAX): the hot path of a large case, which must not
  // build a field path per number.
  template <class J>
  static std::optional<float> plain_float32(const J& v);
  // An array of exactly one of `counts` numbers, each float32(), appended to `out`. `path()`
  // makes the array's path, only for a message ("3 or 4 numbers, got 2"; elements: path[i]).
  template <class J, class PathFn>
  void float32s_into(const J& v, const PathFn& path, std::initializer_list<size_t> counts,
                     std::vector<float>& out) const;
  // One of enum E's names (core/names.hpp's table), exactly; `what` defaults to "one of a, b,
  // c". With Wording::brief a value that is no string fails as "a string" first.
  template <class E, class J>
  E name(const J& v, const std::string& path, const std::string& what = {}) const;

  // ---- Arrays --------------------------------------------------------------------------------

  // `v` if it is an array; else fails with `what`.
  template <class J>
  const J& array(const J& v, const std::string& path, const std::string& what = "an array") const {
    if (!v.is_array()) fail(path, what, got(v));
    return v;
  }
  // Calls each(element, path_index(path, i)) for every element of the array `v` (else fails
  // with `what`), in order.
  template <class J, class F>
  void elements(const J& v, const std::string& path, const std::string& what, F&& each) const {
    array(v, path, what);
    for (size_t i = 0; i < v.size(); ++i)
      each(v[i], path_index(path, i));
  }

 private:
  float float32_from_text(const std::string& s, const std::string& path) const;

  std::string source_;
  Wording wording_;
  Raise raise_;
};

// ---- Implementation ----------------------------------------------------------------------------

template <class J>
std::string Reader::describe(const J& v) {
  switch (v.type()) {
    case J::value_t::null:
      return "null";
    case J::value_t::boolean:
      return v.template get<bool>() ? "true" : "false";
    case J::value_t::string:
      return json_quoted(v.template get_ref<const typename J::string_t&>());
    case J::value_t::number_integer:
    case J::value_t::number_unsigned:
    case J::value_t::number_float:
      return v.dump();
    case J::value_t::array:
      return v.empty() ? "an empty array" : "an array of " + std::to_string(v.size());
    case J::value_t::object:
      return "an object";
    default:
      return "a " + std::string(v.type_name());
  }
}

template <class J>
void Reader::check_keys(const J& obj, const std::string& path,
                        std::initializer_list<std::string_view> allowed) const {
  for (const auto& [key, value] : obj.items()) {
    bool known = false;
    for (std::string_view a : allowed)
      known = known || a == key;
    if (known) continue;
    std::string keys;
    for (std::string_view a : allowed)
      (keys += keys.empty() ? "" : ", ") += a;
    fail(path_key(path, key), "one of the keys " + keys, "unknown key " + json_quoted(key));
  }
}

template <class J>
long long Reader::integer(const J& v, const std::string& path, long long lo, long long hi,
                          const std::string& what) const {
  // A number written with a fraction or an exponent is no integer, whatever its value: said so
  // where the value is whole, since "expected an integer in 0..2, got 2.0" reads as a
  // contradiction.
  // An integer literal beyond 64 bits reaches here as a double too (the parser cannot hold it
  // otherwise), so a whole value that large is not blamed on its spelling.
  if (v.is_number_float() && std::trunc(v.template get<double>()) == v.template get<double>())
    fail(path, what,
         describe(v) + (std::fabs(v.template get<double>()) >= 0x1p63
                            ? " (beyond 64-bit integers)"
                            : " (written with a decimal point or an exponent: not an integer)"));
  if (!v.is_number_integer()) fail(path, what, got(v));
  bool in_range;
  if (v.is_number_unsigned()) {
    const auto u = v.template get<uint64_t>();
    in_range = hi >= 0 && u <= uint64_t(hi) && (lo <= 0 || u >= uint64_t(lo));
  } else {
    const auto i = v.template get<int64_t>();
    in_range = i >= lo && i <= hi;
  }
  if (!in_range) fail(path, what, describe(v));
  return v.template get<long long>();
}

template <class J>
double Reader::number_or_nonfinite(const J& v, const std::string& path) const {
  if (v.is_number()) return v.template get<double>();
  if (v.is_string()) {
    const auto& t = v.template get_ref<const typename J::string_t&>();
    if (t == "nan") return std::nan("");
    if (t == "inf") return HUGE_VAL;
    if (t == "-inf") return -HUGE_VAL;
  }
  fail(path, "a number or \"nan\", \"inf\", \"-inf\"", got(v));
}

template <class J>
float Reader::float32(const J& v, const std::string& path) const {
  if (v.is_string()) return float32_from_text(v.template get_ref<const std::string&>(), path);
  if (!v.is_number()) fail(path, "a number", got(v));
  const double d = v.template get<double>();
  if (!std::isfinite(d)) fail(path, "a finite number", got(v));
  if (std::fabs(d) >= kFloatOverflow)
    fail(path, "a number within float32 range", describe(v) + " (overflows float32)");
  // static_cast of a double beyond FLT_MAX is undefined behaviour, hence the clamp.
  if (std::fabs(d) > double(std::numeric_limits<float>::max()))
    return std::signbit(d) ? -std::numeric_limits<float>::max() : std::numeric_limits<float>::max();
  return static_cast<float>(d);
}

template <class J>
std::optional<float> Reader::plain_float32(const J& v) {
  double d;
  if (v.is_number_float()) {
    d = v.template get_ref<const typename J::number_float_t&>();
  } else if (v.is_number_integer() && !v.is_number_unsigned()) {
    d = double(v.template get_ref<const typename J::number_integer_t&>());
  } else {
    return std::nullopt;
  }
  if (!(std::fabs(d) <= double(std::numeric_limits<float>::max()))) return std::nullopt;
  return static_cast<float>(d);
}

template <class J, class PathFn>
void Reader::float32s_into(const J& v, const PathFn& path, std::initializer_list<size_t> counts,
                           std::vector<float>& out) const {
  const auto what = [&] {
    std::string w;
    for (size_t n : counts)
      w += (w.empty() ? "" : " or ") + std::to_string(n);
    return w + (counts.size() == 1 && *counts.begin() == 1 ? " number" : " numbers");
  };
  if (!v.is_array()) fail(path(), what(), got(v));
  bool count_ok = false;
  for (size_t n : counts)
    count_ok = count_ok || n == v.size();
  if (!count_ok) fail(path(), what(), std::to_string(v.size()));
  for (size_t i = 0; i < v.size(); ++i) {
    const auto f = plain_float32(v[i]);
    out.push_back(f ? *f : float32(v[i], path_index(path(), i)));
  }
}

template <class E, class J>
E Reader::name(const J& v, const std::string& path, const std::string& what) const {
  if (v.is_string())
    if (const auto value = from_name<E>(v.template get_ref<const std::string&>())) return *value;
  if (wording_ == Wording::brief && !v.is_string()) fail(path, "a string");
  if (!what.empty()) fail(path, what, got(v));
  std::string names;
  for (const std::string& n : names_of<E>())
    names += (names.empty() ? "" : ", ") + n;
  fail(path, "one of " + names, got(v));
}

}  // namespace glrc::typed_json
