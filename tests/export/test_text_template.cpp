// export/text_template.hpp: holes filled in place and as whole lines, //@if blocks kept or
// dropped (negated, nested, with //@else), the file's own comments dropped; and every mistake
// in a template or its values named instead of written out.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "export/text_template.hpp"

namespace glrc::reproducer {
namespace {

TEST(TextTemplate, HolesAreFilledInPlaceAndAsWholeLines) {
  const std::string text = "//@ a comment of the file\nint x = @X@;\n@LINES@\nend @X@@Y@\n";
  EXPECT_EQ(fill_template(text, {{"X", "4"}, {"Y", "!"}, {"LINES", "a\nb\n"}}, {}),
            "int x = 4;\na\nb\nend 4!\n");
  // A whole-line hole whose value is empty leaves no line.
  EXPECT_EQ(fill_template(text, {{"X", "4"}, {"Y", ""}, {"LINES", ""}}, {}), "int x = 4;\nend 4\n");
}

TEST(TextTemplate, BlocksAreKeptWhereTheirFlagSays) {
  const std::string text =
      "a\n//@if f\nf\n//@if !g\nf not g\n//@else\nf and g\n//@end\n//@else\nnot f\n//@end\nz\n";
  EXPECT_EQ(fill_template(text, {}, {{"f", true}, {"g", false}}), "a\nf\nf not g\nz\n");
  EXPECT_EQ(fill_template(text, {}, {{"f", true}, {"g", true}}), "a\nf\nf and g\nz\n");
  // Inside a dropped block, neither branch of an inner one is kept.
  EXPECT_EQ(fill_template(text, {}, {{"f", false}, {"g", false}}), "a\nnot f\nz\n");
  EXPECT_EQ(fill_template(text, {}, {{"f", false}, {"g", true}}), "a\nnot f\nz\n");
}

TEST(TextTemplate, MistakesAreNamed) {
  const auto message = [](const std::string& text, const std::map<std::string, std::string>& values,
                          const std::map<std::string, bool>& flags) {
    try {
      fill_template(text, values, flags);
    } catch (const std::logic_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("@X@\n", {}, {}), "fill_template: no value X");
  // A hole in a block that is dropped must be given too.
  EXPECT_EQ(message("//@if f\n@X@\n//@end\n", {}, {{"f", false}}), "fill_template: no value X");
  EXPECT_EQ(message("x\n", {{"X", "1"}}, {}), "fill_template: value X given but never used");
  EXPECT_EQ(message("x\n", {}, {{"f", true}}), "fill_template: flag f given but never used");
  EXPECT_EQ(message("//@if f\nx\n", {}, {{"f", true}}), "fill_template: //@if without //@end");
  EXPECT_EQ(message("//@end\n", {}, {}), "fill_template: //@end without //@if");
  EXPECT_EQ(message("//@else\n", {}, {}), "fill_template: //@else without //@if");
  EXPECT_EQ(message("//@if g\nx\n//@end\n", {}, {}), "fill_template: no flag g");
  EXPECT_EQ(message("a@b\n", {}, {}), "fill_template: an '@' without its pair in: a@b");
  EXPECT_EQ(message("x", {}, {}), "fill_template: a last line without its newline");
}

}  // namespace
}  // namespace glrc::reproducer
