#include "compare/largest_values.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace glrc::compare {

double p99(const std::vector<float>& values) {
  LargestValues largest(values.size());
  for (float v : values)
    largest.add(v);
  return largest.p99();
}

LargestValues::LargestValues(size_t most) : keep_(most / 100 + 16) {}

void LargestValues::keep(uint32_t key) {
  keys_.push_back(key);
  if (keys_.size() >= 2 * keep_) compact();
}

void LargestValues::compact() {
  // The keep_ largest keys, the smallest of them last: everything not above it may go. Above
  // an assumed floor, every key kept is above it, and so is the new floor.
  std::nth_element(keys_.begin(), keys_.begin() + ptrdiff_t(keep_ - 1), keys_.end(),
                   std::greater<>());
  keys_.resize(keep_);
  floor_ = keys_.back();
  compacted_ = true;
  assumed_ = false;
  floor_value_ = float_of_order_key(floor_);
}

void LargestValues::assume_floor(uint32_t floor) {
  if (count_ > 0 || compacted_ || floor <= order_key(0.0f) ||
      floor >= order_key(std::numeric_limits<float>::infinity()))
    throw std::logic_error("LargestValues: a floor is assumed above 0, before any value");
  floor_ = floor;
  compacted_ = assumed_ = true;
  floor_value_ = float_of_order_key(floor_);
}

double LargestValues::p99() {
  if (count_ == 0) return 0;
  const size_t rank = size_t(std::ceil(0.99 * double(count_))) - 1;
  // The (count - rank)-th largest. Every value above floor_ is kept, and at least keep_ values
  // not below it, so the kept keys' j-th largest is the stream's for any j <= keep_.
  const size_t j = count_ - rank;
  if (j > keys_.size() || !complete())
    throw std::logic_error("LargestValues: kept too few values for p99");
  std::nth_element(keys_.begin(), keys_.begin() + ptrdiff_t(j - 1), keys_.end(), std::greater<>());
  return float_of_order_key(keys_[j - 1]);
}

}  // namespace glrc::compare
