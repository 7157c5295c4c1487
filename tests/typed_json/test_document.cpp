// typed_json's document parser: duplicate keys, bytes no JSON text holds, syntax errors and
// numbers beyond double range, each one line with its place; and documents of the arena type.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "typed_json/arena.hpp"
#include "typed_json/document.hpp"

namespace glrc::typed_json {
namespace {

using nlohmann::json;

// The message parsing `text` throws ("" when it parses).
std::string error_of(const std::string& text, const NumberExpectation& expected = nullptr) {
  try {
    json root;
    parse(Reader("d.json"), text, root, expected);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Document, ParsesWhatNlohmannParses) {
  json root;
  parse(Reader("d.json"), R"({"a": [1, 2.5, "x", null, true], "b": {"c": -3}})", root);
  EXPECT_EQ(root, json::parse(R"({"a": [1, 2.5, "x", null, true], "b": {"c": -3}})"));
}

TEST(Document, ADuplicateKeyIsNamedWithItsPath) {
  EXPECT_EQ(error_of(R"({"a": 1, "a": 2})"),
            "d.json: a: expected each key once in its object, got it twice");
  EXPECT_EQ(error_of(R"({"v": [{"x": 1}, {"y": [0, {"k": 1, "k": 2}]}]})"),
            "d.json: v[1].y[1].k: expected each key once in its object, got it twice");
}

TEST(Document, ANulByteIsRefusedWithItsPlace) {
  EXPECT_EQ(error_of(std::string("{\"a\":\n 1\0}", 10)),
            "d.json: line 2, column 3: expected a JSON text without NUL bytes, got a NUL byte at "
            "offset 8");
}

TEST(Document, AByteThatIsNotUtf8IsRefusedWithItsPlace) {
  EXPECT_EQ(error_of("{\"a\": \"\xFF\"}"),
            "d.json: line 1, column 8: expected UTF-8 text, got the byte 0xFF, which is not "
            "UTF-8, at offset 7");
  // A long run of ASCII before it (the eight-bytes-at-a-time path).
  EXPECT_EQ(error_of("{\"a\": \"" + std::string(100, 'x') + "\xC0\x80\"}"),
            "d.json: line 1, column 108: expected UTF-8 text, got the byte 0xC0, which is not "
            "UTF-8, at offset 107");
}

TEST(Document, SyntaxErrorsSayLineAndColumn) {
  EXPECT_EQ(error_of("{\"a\": 1,\n}"),
            "d.json: line 2, column 1: expected valid JSON, got syntax error while parsing "
            "object key - unexpected '}'; expected string literal");
  // The text the parser quotes is cut to 80 characters.
  const std::string msg = error_of("[\"" + std::string(1000, 'x'));
  EXPECT_LT(msg.size(), 250u) << msg;
  EXPECT_NE(msg.find("expected valid JSON, got "), std::string::npos) << msg;
}

TEST(Document, ANumberBeyondDoubleRangeNamesItsField) {
  EXPECT_EQ(error_of(R"({"a": [1, 1e400]})"),
            "d.json: a[1]: expected a number within the range of a double, got 1e400 (beyond the "
            "range of a double)");
  EXPECT_EQ(error_of(R"({"n": 1e400})", [](const std::string& p) { return "an integer at " + p; }),
            "d.json: n: expected an integer at n, got 1e400 (beyond the range of a double)");
}

TEST(Document, ArenaDocumentsParseAndReadLikeAnyOther) {
  const ArenaScope arena;
  ArenaJson root;
  const Reader r("a.json");
  parse(r, R"({"v": [0.1, "0x1p-3", 7]})", root);
  std::vector<float> out;
  r.float32s_into(
      r.required(root, "", "v", "3 numbers"), [] { return std::string("v"); }, {3}, out);
  EXPECT_EQ(out, (std::vector<float>{0.1f, 0.125f, 7.0f}));
  EXPECT_EQ(Reader::describe(root), "an object");
}

}  // namespace
}  // namespace glrc::typed_json
