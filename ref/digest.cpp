#include <openssl/evp.h>

#include <bit>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "ref/reference.hpp"

namespace glrc::ref {

std::string digest(const Frame& f) {
  static_assert(std::endian::native == std::endian::little, "digest hashes little-endian bits");
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("OpenSSL SHA-256 unavailable");
  auto feed = [&](const void* p, size_t n) { EVP_DigestUpdate(ctx.get(), p, n); };
  const int32_t size[2] = {f.width, f.height};
  feed(size, sizeof size);
  // Per pixel, so that the layout of Frame's vectors is not part of the digest.
  for (size_t i = 0; i < f.pixel_count(); ++i) {
    feed(&f.primitive[i], 4);
    feed(&f.depth[i], 4);
    for (const auto& comp : f.components)
      feed(&comp[i], 4);
  }
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  EVP_DigestFinal_ex(ctx.get(), md, &len);
  static const char* kHex = "0123456789abcdef";
  std::string out;
  for (unsigned i = 0; i < len; ++i)
    out += kHex[md[i] >> 4], out += kHex[md[i] & 15];
  return out;
}

}  // namespace glrc::ref
