// core/frame.hpp: a new frame is cleared whole (no primitive, depth 1, every component 0),
// whichever number of threads fills it.
#include <gtest/gtest.h>

#include <algorithm>

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

}  // namespace
}  // namespace glrc
