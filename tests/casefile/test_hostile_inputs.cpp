// Inputs from issue 11: large cases load in linear time, and every malformed byte, overflowing
// number or hostile key gets one line naming the file, the field and what was expected.
#include <sys/stat.h>

#include <string>

#include "tests/casefile/test_helpers.hpp"

namespace glrc::casefile::test {
namespace {

// `n` vertices (n a multiple of 3) with one vec4 varying, each on one line of about 110 bytes;
// `extra` goes inside the object of vertex `extra_at`.
std::string many_vertices(size_t n, size_t extra_at = size_t(-1), const std::string& extra = "") {
  std::string s =
      R"({"description": "many", "varyings": [{"name": "c", "size": 4}], "vertices": [)";
  s.reserve(n * 112);
  for (size_t i = 0; i < n; ++i) {
    const std::string k = std::to_string(i % 1000);
    s += i ? ",\n" : "\n";
    s += R"({"clip": [0.)" + k + ", -0." + k + R"(, 0.5, 1], "c": [)" + k + ", 1, 2, 3]" +
         (i == extra_at ? ", " + extra : "") + "}";
  }
  return s + "]}";
}

// Loading was quadratic in the vertex objects (the duplicate-key check rescanned the parent
// array at the end of every object): 300,000 vertices took minutes. Linear now; the assertions
// are on what is loaded, the time is the test's own (about a second).
TEST_F(CaseFileTest, ThreeHundredThousandVerticesLoad) {
  const Case c = load_text(many_vertices(300000));
  ASSERT_EQ(c.vertices.size(), 300000u);
  EXPECT_EQ(c.triangles.size(), 100000u);
  EXPECT_EQ(c.vertices[299999].clip[0], 0.999f);
  EXPECT_EQ(c.vertices[299999].clip[1], -0.999f);
  EXPECT_EQ(c.vertices[299999].values, (std::vector<float>{999, 1, 2, 3}));
}

TEST_F(CaseFileTest, DuplicateKeyInTheLastOfManyVerticesIsNamed) {
  const std::string file = (dir_ / "case.json").string();
  EXPECT_EQ(error_of(many_vertices(300000, 299999, R"("c": [1, 2, 3, 4])")),
            file + ": vertices[299999].c: expected each key once in its object, got it twice");
}

TEST_F(CaseFileTest, DuplicateKeysAnywhereAreNamedWithTheirPath) {
  const std::string file = (dir_ / "case.json").string();
  EXPECT_EQ(error_of(R"({"description": "d", "description": "e"})"),
            file + ": description: expected each key once in its object, got it twice");
  EXPECT_EQ(error_of(R"({"description": "d", "vertices": [{"clip": [0, 0, 0, 1]},
                       {"clip": [1, 0, 0, 1]}, {"clip": [0, 1, 0, 1]}],
                       "transform": {"model": [{"rotate": {"degrees": 1, "degrees": 2}}]}})"),
            file +
                ": transform.model[0].rotate.degrees: expected each key once in its object, got "
                "it twice");
}

// A number beyond double range in an integer field says what the field expects, not "float32".
TEST_F(CaseFileTest, HugeNumberInAnIntegerFieldExpectsAnInteger) {
  const std::string file = (dir_ / "case.json").string();
  const std::string tri =
      R"("vertices": [{"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0, 1]}, {"clip": [0, 1, 0, 1]}])";
  EXPECT_EQ(error_of(R"({"description": "d", "framebuffer": {"width": 1e400, "height": 8}, )" +
                     tri + "}"),
            file +
                ": framebuffer.width: expected an integer in 1..4096, got 1e400 (beyond the "
                "range of a double)");
  EXPECT_EQ(
      error_of(
          R"({"description": "d", "viewport": {"x": -1e999, "y": 0, "width": 8, "height": 8}, )" +
          tri + "}"),
      file +
          ": viewport.x: expected a number in -16384..16383, got -1e999 (beyond the range of a "
          "double)");
  EXPECT_EQ(error_of(R"({"description": "d", )" + tri + R"(, "triangles": [[0, 1e400, 2]]})"),
            file +
                ": triangles[0][1]: expected a vertex index (an integer), got 1e400 (beyond the "
                "range of a double)");
  EXPECT_EQ(
      error_of(R"({"description": "d", "varyings": [{"name": "v", "size": 1e400}], )" + tri + "}"),
      file +
          ": varyings[0].size: expected an integer in 1..4, got 1e400 (beyond the range "
          "of a double)");
  // The twelfth hostile campaign (issue 45): an integral value written as a float was quoted
  // inside the range the message asked for ("expected an index in 0..2, got 2.0"); 1e-400
  // (read as 0.0) too. Such a number is no integer as written, and the message says so.
  for (const char* index : {"2.0", "2e0", "1e-400"})
    EXPECT_EQ(
        error_of(R"({"description": "d", )" + tri + R"(, "triangles": [[0, 1, )" + index + "]]}"),
        file + ": triangles[0][2]: expected an integer index in 0..2, got " +
            (std::string(index) == "1e-400" ? "0.0" : "2.0") +
            " (written with a decimal point or an exponent: not an integer)");
  EXPECT_EQ(
      error_of(R"({"description": "d", "framebuffer": {"width": 64.0, "height": 8}, )" + tri + "}"),
      file +
          ": framebuffer.width: expected an integer in 1..4096, got 64.0 (written with a "
          "decimal point or an exponent: not an integer)");
  // A float field keeps the float32 expectation.
  EXPECT_EQ(error_of(R"({"description": "d", "vertices": [{"clip": [1e400, -1, 0, 1]}]})"),
            file +
                ": vertices[0].clip[0]: expected a number within float32 range, got 1e400 "
                "(beyond the range of a double)");
}

