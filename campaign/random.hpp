// The campaign's random numbers: one stream per generated case, the same numbers on every
// machine, compiler and standard library. std::mt19937 would be portable but its distributions
// are not (std::uniform_real_distribution differs between libstdc++ and libc++), so every
// distribution here is written out in integer arithmetic and IEEE +, -, *, / (no libm), and the
// module is compiled without floating-point contraction.
#pragma once

#include <cstdint>
#include <string_view>

namespace glrc::campaign {

// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators", 2014):
// 64 bits of state, every output a bijective mix of it; plenty for test inputs.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, n), n >= 1 (Lemire's multiply-shift; the tiny bias of skipping rejection is
  // irrelevant for test inputs and keeps one draw per call).
  uint64_t below(uint64_t n) {
    // The high half of the 128-bit product, from 32-bit halves (ISO C++ has no __int128).
    const uint64_t x = next(), xl = x & 0xffffffff, xh = x >> 32;
    const uint64_t nl = n & 0xffffffff, nh = n >> 32;
    const uint64_t ll = xl * nl, lh = xl * nh, hl = xh * nl, hh = xh * nh;
    const uint64_t mid = (ll >> 32) + (lh & 0xffffffff) + (hl & 0xffffffff);
    return hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
  }
  // Uniform in [lo, hi], lo <= hi.
  int between(int lo, int hi) { return lo + int(below(uint64_t(int64_t(hi) - lo + 1))); }
  // Uniform in [0, 1), 53 random bits.
  double unit() { return double(next() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  bool chance(double p) { return unit() < p; }
  // 2^e · (1 + u), e uniform in [lo_exponent, hi_exponent], u uniform in [0, 1): magnitudes
  // spread evenly over binades (log-distributed).
  double binades(int lo_exponent, int hi_exponent) {
    const int e = between(lo_exponent, hi_exponent);
    double v = 1 + unit();
    // Scaling by 2 is exact: no libm ldexp needed.
    for (int k = 0; k < e; ++k)
      v *= 2;
    for (int k = 0; k > e; --k)
      v *= 0.5;
    return v;
  }
  double sign() { return chance(0.5) ? -1.0 : 1.0; }

 private:
  uint64_t state_;
};

// A seed for one stream from the campaign's seed, the case's index and the generator's name:
// distinct inputs give unrelated streams.
inline uint64_t stream_seed(uint64_t seed, uint64_t index, std::string_view generator) {
  uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a over the name
  for (const char ch : generator)
    h = (h ^ uint8_t(ch)) * 0x100000001b3ull;
  Random by_seed(seed ^ h);
  Random by_index(by_seed.next() + index * 0xd6e8feb86659fd93ull);
  return by_index.next();
}

}  // namespace glrc::campaign
