// typed_json's reader on plain nlohmann::json: each accessor's value, and its message for each
// way a field can be wrong, in both wordings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/case.hpp"
#include "typed_json/reader.hpp"

namespace glrc::typed_json {
namespace {

using nlohmann::json;

struct MyError : Error {
  using Error::Error;
};

// The message `f` throws as MyError ("" when it throws nothing).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const MyError& e) {
    return e.what();
  }
  return "";
}

const Reader full("f.json", Wording::full, &raise_as<MyError>);
const Reader brief("r.json", Wording::brief, &raise_as<MyError>);

TEST(Reader, FailSaysSourcePathExpectedAndGot) {
  EXPECT_EQ(error_of([] { full.fail("a.b", "x", "y"); }), "f.json: a.b: expected x, got y");
  EXPECT_EQ(error_of([] { full.fail("", "x"); }), "f.json: expected x");
  EXPECT_EQ(error_of([] { Reader("", Wording::full, &raise_as<MyError>).fail("p", "x"); }),
            "p: expected x");
  // One line, whatever a key holds.
  EXPECT_EQ(error_of([] { full.fail("a\nb", "x", "\x01"); }),
            "f.json: a\\nb: expected x, got \\u0001");
}

TEST(Reader, TheDefaultErrorIsTypedJsonError) {
  const Reader r("s");
  EXPECT_THROW(r.fail("p", "x"), Error);
  EXPECT_THROW(r.fail("p", "x"), std::runtime_error);
}

TEST(Reader, UnknownKeyNamesTheAllowedOnes) {
  const json j = json::parse(R"({"a": 1, "bee": 2})");
  EXPECT_EQ(error_of([&] {
              full.check_keys(j, "top", {"a", "b"});
            }),
            "f.json: top.bee: expected one of the keys a, b, got unknown key \"bee\"");
  full.check_keys(j, "top", {"a", "bee"});
}

TEST(Reader, RequiredFieldsInBothWordings) {
  const json j = json::parse(R"({"a": 1})");
  EXPECT_EQ(full.required(j, "", "a", "n").get<int>(), 1);
  EXPECT_EQ(error_of([&] { full.required(j, "o", "b", "a number"); }),
            "f.json: o.b: expected a number, got nothing (the field is required)");
  EXPECT_EQ(error_of([&] { brief.required(j, "run", "b"); }),
            "r.json: run.b: expected a field \"b\"");
  EXPECT_EQ(error_of([&] { brief.required(json(3), "run", "b"); }),
            "r.json: run.b: expected a field \"b\"");
  EXPECT_EQ(Reader::find(j, "b"), nullptr);
  EXPECT_EQ(Reader::find(json(3), "a"), nullptr);
}

TEST(Reader, WrongTypeSaysWhatCameInFullWordingOnly) {
  EXPECT_EQ(error_of([] { full.boolean(json("yes"), "t.flag"); }),
            "f.json: t.flag: expected true or false, got \"yes\"");
  EXPECT_EQ(error_of([] { brief.boolean(json("yes"), "t.flag"); }),
            "r.json: t.flag: expected true or false");
  EXPECT_EQ(error_of([] {
              full.string(json::array({1, 2}), "s");
            }),
            "f.json: s: expected a string, got an array of 2");
  EXPECT_EQ(error_of([] { full.object(json::array(), "o"); }),
            "f.json: o: expected an object, got an empty array");
  EXPECT_EQ(error_of([] { full.count(json(-1), "n"); }),
            "f.json: n: expected a count (an integer >= 0), got -1");
  EXPECT_EQ(full.count(json::parse("18446744073709551615"), "n"), UINT64_MAX);
}

