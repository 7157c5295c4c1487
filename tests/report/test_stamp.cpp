// Stamps (report/stamp.hpp), from both sides: a file glrefcheck stamped is recognised as long as
// not one byte of it changed; a file with no stamp, the prefix written by hand, or any edit is not.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "report/stamp.hpp"

namespace glrc::report {
namespace {

TEST(Stamp, HoldsUntilAnyByteChanges) {
  const std::string text = stamped("# notes\n" + stamp_placeholder() + "\nbody\n");
  EXPECT_EQ(text.find(stamp_placeholder()), std::string::npos);
  EXPECT_TRUE(stamp_intact(text));
  for (size_t k = 0; k < text.size(); ++k) {
    std::string edited = text;
    edited[k] = char(edited[k] ^ 1);
    EXPECT_FALSE(stamp_intact(edited)) << "byte " << k;
  }
  EXPECT_FALSE(stamp_intact(text + "x"));
  EXPECT_FALSE(stamp_intact(text.substr(0, text.size() - 1)));
}

TEST(Stamp, NoneOrAForgedOneIsNotIntact) {
  EXPECT_FALSE(stamp_intact("glrefcheck fuzz wrote this, says a person"));
  EXPECT_FALSE(stamp_intact(stamp_placeholder()));  // zeros are no hash of anything here
  EXPECT_FALSE(stamp_intact(std::string(kStampPrefix) + "abc"));
  EXPECT_FALSE(stamp_intact(""));
  EXPECT_THROW(stamped("no placeholder"), std::logic_error);
}

}  // namespace
}  // namespace glrc::report
