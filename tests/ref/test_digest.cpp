// The frame digest (ref::digest, FrameDigest; results.json's gl_digest): SHA-256 of the width
// and height, then per pixel its primitive, depth and every component, 4 bytes each. Its rows
// are put together four pixels and four channels at a time where it can: every channel count
// and width, and bits that are NaNs with payloads, must hash as the plain layout does.
#include <gtest/gtest.h>
#include <openssl/evp.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ref/reference.hpp"

namespace glrc::ref {
namespace {

// SHA-256 (hex) of the bytes the digest is defined on, laid out one word at a time.
std::string plain_digest(const Frame& f) {
  std::vector<unsigned char> bytes;
  auto word = [&](const void* p) {
    const auto* b = static_cast<const unsigned char*>(p);
    bytes.insert(bytes.end(), b, b + 4);
  };
  const int32_t size[2] = {f.width, f.height};
  word(&size[0]), word(&size[1]);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const size_t i = f.index(x, y);
      word(&f.primitive[i]);
      word(&f.depth[i]);
      for (const auto& component : f.components)
        word(&component[i]);
    }
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_Digest(bytes.data(), bytes.size(), md, &length, EVP_sha256(), nullptr);
  std::string hex;
  for (unsigned k = 0; k < length; ++k) {
    static const char* digits = "0123456789abcdef";
    hex += digits[md[k] >> 4], hex += digits[md[k] & 15];
  }
  return hex;
}

TEST(Digest, IsSha256OfEachPixelsWordsForEveryWidthAndChannelCount) {
  uint32_t seed = 12345;
  auto next = [&] { return seed = seed * 1664525u + 1013904223u; };
  for (int components = 0; components <= 7; ++components)
    for (int width : {1, 3, 4, 5, 8, 13}) {
      Frame f(width, 3, components);
      for (size_t i = 0; i < f.pixel_count(); ++i) {
        f.primitive[i] = int32_t(next());
        f.depth[i] = std::bit_cast<float>(next());
        for (auto& component : f.components)
          component[i] = std::bit_cast<float>(next());
      }
      // A quiet and a signalling NaN with payloads: their bits, not their values, are hashed.
      if (components > 0) {
        f.components[0][0] = std::bit_cast<float>(0x7fc01234u);
        f.components[size_t(components - 1)][f.pixel_count() - 1] =
            std::bit_cast<float>(0xff800001u);
      }
      const std::string expected = plain_digest(f);
      EXPECT_EQ(digest(f), expected) << components << " components, " << width << " wide";
      // Band by band, as a streamed case adds them.
      FrameDigest bands(width, 3);
      bands.add_rows(f.rows(0, 1));
      bands.add_rows(f.rows(1, 2));
      EXPECT_EQ(bands.hex(), expected);
    }
}

}  // namespace
}  // namespace glrc::ref
