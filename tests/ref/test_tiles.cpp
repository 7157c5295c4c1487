// The reference's tiles (ref/tiles.hpp): bands that cover every row once, in order; a parallel
// loop that runs every item once on any number of threads and hands an item's exception back;
// and the same bits from render() on 1, 2 and 5 threads (the committed digests of every case
// at 2 and 5 threads are ctest's digest.threads_* and digest.expectation_threads_*).
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "ref/reference.hpp"
#include "ref/tiles.hpp"

namespace glrc::ref {
namespace {

TEST(Tiles, BandsCoverEveryRowOnceInOrder) {
  for (int threads : {1, 2, 5, 64})
    for (auto [y0, y1] : {std::pair{0, 0}, {0, 7}, {3, 1002}, {0, 4095}}) {
      const std::vector<Band> b = bands(y0, y1, threads);
      ASSERT_FALSE(b.empty());
      EXPECT_EQ(b.front().y0, y0);
      EXPECT_EQ(b.back().y1, y1);
      for (size_t k = 0; k < b.size(); ++k) {
        EXPECT_LE(b[k].y0, b[k].y1);
        if (k > 0) {
          EXPECT_EQ(b[k].y0, b[k - 1].y1 + 1);
        }
      }
      EXPECT_LE(int(b.size()), std::max(1, 4 * threads));
    }
  EXPECT_TRUE(bands(5, 4, 2).empty());
}

TEST(Tiles, ParallelForRunsEveryItemOnce) {
  for (int threads : {1, 2, 5}) {
    std::vector<std::atomic<int>> seen(1000);
    parallel_for(1000, threads, [&](int k) { ++seen[size_t(k)]; });
    for (const auto& s : seen)
      EXPECT_EQ(s.load(), 1);
  }
}

TEST(Tiles, AnItemsExceptionReachesTheCaller) {
  EXPECT_THROW(parallel_for(100, 4,
                            [](int k) {
                              if (k == 37) throw std::runtime_error("item 37");
                            }),
               std::runtime_error);
}

TEST(Tiles, ThreadCountIsAtLeastOne) {
  EXPECT_EQ(thread_count(3), 3);
  EXPECT_GE(thread_count(0), 1);
}

TEST(Tiles, OverlappingTrianglesGiveTheSameBitsOnAnyNumberOfThreads) {
  // Many triangles over one another, depth-tested and contested: the order in which a pixel
  // sees them decides its bits and its candidates.
  Case c;
  c.name = "tiles";
  c.fb_width = 97, c.fb_height = 61;
  c.viewport = {0, 0, 97, 61};
  c.depth_func = DepthFunc::less;
  c.varyings = {{"v", 2, Interpolation::smooth}};
  uint32_t seed = 7;
  auto next = [&] {
    seed = seed * 1664525u + 1013904223u;
    return float(seed >> 8) / float(1u << 24) * 2.4f - 1.2f;
  };
  for (int t = 0; t < 300; ++t) {
    for (int k = 0; k < 3; ++k)
      c.vertices.push_back(
          {{next(), next(), next() * 1e-6f, 1.0f + 0.5f * next()}, {next(), next()}});
    c.triangles.push_back({uint32_t(3 * t), uint32_t(3 * t + 1), uint32_t(3 * t + 2)});
  }
  const std::string one = expectation_digest(render(c, Model{}, 8, 1));
  EXPECT_EQ(expectation_digest(render(c, Model{}, 8, 2)), one);
  EXPECT_EQ(expectation_digest(render(c, Model{}, 8, 5)), one);
  EXPECT_EQ(digest(render(c, Model{}, std::nullopt, 5).frame),
            digest(render(c, Model{}, std::nullopt, 1).frame));
  EXPECT_FALSE(render(c, Model{}, 8, 5).candidates.empty());  // the depth order was contested
}

}  // namespace
}  // namespace glrc::ref
