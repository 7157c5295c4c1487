#include <openssl/evp.h>

#include <bit>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "ref/reference.hpp"

namespace glrc::ref {

namespace {

// SHA-256 of what `fill` feeds it, as hex.
template <typename Fill>
std::string sha256(const Fill& fill) {
  static_assert(std::endian::native == std::endian::little, "digest hashes little-endian bits");
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("OpenSSL SHA-256 unavailable");
  fill([&](const void* p, size_t n) { EVP_DigestUpdate(ctx.get(), p, n); });
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  EVP_DigestFinal_ex(ctx.get(), md, &len);
  static const char* kHex = "0123456789abcdef";
  std::string out;
  for (unsigned i = 0; i < len; ++i)
    out += kHex[md[i] >> 4], out += kHex[md[i] & 15];
  return out;
}

}  // namespace

std::string digest(const Frame& f) {
  return sha256([&](const auto& feed) {
    const int32_t size[2] = {f.width, f.height};
    feed(size, sizeof size);
    // Per pixel, so that the layout of Frame's vectors is not part of the digest.
    for (size_t i = 0; i < f.pixel_count(); ++i) {
      feed(&f.primitive[i], 4);
      feed(&f.depth[i], 4);
      for (const auto& comp : f.components)
        feed(&comp[i], 4);
    }
  });
}

std::string expectation_digest(const Reference& r) {
  return sha256([&](const auto& feed) {
    feed(digest(r.frame).data(), 64);
    feed(r.edges.data(), r.edges.size());
    const Frame& a = r.allowed;
    for (size_t i = 0; i < a.primitive.size(); ++i) {
      feed(&a.primitive[i], 4);
      feed(&a.depth[i], 4);
      for (const auto& comp : a.components)
        feed(&comp[i], 4);
    }
    for (const Candidate& k : r.candidates) {
      const uint64_t pixel = k.pixel;
      feed(&pixel, 8);
      feed(&k.primitive, 4);
      feed(&k.depth, 4);
      feed(&k.allowed_depth, 4);
      feed(k.values.data(), 4 * k.values.size());
      feed(k.allowed.data(), 4 * k.allowed.size());
    }
  });
}

}  // namespace glrc::ref