// nlohmann-json takes a NUL for the end of input: the message said "unexpected end of input",
// or a NUL after the document hid what followed it.
TEST_F(CaseFileTest, NulByteIsRejectedAsSuch) {
  const std::string file = (dir_ / "case.json").string();
  const std::string nul(1, '\0');
  EXPECT_EQ(error_of("{\"description\": \"d" + nul + "\"}"),
            file +
                ": line 1, column 19: expected a JSON text without NUL bytes, got a NUL byte at "
                "offset 18");
  EXPECT_EQ(error_of("{}\n" + nul + "garbage"),
            file +
                ": line 2, column 1: expected a JSON text without NUL bytes, got a NUL byte at "
                "offset 3");
}

TEST_F(CaseFileTest, NonUtf8ByteIsReportedWithItsOffset) {
  const std::string file = (dir_ / "case.json").string();
  EXPECT_EQ(error_of("{\"description\": \"caf\xE9\"}"),
            file +
                ": line 1, column 21: expected UTF-8 text, got the byte 0xE9, which is not "
                "UTF-8, at offset 20");
  // Overlong forms and surrogates are not UTF-8 either.
  EXPECT_NE(error_of("{\"description\": \"\xC0\xAF\"}").find("the byte 0xC0"), std::string::npos);
  EXPECT_NE(error_of("{\"description\": \"\xED\xA0\x80\"}").find("the byte 0xED"),
            std::string::npos);
  // Valid multi-byte UTF-8 passes the check (and fails later for what it is).
  EXPECT_EQ(error_of("{\"description\": \"caf\xC3\xA9 \xF0\x9F\x98\x80\"}"),
            file +
                ": vertices: expected an array of vertices, got nothing (the field is "
                "required)");
}

