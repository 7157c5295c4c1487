#include "core/fragment_trace.hpp"

#include <algorithm>
#include <tuple>

namespace glrc {

std::optional<std::vector<FragmentTrace>> admitted(const FragmentChoices& choices) {
  if (choices.anything || choices.edges >= 64) return std::nullopt;
  // The free members whatever the sides are: an upper bound of those of any one choice of sides.
  uint64_t sides = uint64_t(1) << choices.edges;
  size_t free = 0;
  for (const FragmentChoices::Member& m : choices.members)
    free += size_t(m.free) + size_t(m.folds);
  // (free first: a shift by 64 or more, or one that carries bits out, would say nothing.)
  if (free > 12 || sides > kMostTraceChoices || (sides << free) > kMostTraceChoices)
    return std::nullopt;
  std::vector<FragmentTrace> out;
  std::vector<FragmentTrace> optional;
  for (uint64_t s = 0; s < sides; ++s) {
    // Bit e of s: edge e gives the pixel to its first side.
    FragmentTrace base = choices.sure;
    optional.clear();
    for (const FragmentChoices::Member& m : choices.members) {
      const bool on_side = std::all_of(m.sides.begin(), m.sides.end(), [&](const auto& side) {
        return (((s >> side.first) & 1) != 0) == side.second;
      });
      if (!on_side) continue;
      if (m.free)
        optional.push_back(fragment_trace(m.primitive));
      else
        base += fragment_trace(m.primitive);
      if (m.folds) optional.push_back(fragment_trace(m.primitive));  // a second cover
    }
    for (uint64_t subset = 0; subset < (uint64_t(1) << optional.size()); ++subset) {
      FragmentTrace ids = base;
      for (size_t k = 0; k < optional.size(); ++k)
        if ((subset >> k) & 1) ids += optional[k];
      out.push_back(ids);
    }
  }
  const auto key = [](const FragmentTrace& i) { return std::tie(i.count, i.id_sum, i.hash_sum); };
  std::sort(out.begin(), out.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace glrc
