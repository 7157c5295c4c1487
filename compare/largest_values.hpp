// The largest values of a stream, enough of them for its nearest-rank 99th percentile: what the
// comparator keeps of each channel's errors instead of every one of them.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace glrc::compare {

// A float's bits as an unsigned key in the float's order: negatives below positives, -0 just
// below +0, a NaN above +infinity, so that every value has a place.
inline uint32_t order_key(float v) {
  const uint32_t bits = std::bit_cast<uint32_t>(v);
  return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}
inline float float_of_order_key(uint32_t key) {
  return std::bit_cast<float>(key & 0x80000000u ? key & 0x7fffffffu : ~key);
}

// The nearest-rank 99th percentile of `values` (the ChannelStats p99s): the element of rank
// ceil(0.99·n) - 1 in ascending order (order_key's order); 0 for no values.
double p99(const std::vector<float>& values);

// The p99 above of a stream of values, without holding the stream: for n values it is the
// (n - rank)-th largest, and n - rank <= n/100 + 1, so only the largest few are kept (at most
// 2·(most/100 + 16) for at most `most` values; those not above the smallest kept value once
// enough are kept are dropped as they come). Amortized constant time per value.
class LargestValues {
 public:
  explicit LargestValues(size_t most);
  void add(float v) {  // inline: once per compared value; most are dropped here
    ++count_;
    offer(order_key(v));
  }
  // add() in two parts, for a loop over many values: count_dropped(n) counts them, and offer()
  // of each value's order_key, in order, keeps it if add() would. offer() may be left out for
  // a key not above floor_key() (for a key above 0): add() drops it.
  void offer(uint32_t key) {
    if (compacted_ && key <= floor_) return;
    keep(key);
  }
  uint32_t floor_key() const { return compacted_ ? floor_ : 0; }
  // Whether add(float(a / b)) certainly drops the value, for a >= 0 and b > 0, without the
  // division: once compacted, when a < floor·b·(1 - 2^-20) as computed, so that a/b <
  // floor·(1 - 2^-22) and neither rounding, the division's nor float's, can carry it up to the
  // floor. Then the value is below every kept value, and below the keep_-th (at least the 16th)
  // largest value added so far: for a floor of a normal float > 0, every value kept was at
  // least floor·(1 - 2^-24) before its rounding to float. False (always for a NaN, an infinite
  // a or a zero b) says nothing: add it.
  bool certainly_dropped(double a, double b) const {
    return may_drop() && below_drop_bound(a, b, floor_value_);
  }
  // certainly_dropped(a, b) is may_drop() && below_drop_bound(a, b, floor_value()): apart, for
  // a loop over many values that tests the one once and the other without a branch.
  bool may_drop() const { return compacted_ && floor_value_ >= 0x1p-100; }
  double floor_value() const { return floor_value_; }
  static bool below_drop_bound(double a, double b, double floor_value) {
    return a < floor_value * b * (1 - 0x1p-20);
  }
  // Counts n values: dropped (certainly_dropped said so), or offered apart.
  void count_dropped(size_t n = 1) { count_ += n; }
  size_t count() const { return count_; }
  // Starts the stream as if it had been compacted to `floor` (an order_key above that of a
  // float > 0), before any value is added: values not above it are dropped from the first.
  // For a floor guessed from a sample of the stream (Comparator): in a stream whose values
  // rise (the errors of a frame growing from row to row), the floor of the largest values so
  // far climbs slowly, and until it reaches the stream's 99th percentile many values are kept
  // and selected among only to be dropped (measured on a 1024x1024 frame: 7% of its values
  // kept, 203 compactions). The stream may not bear the guess out: complete() says whether
  // it did.
  void assume_floor(uint32_t floor);
  // Whether what the kept values give is the stream's: p99(), and certainly_dropped()'s
  // promise that a value it drops is below the keep_ largest (the comparator's largest and
  // worst values rely on it). Always, unless a floor was assumed and no compaction happened
  // since: then only if at least keep_ values were kept, every value above the floor being
  // kept, and p99() reaching down to the (count - rank)-th largest, fewer than keep_.
  bool complete() const { return !assumed_ || keys_.size() >= keep_; }
  // How many of the largest values a compaction keeps (most / 100 + 16).
  size_t kept_after_compaction() const { return keep_; }
  // The nearest-rank 99th percentile of every value added; 0 for none. Requires complete().
  double p99();

 private:
  void keep(uint32_t key);  // out of line: it may grow or compact the keys
  void compact();

  size_t keep_, count_ = 0;
  std::vector<uint32_t> keys_;
  uint32_t floor_ = 0;
  double floor_value_ = 0;  // float_of_order_key(floor_)
  bool compacted_ = false;
  bool assumed_ = false;  // floor_ was assumed, and no compaction has happened since
};

}  // namespace glrc::compare