// A key holding \u0000 cut the message at the NUL (what() is a C string).
TEST_F(CaseFileTest, ControlCharactersInKeysAndValuesAreEscaped) {
  const std::string file = (dir_ / "case.json").string();
  const std::string msg = error_of(R"({"description": "d", "a\u0000b\u001fc": 1})");
  EXPECT_EQ(
      msg,
      file +
          R"(: a\u0000b\u001Fc: expected one of the keys description, framebuffer, )"
          R"(viewport, scissor, depth_range, state, varyings, enabled_clip_distances, )"
          R"(transform, vertices, )"
          R"(triangles, )"
          R"(draws, tolerance, work_arounds, written_by, polygon_offset, got unknown key "a\u0000b\u001Fc")");
  EXPECT_EQ(error_of(R"({"description": "two\nlines\u0007"})"),
            file + R"(: description: expected a non-empty one-line string without control )"
                   R"(characters, got "two\nlines\u0007")");
  // A description is printed by list, diff and run: an escape sequence or a NUL in it was
  // accepted and reached the terminal raw.
  EXPECT_EQ(error_of(R"({"description": "\u001b[2J\u001b[31mcleared"})"),
            file + R"(: description: expected a non-empty one-line string without control )"
                   R"(characters, got "\u001B[2J\u001B[31mcleared")");
  EXPECT_EQ(error_of(R"({"description": "a\u0000b"})"),
            file + R"(: description: expected a non-empty one-line string without control )"
                   R"(characters, got "a\u0000b")");
  EXPECT_EQ(error_of(R"({"description": "tab\there"})"),
            file + R"(: description: expected a non-empty one-line string without control )"
                   R"(characters, got "tab\there")");
  // A file name with a newline stays one line too.
  EXPECT_EQ(error_of("[]", "new\nline.json"),
            (dir_ / "new").string() +
                R"(\nline.json: expected a JSON object at the top level, got an empty array)");
}

// Found by fuzz_casefile (30 minutes): a key of 150 DEL bytes made a message of over 1,000
// characters, since the key was cut to 200 bytes and only then escaped, six characters a byte.
// Keys and values are now cut as shown.
TEST_F(CaseFileTest, KeysOfControlCharactersAreCutAsShown) {
  const std::string file = (dir_ / "case.json").string();
  const std::string del(150, '\x7f');
  const std::string msg = error_of("{\"$des1, 0, 1]0!!!varyiyings!!,80!!!var" + del +
                                   "yiyings89:8888~ie ns\": [[0, 1, 3]]}\n");
  EXPECT_LT(msg.size(), file.size() + 600) << msg;  // the list of allowed keys included
  std::string shown_key = "$des1, 0, 1]0!!!varyiyings!!,80!!!var";
  while (shown_key.size() + 6 <= 100)
    shown_key += "\\u007F";
  EXPECT_EQ(msg.rfind(file + ": " + shown_key + "...", 0), 0u) << msg;
  EXPECT_NE(msg.find("got unknown key \"$des1, 0, 1]0!!!varyiyings!!,80!!!var\\u007F"),
            std::string::npos)
      << msg;
  EXPECT_EQ(msg.find('\x7f'), std::string::npos);
}

// Parse errors quoted the text read so far, unbounded (a 52 MB line in one message).
TEST_F(CaseFileTest, ParseErrorsQuoteAtMostEightyCharacters) {
  const std::string msg = error_of("{\"description\": \"" + std::string(1000000, 'x'));
  const std::string file = (dir_ / "case.json").string();
  EXPECT_EQ(msg, file +
                     ": line 1, column 1000018: expected valid JSON, got syntax error while "
                     "parsing value - invalid string: missing closing quote; last read: '\"" +
                     std::string(79, 'x') + "...'");
  // A raw control character in a string: nlohmann-json quotes it as <U+0009>.
  const std::string tab = error_of("{\"description\": \"a\tb\"}");
  EXPECT_NE(tab.find("control character U+0009 (HT) must be escaped"), std::string::npos) << tab;
  EXPECT_EQ(tab.find('\t'), std::string::npos) << tab;
}

// Opening a FIFO waits for a writer: load refuses what is not a regular file.
TEST_F(CaseFileTest, LoadRefusesAFifoAndADirectory) {
  const auto fifo = dir_ / "pipe.json";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  try {
    load(fifo);
    FAIL() << "a FIFO loaded";
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()), fifo.string() + ": expected a regular case file, got a FIFO");
  }
  try {
    load(dir_);
    FAIL() << "a directory loaded";
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              dir_.string() + ": expected a regular case file, got a directory");
  }
}

// A huge key or a deep path makes no huge message: the path keeps its start and its end.
TEST_F(CaseFileTest, LongKeysAndDeepPathsAreCutInMessages) {
  const std::string file = (dir_ / "case.json").string();
  const std::string key(10000, 'k');
  const std::string msg = error_of(R"({"description": "d", ")" + key + R"(": 1})");
  EXPECT_EQ(msg, file + ": " + std::string(100, 'k') + "..." + std::string(100, 'k') +
                     ": expected one of the keys description, framebuffer, viewport, scissor, "
                     "depth_range, state, varyings, enabled_clip_distances, transform, vertices, "
                     "triangles, draws, tolerance, "
                     "work_arounds, written_by, polygon_offset, got unknown key \"" +
                     std::string(60, 'k') + "...\"");
  // 1e400 inside 100,000 nested arrays: the path is vertices[0][0]...[0].
  const std::string deep =
      error_of(R"({"description": "d", "vertices": )" + std::string(100000, '[') + "1e400");
  std::string full = "vertices";
  for (int i = 0; i < 100000; ++i)
    full += "[0]";
  EXPECT_EQ(deep, file + ": " + full.substr(0, 100) + "..." + full.substr(full.size() - 100) +
                      ": expected a number within float32 range, got 1e400 (beyond the range "
                      "of a double)");
}

// Deep nesting is parsed without recursion and refused as the wrong shape.
TEST_F(CaseFileTest, DeepNestingIsOneLine) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_EQ(error_of(R"({"description": "d", "vertices": )" + deep + "}"),
            (dir_ / "case.json").string() + ": vertices[0]: expected an object, got an array of 1");
}

}  // namespace
}  // namespace glrc::casefile::test
