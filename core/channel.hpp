// Channel: which of a frame's interpolated values is meant, the depth or a varying component,
// and where it stands among them.
#pragma once

#include <cstddef>
#include <vector>

namespace glrc {

// One channel of a frame that is interpolated and judged: the depth (z_w) or varying component
// k (Case component order). Its slot among a frame's channels, in the order the comparator and
// results.json list them, is 0 for the depth and k + 1 for component k.
class Channel {
 public:
  static constexpr Channel depth() { return Channel(-1); }
  static constexpr Channel component(int k) { return Channel(k); }  // k >= 0
  static constexpr Channel at_slot(size_t slot) { return Channel(int(slot) - 1); }
  constexpr bool is_depth() const { return k_ < 0; }
  constexpr int component() const { return k_; }  // only for !is_depth()
  constexpr size_t slot() const { return size_t(k_ + 1); }
  friend constexpr bool operator==(Channel, Channel) = default;

 private:
  explicit constexpr Channel(int k) : k_(k) {}
  int k_;
};

// Every channel of a frame with `component_count` components, by slot: the depth, then each
// component.
inline std::vector<Channel> channels_of(int component_count) {
  std::vector<Channel> out{Channel::depth()};
  for (int k = 0; k < component_count; ++k)
    out.push_back(Channel::component(k));
  return out;
}

}  // namespace glrc
