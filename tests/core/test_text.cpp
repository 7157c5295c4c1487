// Text helpers (core/text.hpp): word wrapping for the comment blocks of generated files.
#include <gtest/gtest.h>

#include "core/text.hpp"

namespace glrc {
namespace {

TEST(WrapWords, BreaksAtSpacesWithinTheWidthAndPrefixesEveryLine) {
  EXPECT_EQ(wrap_words("one two three four", 9, "# "), "# one two\n# three\n# four\n");
  // Runs of spaces count as one; a word longer than the width has a line of its own.
  EXPECT_EQ(wrap_words("a  verylongword b", 4, " * "), " * a\n * verylongword\n * b\n");
  EXPECT_EQ(wrap_words("", 10, "# "), "");
  EXPECT_EQ(wrap_words("exactly10c", 10, ""), "exactly10c\n");
}

}  // namespace
}  // namespace glrc
