#include <openssl/evp.h>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include <bit>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ref/reference.hpp"

namespace glrc::ref {

namespace {

// The digest of `ctx`, as hex.
std::string final_hex(EVP_MD_CTX* ctx) {
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  EVP_DigestFinal_ex(ctx, md, &len);
  static const char* kHex = "0123456789abcdef";
  std::string out;
  for (unsigned i = 0; i < len; ++i)
    out += kHex[md[i] >> 4], out += kHex[md[i] & 15];
  return out;
}

// SHA-256 of what `fill` feeds it, as hex.
template <typename Fill>
std::string sha256(const Fill& fill) {
  static_assert(std::endian::native == std::endian::little, "digest hashes little-endian bits");
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("OpenSSL SHA-256 unavailable");
  fill([&](const void* p, size_t n) { EVP_DigestUpdate(ctx.get(), p, n); });
  return final_hex(ctx.get());
}

// One row of pixels, each pixel's channels together: out[x·channels + k] = in[k][x] for every x
// below `width` and channel k. Four pixels of four channels at a time where x86-64's baseline
// (SSE) can: a 4x4 transpose in registers, four stores where one word at a time takes sixteen.
// Shuffles move bits, never compute with them, so a NaN's payload is kept.
void interleave_row(const uint32_t* const* in, size_t channels, size_t width, uint32_t* out) {
  size_t x = 0;
#if defined(__SSE2__)
  const size_t grouped = channels / 4 * 4;
  for (; x + 4 <= width; x += 4) {
    uint32_t* pixels = out + x * channels;
    for (size_t k = 0; k < grouped; k += 4) {
      __m128 r0 = _mm_loadu_ps(reinterpret_cast<const float*>(in[k] + x));
      __m128 r1 = _mm_loadu_ps(reinterpret_cast<const float*>(in[k + 1] + x));
      __m128 r2 = _mm_loadu_ps(reinterpret_cast<const float*>(in[k + 2] + x));
      __m128 r3 = _mm_loadu_ps(reinterpret_cast<const float*>(in[k + 3] + x));
      _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
      _mm_storeu_ps(reinterpret_cast<float*>(pixels + k), r0);
      _mm_storeu_ps(reinterpret_cast<float*>(pixels + channels + k), r1);
      _mm_storeu_ps(reinterpret_cast<float*>(pixels + 2 * channels + k), r2);
      _mm_storeu_ps(reinterpret_cast<float*>(pixels + 3 * channels + k), r3);
    }
    for (size_t k = grouped; k < channels; ++k)
      for (size_t j = 0; j < 4; ++j)
        pixels[j * channels + k] = in[k][x + j];
  }
#endif
  for (; x < width; ++x)
    for (size_t k = 0; k < channels; ++k)
      out[x * channels + k] = in[k][x];
}

}  // namespace

struct FrameDigest::Context {
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> md{EVP_MD_CTX_new(), EVP_MD_CTX_free};
  std::vector<uint32_t> row;             // one row's pixels, fed at once
  std::vector<const uint32_t*> sources;  // one row of each channel
};

FrameDigest::FrameDigest(int width, int height)
    : context_(std::make_unique<Context>()), width_(width) {
  static_assert(std::endian::native == std::endian::little, "digest hashes little-endian bits");
  if (!context_->md || EVP_DigestInit_ex(context_->md.get(), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("OpenSSL SHA-256 unavailable");
  const int32_t size[2] = {width, height};
  EVP_DigestUpdate(context_->md.get(), size, sizeof size);
}

FrameDigest::~FrameDigest() = default;

void FrameDigest::add_rows(const Frame& f) {
  if (f.width != width_) throw std::invalid_argument("FrameDigest: a slice of another width");
  // Per pixel, so that the layout of Frame's vectors is not part of the digest: primitive,
  // depth, every component, 4 bytes each: a row put together from each channel's row
  // (interleave_row), then hashed.
  static_assert(sizeof(float) == 4 && sizeof(int32_t) == 4);
  const size_t channels = 2 + f.components.size(), width = size_t(f.width);
  std::vector<uint32_t>& row = context_->row;
  std::vector<const uint32_t*>& sources = context_->sources;
  row.resize(channels * width);
  sources.resize(channels);
  for (int y = 0; y < f.height; ++y) {
    const size_t i = f.index(0, y);
    sources[0] = reinterpret_cast<const uint32_t*>(f.primitive.data() + i);
    sources[1] = reinterpret_cast<const uint32_t*>(f.depth.data() + i);
    for (size_t k = 0; k < f.components.size(); ++k)
      sources[2 + k] = reinterpret_cast<const uint32_t*>(f.components[k].data() + i);
    interleave_row(sources.data(), channels, width, row.data());
    EVP_DigestUpdate(context_->md.get(), row.data(), row.size() * sizeof(uint32_t));
  }
}

std::string FrameDigest::hex() {
  return final_hex(context_->md.get());
}

std::string digest(const Frame& f) {
  FrameDigest d(f.width, f.height);
  d.add_rows(f);
  return d.hex();
}

std::string expectation_digest(const Expectation& r) {
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