TEST(Reader, IntegersInRanges) {
  EXPECT_EQ(full.integer(json(4096), "w", 1, 4096, "an integer in 1..4096"), 4096);
  EXPECT_EQ(error_of([] { full.integer(json(4097), "w", 1, 4096, "an integer in 1..4096"); }),
            "f.json: w: expected an integer in 1..4096, got 4097");
  EXPECT_EQ(error_of([] { full.integer(json(1.5), "w", 1, 4096, "an integer in 1..4096"); }),
            "f.json: w: expected an integer in 1..4096, got 1.5");
  // A whole value written as a float is no integer either, and the message says why (the
  // twelfth hostile campaign of issue 45: "expected an integer in 1..4096, got 64.0").
  EXPECT_EQ(error_of([] { full.integer(json(64.0), "w", 1, 4096, "an integer in 1..4096"); }),
            "f.json: w: expected an integer in 1..4096, got 64.0 (written with a decimal point or "
            "an exponent: not an integer)");
  // Out of range says what came in the brief wording too.
  EXPECT_EQ(error_of([] { brief.integer(json(0), "run.fraction", 1, 9, "an integer >= 1"); }),
            "r.json: run.fraction: expected an integer >= 1, got 0");
  EXPECT_EQ(error_of([] { brief.integer(json(true), "run.fraction", 1, 9, "an integer >= 1"); }),
            "r.json: run.fraction: expected an integer >= 1");
  // 2^64 - 1 parses unsigned: out of range, never -1; 2^32 + 1 is never 1.
  const json huge = json::parse("18446744073709551615");
  EXPECT_EQ(error_of([&] { full.integer(huge, "i", -5, 5, "w"); }),
            "f.json: i: expected w, got 18446744073709551615");
  EXPECT_EQ(error_of([] { full.integer(json::parse("4294967297"), "i", 0, INT32_MAX, "w"); }),
            "f.json: i: expected w, got 4294967297");
  EXPECT_EQ(full.integer(json(-5), "i", -5, 5, "w"), -5);
}

TEST(Reader, NumbersInRanges) {
  EXPECT_EQ(full.number(json(0.5), "t", 0, 1, "a number in [0, 1]"), 0.5);
  EXPECT_EQ(error_of([] { full.number(json(-0.5), "t", 0, 1, "a number in [0, 1]"); }),
            "f.json: t: expected a number in [0, 1], got -0.5");
}

TEST(Reader, NanAndInfinitiesAsStrings) {
  EXPECT_TRUE(std::isnan(brief.number_or_nonfinite(json("nan"), "x")));
  EXPECT_EQ(brief.number_or_nonfinite(json("inf"), "x"), HUGE_VAL);
  EXPECT_EQ(brief.number_or_nonfinite(json("-inf"), "x"), -HUGE_VAL);
  EXPECT_EQ(brief.number_or_nonfinite(json(0.25), "x"), 0.25);
  EXPECT_EQ(error_of([] { brief.number_or_nonfinite(json("NaN"), "c.max_ulps"); }),
            "r.json: c.max_ulps: expected a number or \"nan\", \"inf\", \"-inf\"");
  EXPECT_EQ(error_of([] { full.number_or_nonfinite(json(nullptr), "c.max_ulps"); }),
            "f.json: c.max_ulps: expected a number or \"nan\", \"inf\", \"-inf\", got null");
}

