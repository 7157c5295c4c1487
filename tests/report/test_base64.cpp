// base64_encode against RFC 4648's test vectors (section 10), and bytes above 0x7f, which a
// signed char would turn into negative indices.
#include <gtest/gtest.h>

#include <string>

#include "report/base64.hpp"

using glrc::report::base64_encode;

TEST(Base64, Rfc4648Vectors) {
  EXPECT_EQ(base64_encode(""), "");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("foo"), "Zm9v");
  EXPECT_EQ(base64_encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64_encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, HighBytesAndTheWholeAlphabet) {
  EXPECT_EQ(base64_encode(std::string("\xff\xfe\xfd", 3)), "//79");
  EXPECT_EQ(base64_encode(std::string("\x00\x00\x00", 3)), "AAAA");
  EXPECT_EQ(base64_encode(std::string("\x89PNG\r\n\x1a\n", 8)), "iVBORw0KGgo=");
  // 0x00 0x10 0x83 ... : every 6-bit value once, so the output is the alphabet in order.
  std::string bytes;
  for (unsigned k = 0; k < 64; k += 4) {
    const unsigned v = k << 18 | (k + 1) << 12 | (k + 2) << 6 | (k + 3);
    bytes += char(v >> 16 & 0xff);
    bytes += char(v >> 8 & 0xff);
    bytes += char(v & 0xff);
  }
  EXPECT_EQ(base64_encode(bytes),
            "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/");
}
