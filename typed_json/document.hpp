// A JSON text parsed into a document for a typed_json::Reader, with one-line errors: bytes no
// JSON text may hold, syntax errors at their line and column, numbers beyond double range at
// their field, and keys written twice in one object (nlohmann-json would keep the last one
// without a word). Linear in the text: a 50 MB case parses in about a second.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "typed_json/reader.hpp"

namespace glrc::typed_json {

// A function of a field's path giving what that field holds ("an integer in 1..4096"), for a
// number beyond double range there, which the parser meets before any reader sees the field.
using NumberExpectation = std::function<std::string(const std::string& path)>;

// Parses the JSON text `text` into `root` (any nlohmann::basic_json, e.g. ArenaJson inside an
// ArenaScope). Fails through `r` (source: r.source()):
//   - "line L, column C: expected a JSON text without NUL bytes, got a NUL byte at offset N"
//     (nlohmann-json takes a NUL for the end of the input), and likewise "expected UTF-8 text,
//     got the byte 0xFF, which is not UTF-8, at offset N";
//   - "line L, column C: expected valid JSON, got <nlohmann-json's words>" with the text it
//     quotes cut to 80 characters;
//   - "<path>: expected <expected_number(path)>, got 1e400 (beyond the range of a double)"
//     (default: "a number within the range of a double");
//   - "<path>: expected each key once in its object, got it twice".
template <class J>
void parse(const Reader& r, const std::string& text, J& root,
           const NumberExpectation& expected_number = nullptr);

// ---- Implementation ----------------------------------------------------------------------------

// What the parser stopped at.
struct ParseError {
  size_t position;         // bytes read
  std::string last_token;  // as the message quotes it
  int id;                  // nlohmann-json's exception id: 101 syntax, 406 number overflow
  std::string message;
  std::string path;  // of the value being read
};

// Fails at the first NUL byte or byte that is not UTF-8 of `text`, if any (see parse()).
void check_bytes(const Reader& r, std::string_view text);
// Fails with the parse error `e` as parse() words it.
[[noreturn]] void fail_parse(const Reader& r, const ParseError& e,
                             const NumberExpectation& expected_number);

// Builds the document as nlohmann-json's own SAX DOM parser does, and stops at a key written
// twice in one object: an object is a std::map, so the check is one lookup as the key is read.
// (nlohmann's parser callback, used before, rescanned the parent array at the end of every
// object, which made loading quadratic in the number of objects.) The open containers give the
// path of the value being read, for errors found while parsing.
template <class J>
class DomBuilder final : public J::json_sax_t {
 public:
  explicit DomBuilder(J& root) : root_(root) {}

  bool null() override { return add(nullptr); }
  bool boolean(bool b) override { return add(b); }
  bool number_integer(typename J::number_integer_t v) override { return add(v); }
  bool number_unsigned(typename J::number_unsigned_t v) override { return add(v); }
  bool number_float(typename J::number_float_t v, const std::string& /*text*/) override {
    return add(v);
  }
  bool string(std::string& s) override { return add(std::move(s)); }
  bool binary(typename J::binary_t& b) override { return add(std::move(b)); }
  bool start_object(size_t /*size*/) override { return open(J::object()); }
  bool start_array(size_t /*size*/) override {
    // Most arrays of a case hold 3 or 4 numbers: one allocation instead of three.
    J array = J::array();
    array.template get_ref<typename J::array_t&>().reserve(4);
    return open(std::move(array));
  }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(std::string& k) override {
    Level& top = stack_.back();
    auto [it, inserted] =
        top.node->template get_ref<typename J::object_t&>().emplace(std::move(k), nullptr);
    if (!inserted) {
      top.slot = nullptr;  // the path of the object, not of its previous key
      duplicate_ = path_key(path(), it->first);
      return false;
    }
    top.key = &it->first;
    top.slot = &it->second;
    return true;
  }
  bool parse_error(size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& ex) override {
    error_ = ParseError{position, last_token, ex.id, ex.what(), path()};
    return false;
  }

  const std::optional<ParseError>& error() const { return error_; }
  const std::optional<std::string>& duplicate() const { return duplicate_; }

 private:
  struct Level {
    J* node;
    const std::string* key = nullptr;  // objects: the key being read (a node of the map)
    J* slot = nullptr;                 // objects: where its value goes
  };

  J* place(J&& v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Level& top = stack_.back();
    if (top.node->is_array()) {
      // Only the last element is ever open, so a reallocation moves no pointer held here.
      top.node->push_back(std::move(v));
      return &top.node->back();
    }
    *top.slot = std::move(v);
    return top.slot;
  }
  bool add(J&& v) {
    place(std::move(v));
    return true;
  }
  bool open(J&& container) {
    stack_.push_back({place(std::move(container))});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }
  // An open array's element being read is its last one if that is itself open, else the next.
  std::string path() const {
    std::string p;
    for (size_t k = 0; k < stack_.size(); ++k) {
      const Level& l = stack_[k];
      // Appended in place: a path 100,000 levels deep must not be copied at every level.
      if (l.node->is_array()) {
        const size_t n = l.node->size();
        // Three appends, not "[" + ...: GCC 12 at -O3 reports a false -Wrestrict in operator+.
        p += '[';
        p += std::to_string(k + 1 < stack_.size() ? n - 1 : n);
        p += ']';
      } else if (l.slot) {
        if (!p.empty()) p += '.';
        p += *l.key;
      } else {
        break;
      }
    }
    return p;
  }

  J& root_;
  std::vector<Level> stack_;
  std::optional<ParseError> error_;
  std::optional<std::string> duplicate_;
};

template <class J>
void parse(const Reader& r, const std::string& text, J& root,
           const NumberExpectation& expected_number) {
  check_bytes(r, text);
  DomBuilder<J> builder(root);
  J::sax_parse(text, &builder, J::input_format_t::json, /*strict=*/true);
  if (const auto& e = builder.error()) fail_parse(r, *e, expected_number);
  if (builder.duplicate()) r.fail(*builder.duplicate(), "each key once in its object", "it twice");
}

}  // namespace glrc::typed_json
