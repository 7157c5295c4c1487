// core/channel.hpp and core/expectation.hpp: a channel's slot is 0 for the depth and k + 1 for
// component k, in every direction; an expectation's allowance state is read from its fields in
// one place, and every way the fields can contradict it is named by allowance_shape_error (which
// the comparator, tests/compare/test_comparator.cpp, and the exporters refuse).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/expectation.hpp"

namespace glrc {
namespace {

TEST(Channel, SlotsAreDepthThenEachComponent) {
  EXPECT_TRUE(Channel::depth().is_depth());
  EXPECT_EQ(Channel::depth().slot(), 0u);
  EXPECT_EQ(Channel::component(0).slot(), 1u);
  EXPECT_EQ(Channel::component(6).slot(), 7u);
  EXPECT_FALSE(Channel::component(0).is_depth());
  for (size_t slot = 0; slot < 9; ++slot)
    EXPECT_EQ(Channel::at_slot(slot).slot(), slot);
  EXPECT_EQ(Channel::at_slot(3), Channel::component(2));
  const std::vector<Channel> all = channels_of(3);
  ASSERT_EQ(all.size(), 4u);
  for (size_t slot = 0; slot < all.size(); ++slot)
    EXPECT_EQ(all[slot].slot(), slot);
  EXPECT_EQ(channels_of(0), std::vector<Channel>{Channel::depth()});

  Frame f(3, 2, 2);
  f.components[1][4] = 7.0f, f.depth[4] = 0.5f;
  EXPECT_EQ(f.values(Channel::component(1))[4], 7.0f);
  EXPECT_EQ(f.values(Channel::depth())[4], 0.5f);
  EXPECT_EQ(&f.values(Channel::component(0)), &f.components[0]);

  const Candidate o{4, 1, 0.25f, 0.125f, {1, 2}, {0.5f, 0.75f}};
  EXPECT_EQ(o.value(Channel::depth()), 0.25f);
  EXPECT_EQ(o.value(Channel::component(1)), 2.0f);
  EXPECT_EQ(o.allowance(Channel::depth()), 0.125f);
  EXPECT_EQ(o.allowance(Channel::component(0)), 0.5f);
}

// A deferred allowance that says whether it defers the depth; nothing asks it for values here.
class Deferred final : public DeferredAllowance {
 public:
  explicit Deferred(bool depth) : depth_(depth) {}
  bool defers_depth() const override { return depth_; }
  void at(const Frame&, Channel, size_t, int n, float* out) const override {
    std::fill(out, out + n, 1.0f);
  }
  std::array<double, 2> range(Channel, int32_t, int, int, int, float, float) const override {
    return {1.0, 1.0};
  }

 private:
  bool depth_;
};

Expectation of_state(AllowanceState state) {
  Expectation e;
  e.frame = Frame(4, 3, 2);
  e.edges.assign(e.frame.pixel_count(), 0);
  if (state == AllowanceState::none) return e;
  if (state != AllowanceState::all_deferred) e.allowed.depth.assign(e.frame.pixel_count(), 0.0f);
  if (state == AllowanceState::per_pixel)
    e.allowed.components.assign(2, std::vector<float>(e.frame.pixel_count(), 0.0f));
  else
    e.deferred = std::make_shared<Deferred>(state == AllowanceState::all_deferred);
  return e;
}

TEST(Expectation, EachAllowanceStateIsReadFromItsFields) {
  for (const AllowanceState state :
       {AllowanceState::none, AllowanceState::per_pixel, AllowanceState::deferred_components,
        AllowanceState::all_deferred}) {
    const Expectation e = of_state(state);
    EXPECT_EQ(e.allowance_state(), state) << int(state);
    EXPECT_EQ(e.allowance_shape_error(), "") << int(state);
  }
}

TEST(Expectation, FieldsThatContradictTheStateAreNamed) {
  const size_t pixels = 12;
  Expectation e = of_state(AllowanceState::per_pixel);
  e.allowed.components[1].pop_back();
  EXPECT_EQ(e.allowance_shape_error(), "the allowance's components are not the frame's size");
  e = of_state(AllowanceState::per_pixel);
  e.allowed.components.pop_back();
  EXPECT_EQ(e.allowance_shape_error(), "the allowance has not the frame's components");
  e = of_state(AllowanceState::per_pixel);
  e.allowed.depth.resize(pixels - 1);
  EXPECT_EQ(e.allowance_shape_error(), "the allowance's depth is not the frame's size");
  e = of_state(AllowanceState::deferred_components);
  e.allowed.components.assign(2, std::vector<float>(pixels, 0.0f));
  EXPECT_EQ(e.allowance_shape_error(), "components both deferred and held");
  e = of_state(AllowanceState::all_deferred);
  e.allowed.depth.assign(pixels, 0.0f);
  // Held depth with a deferred allowance that defers it too: the state is all_deferred (the
  // deferred allowance says so), and the held depth contradicts it.
  EXPECT_EQ(e.allowance_state(), AllowanceState::all_deferred);
  EXPECT_EQ(e.allowance_shape_error(), "an allowance both deferred and held");
  e = of_state(AllowanceState::none);
  e.allowed.components.assign(2, std::vector<float>(pixels, 0.0f));
  EXPECT_EQ(e.allowance_shape_error(), "an allowance of components without the depth's");
}

// A deferred allowance gives the components', and the depth's only where it defers it.
TEST(Expectation, ADeferredAllowanceGivesItsChannels) {
  EXPECT_EQ(Deferred(false).channels(2),
            (std::vector<Channel>{Channel::component(0), Channel::component(1)}));
  EXPECT_EQ(Deferred(true).channels(1),
            (std::vector<Channel>{Channel::depth(), Channel::component(0)}));
  EXPECT_TRUE(Deferred(false).channels(0).empty());
}

// complete_allowance makes either deferred state per pixel, with every channel's values.
TEST(Expectation, CompletingADeferredAllowanceMakesItPerPixel) {
  for (const AllowanceState state :
       {AllowanceState::deferred_components, AllowanceState::all_deferred}) {
    Expectation e = of_state(state);
    complete_allowance(e, 2);
    EXPECT_EQ(e.allowance_state(), AllowanceState::per_pixel) << int(state);
    EXPECT_EQ(e.allowance_shape_error(), "") << int(state);
    EXPECT_EQ(e.allowed.components[1][11], 1.0f);
    // The depth: held as it was (0), or computed by the deferred allowance (1).
    EXPECT_EQ(e.allowed.depth[5], state == AllowanceState::all_deferred ? 1.0f : 0.0f);
  }
}

}  // namespace
}  // namespace glrc
