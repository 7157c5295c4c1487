// core/frame.hpp: a new frame is cleared whole (no primitive, depth 1, every component 0),
// whichever number of threads fills it; a frame reset in another's buffers is the same frame,
// reusing them where they are large enough and giving back those far too large.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/frame.hpp"

namespace glrc {
namespace {

TEST(Frame, ClearedWholeOnAnyThreadCount) {
  for (int threads : {1, 2, 5}) {
    const Frame f(37, 11, 6, threads);
    ASSERT_EQ(f.pixel_count(), size_t(37 * 11));
    ASSERT_EQ(f.primitive.size(), f.pixel_count()) << threads;
    ASSERT_EQ(f.depth.size(), f.pixel_count()) << threads;
    ASSERT_EQ(f.components.size(), size_t(6)) << threads;
    EXPECT_TRUE(std::all_of(f.primitive.begin(), f.primitive.end(),
                            [](int32_t p) { return p == Frame::kNoPrimitive; }));
    EXPECT_TRUE(std::all_of(f.depth.begin(), f.depth.end(), [](float z) { return z == 1.0f; }));
    for (const auto& c : f.components) {
      ASSERT_EQ(c.size(), f.pixel_count()) << threads;
      EXPECT_TRUE(std::all_of(c.begin(), c.end(), [](float v) { return v == 0.0f; }));
    }
  }
}

// reset() of a frame that held another case's values (another size, more or fewer components,
// fragment counts) is a new frame, field for field.
TEST(Frame, ResetInAnotherFramesBuffersIsANewFrame) {
  for (const auto& [w, h, k] :
       {std::array{37, 11, 6}, std::array{20, 9, 2}, std::array{37, 11, 9}, std::array{1, 1, 0}}) {
    Frame old(40, 12, 7, 2);
    std::fill(old.primitive.begin(), old.primitive.end(), 3);
    std::fill(old.depth.begin(), old.depth.end(), 0.25f);
    for (auto& c : old.components)
      std::fill(c.begin(), c.end(), -2.0f);
    old.fragments.assign(old.pixel_count(), uint16_t(2));
    old.reset(w, h, k, 2);
    const Frame fresh(w, h, k);
    EXPECT_EQ(old.width, fresh.width);
    EXPECT_EQ(old.height, fresh.height);
    EXPECT_EQ(old.primitive, fresh.primitive);
    EXPECT_EQ(old.depth, fresh.depth);
    EXPECT_EQ(old.components, fresh.components);
    EXPECT_TRUE(old.fragments.empty());
  }
}

// reset_uncleared() sizes every buffer as reset() does, in the same storage, and fills none:
// what a buffer held stays where it still fits (GL's readback then writes every value).
TEST(Frame, ResetUnclearedSizesEveryBufferAndFillsNone) {
  Frame f(40, 12, 3, 2);
  std::fill(f.primitive.begin(), f.primitive.end(), 3);
  std::fill(f.depth.begin(), f.depth.end(), 0.25f);
  for (auto& c : f.components)
    std::fill(c.begin(), c.end(), -2.0f);
  f.fragments.assign(f.pixel_count(), uint16_t(2));
  const float* depth = f.depth.data();
  f.reset_uncleared(30, 10, 2, 2);
  EXPECT_EQ(f.width, 30);
  EXPECT_EQ(f.height, 10);
  EXPECT_EQ(f.depth.data(), depth);
  EXPECT_EQ(f.primitive, std::vector<int32_t>(300, 3));
  EXPECT_EQ(f.depth, std::vector<float>(300, 0.25f));
  ASSERT_EQ(f.components.size(), size_t(2));
  for (const auto& c : f.components)
    EXPECT_EQ(c, std::vector<float>(300, -2.0f));
  EXPECT_TRUE(f.fragments.empty());
  // A component the frame did not have is sized too.
  f.reset_uncleared(30, 10, 4, 2);
  ASSERT_EQ(f.components.size(), size_t(4));
  EXPECT_EQ(f.components[3].size(), size_t(300));
}

// The buffers are reused, pages and all, where they are large enough; one over twice as large
// as needed (and over 1 MiB more) is given back, so that a kept frame holds at most about
// twice what it is used for.
TEST(Frame, ResetReusesBuffersLargeEnoughAndGivesBackFarLargerOnes) {
  Frame f(1024, 512, 2);
  const float* depth = f.depth.data();
  f.reset(1000, 500, 2);
  EXPECT_EQ(f.depth.data(), depth);  // 2 MB for 1.95 MB: reused
  f.reset(1024, 128, 2);
  EXPECT_LE(f.depth.capacity(), f.pixel_count() * 2);  // 2 MB for 0.5 MB: given back
  EXPECT_EQ(f.depth.size(), f.pixel_count());
  std::vector<float> small(1000, 1.0f);
  assign_large(small, 10, 0.0f);  // far larger, but under 1 MiB more: kept
  EXPECT_GE(small.capacity(), size_t(1000));
  EXPECT_EQ(small, std::vector<float>(10, 0.0f));
}

}  // namespace
}  // namespace glrc
