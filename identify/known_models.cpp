#include "identify/known_models.hpp"

namespace glrc::identify {

namespace {

constexpr KnownModel kKnown[] = {
    {"llvmpipe", {8, Planes::unsnapped, TieBreak::bottom_left}, 8},
    {"softpipe", {0, Planes::unsnapped, TieBreak::bottom_right}, 4},
    {"zink", {8, Planes::unsnapped, TieBreak::bottom_left}, 4},
};

}  // namespace

std::span<const KnownModel> known_models() {
  return kKnown;
}

const KnownModel* known_model(std::string_view driver) {
  for (const KnownModel& k : kKnown)
    if (k.driver == driver) return &k;
  return nullptr;
}

}  // namespace glrc::identify