TEST(Reader, Float32RoundsOnceAndReadsStringsExactly) {
  // 0.1 as a double, rounded to the nearest float once.
  EXPECT_EQ(full.float32(json(0.1), "v"), 0.1f);
  // Half-way between 1 and the next float: ties to even (1), a hair above rounds up.
  EXPECT_EQ(full.float32(json(1.0 + 0x1p-24), "v"), 1.0f);
  EXPECT_EQ(full.float32(json(1.0 + 0x1p-24 + 0x1p-40), "v"), 1.0f + 0x1p-23f);
  EXPECT_EQ(full.float32(json("0x1.8p-3"), "v"), 0.1875f);
  EXPECT_EQ(full.float32(json("0.1"), "v"), 0.1f);
  // Beyond FLT_MAX but below the rounding threshold: FLT_MAX; at it, an error.
  EXPECT_EQ(full.float32(json(0x1.fffffefp127), "v"), 0x1.fffffep127f);
  EXPECT_EQ(error_of([] { full.float32(json(1e39), "v[2]"); }),
            "f.json: v[2]: expected a number within float32 range, got 1e+39 (overflows float32)");
  EXPECT_EQ(error_of([] { full.float32(json(" 1"), "v"); }),
            "f.json: v: expected a number or a string holding a C99 hex float or decimal, got "
            "\" 1\"");
  EXPECT_EQ(error_of([] { full.float32(json("1e39"), "v"); }),
            "f.json: v: expected a finite float32 value, got \"1e39\"");
  EXPECT_EQ(error_of([] { full.float32(json(true), "v"); }),
            "f.json: v: expected a number, got true");
  EXPECT_EQ(Reader::plain_float32(json(0.1)), 0.1f);
  EXPECT_EQ(Reader::plain_float32(json("0.1")), std::nullopt);
  EXPECT_EQ(Reader::plain_float32(json(1e39)), std::nullopt);
}

TEST(Reader, Float32ArraysNameTheirElements) {
  std::vector<float> out;
  full.float32s_into(
      json::parse("[1, 2, 3]"), [] { return std::string("p"); }, {3, 4}, out);
  EXPECT_EQ(out, (std::vector<float>{1, 2, 3}));
  EXPECT_EQ(error_of([&] {
              full.float32s_into(
                  json::parse("[1, 2]"), [] { return std::string("v[0].clip"); }, {3, 4}, out);
            }),
            "f.json: v[0].clip: expected 3 or 4 numbers, got 2");
  EXPECT_EQ(error_of([&] {
              full.float32s_into(
                  json::parse("[1, 2, null, 4]"), [] { return std::string("v[0].clip"); }, {4},
                  out);
            }),
            "f.json: v[0].clip[2]: expected a number, got null");
}

TEST(Reader, EnumNamesComeFromTheNameTables) {
  EXPECT_EQ(full.name<CullFace>(json("front"), "state.cull"), CullFace::front);
  EXPECT_EQ(error_of([] { full.name<FrontFace>(json("CCW"), "state.front_face"); }),
            "f.json: state.front_face: expected one of ccw, cw, got \"CCW\"");
  EXPECT_EQ(error_of([] { brief.name<ToleranceMode>(json("x"), "t.mode", "spec, ulps or exact"); }),
            "r.json: t.mode: expected spec, ulps or exact");
  EXPECT_EQ(error_of([] { brief.name<ToleranceMode>(json(1), "t.mode", "spec, ulps or exact"); }),
            "r.json: t.mode: expected a string");
}

TEST(Reader, ArrayElementsGetTheirPaths) {
  std::vector<std::string> paths;
  full.elements(json::parse("[1, [2], 3]"), "cases", "an array",
                [&](const json& /*e*/, const std::string& p) { paths.push_back(p); });
  EXPECT_EQ(paths, (std::vector<std::string>{"cases[0]", "cases[1]", "cases[2]"}));
  EXPECT_EQ(error_of([] {
              full.elements(json::parse(R"([1, "x"])"), "run.gl_warnings", "an array of strings",
                            [](const json& e, const std::string& p) { full.string(e, p); });
            }),
            "f.json: run.gl_warnings[0]: expected a string, got 1");
  EXPECT_EQ(error_of([] {
              brief.elements(json(1), "cases", "an array", [](const json&, const std::string&) {});
            }),
            "r.json: cases: expected an array");
}

TEST(Reader, LongPathsKeepTheirStartAndEnd) {
  const std::string key(500, 'k');
  const std::string msg = error_of([&] { full.fail("a." + key + ".z", "x"); });
  EXPECT_EQ(msg,
            "f.json: a." + std::string(98, 'k') + "..." + std::string(98, 'k') + ".z: expected x");
}

}  // namespace
}  // namespace glrc::typed_json
