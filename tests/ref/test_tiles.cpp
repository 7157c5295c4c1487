// The reference's tiles (ref/tiles.hpp): bands that cover every row once, in order; a parallel
// loop that runs every item once on any number of threads and hands an item's exception back;
// and the same bits from render() on 1, 2 and 5 threads (the committed digests of every case
// at 2 and 5 threads are ctest's digest.threads_* and digest.expectation_threads_*).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "casefile/casefile.hpp"
#include "ref/reference.hpp"
#include "ref/tiles.hpp"

namespace glrc::ref {
namespace {

TEST(Tiles, BandsCoverEveryRowOnceInOrder) {
  for (int threads : {1, 2, 5, 64})
    for (auto [y0, y1] : {std::pair{0, 0}, {0, 7}, {3, 1002}, {0, 4095}}) {
      const std::vector<Tile> b = tiles(y0, y1, threads);
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
  EXPECT_TRUE(tiles(5, 4, 2).empty());
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

TEST(Tiles, AThreadPoolRunsEveryItemOfEveryCallOnce) {
  // Many calls on the same threads, of every size (none, one, fewer items than threads, many):
  // every item of each call once, each call done when it returns; an exception leaves the pool
  // usable.
  for (int threads : {1, 2, 5}) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    std::set<std::thread::id> ids;
    std::mutex ids_lock;
    for (int call = 0; call < 200; ++call) {
      const int n = call % 7 == 0 ? 0 : call % 5 == 0 ? 1 : call % 3 == 0 ? 3 : 64 + call;
      std::vector<std::atomic<int>> seen(static_cast<size_t>(n));
      pool.parallel_for(n, [&](int k) {
        ++seen[size_t(k)];
        const std::lock_guard hold(ids_lock);
        ids.insert(std::this_thread::get_id());
      });
      for (const auto& s : seen)
        ASSERT_EQ(s.load(), 1) << "call " << call << " threads " << threads;
      if (call == 100) {
        EXPECT_THROW(pool.parallel_for(100,
                                       [](int k) {
                                         if (k == 37) throw std::runtime_error("item 37");
                                       }),
                     std::runtime_error);
      }
    }
    // The same threads throughout: at most the pool's, the caller's among them.
    EXPECT_LE(ids.size(), size_t(threads));
    EXPECT_TRUE(ids.count(std::this_thread::get_id()));
  }
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
  // Drawn in the buffers of another case's Expectation (larger, with more components, its
  // candidates and edge bits set; or one without an allowance): the same bits.
  Case other = c;
  other.fb_width = 120, other.fb_height = 70;
  other.viewport = {0, 0, 120, 70};
  other.varyings = {{"v", 2, Interpolation::smooth}, {"u", 3, Interpolation::smooth}};
  for (Vertex& v : other.vertices)
    v.values = {v.values[0], v.values[1], 0.5f, -1.0f, v.values[0]};
  for (const std::optional<int> bits : {std::optional<int>(8), std::optional<int>()}) {
    Expectation storage = render(other, Model{}, bits, 2);
    ASSERT_FALSE(storage.edges.empty());
    EXPECT_EQ(expectation_digest(render(c, Model{}, 8, 2, std::move(storage))), one);
    EXPECT_TRUE(storage.frame.primitive.empty() && storage.allowed.depth.empty());
  }
  Expectation storage = render(other, Model{}, 8, 2);
  EXPECT_EQ(expectation_digest(render(c, Model{}, std::nullopt, 2, std::move(storage))),
            expectation_digest(render(c, Model{}, std::nullopt, 2)));
}

TEST(Tiles, PixelsNothingDrawsAreClearedInAnotherCasesBuffers) {
  // The reference sizes its components without clearing them and clears the pixels no fragment
  // reached once it has drawn: drawn in the buffers of a case that covered every pixel with
  // values and allowances other than 0, a small triangle's frame must still be 0 elsewhere.
  Case full;
  full.name = "full";
  full.fb_width = 40, full.fb_height = 30;
  full.viewport = {0, 0, 40, 30};
  full.varyings = {{"v", 3, Interpolation::smooth}};
  full.vertices = {{{-1, -1, 0, 1}, {1.0f, 2.0f, 3.0f}},
                   {{6, -2, 0, 2}, {4.0f, 5.0f, 6.0f}},
                   {{-1, 3, 0, 1}, {7.0f, 8.0f, 9.0f}}};
  full.triangles = {{0, 1, 2}};
  Case small = full;
  small.name = "small";
  small.vertices = {{{-0.5f, -0.5f, 0, 1}, {1.0f, 2.0f, 3.0f}},
                    {{0.25f, -0.5f, 0, 1}, {4.0f, -5.0f, 6.0f}},
                    {{-0.5f, 0.25f, 0, 1}, {7.0f, 8.0f, -9.0f}}};
  for (const std::optional<int> bits : {std::optional<int>(8), std::optional<int>()}) {
    Expectation storage = render(full, Model{}, bits, 2);
    for (const auto& component : storage.frame.components)
      ASSERT_EQ(std::count(component.begin(), component.end(), 0.0f), 0);
    const Expectation fresh = render(small, Model{}, bits, 2);
    const Expectation reused = render(small, Model{}, bits, 2, std::move(storage));
    EXPECT_EQ(expectation_digest(reused), expectation_digest(fresh));
    ASSERT_EQ(reused.frame.components.size(), 3u);
    size_t undrawn = 0;
    for (size_t i = 0; i < reused.frame.pixel_count(); ++i) {
      if (reused.frame.primitive[i] != Frame::kNoPrimitive) continue;
      ++undrawn;
      for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(reused.frame.components[k][i], 0.0f) << i;
        if (bits) {
          EXPECT_EQ(reused.allowed.components[k][i], 0.0f) << i;
        }
      }
    }
    EXPECT_GT(undrawn, 1000u);  // most of the 1,200 pixels
    EXPECT_LT(undrawn, 1200u);  // and not all
  }
}

// render_rows' bands, one after another, as one Expectation: what render() gives, if they are
// right.
Expectation stacked(const Case& c, std::optional<int> bits, int rows, int threads) {
  Expectation whole{Frame(c.fb_width, 0, c.component_count()), {}, Frame()};
  whole.frame.fragments.clear();
  if (bits) whole.allowed = Frame(c.fb_width, 0, c.component_count());
  auto append = [](Frame& to, const Frame& band) {
    to.height += band.height;
    to.primitive.insert(to.primitive.end(), band.primitive.begin(), band.primitive.end());
    to.depth.insert(to.depth.end(), band.depth.begin(), band.depth.end());
    to.fragments.insert(to.fragments.end(), band.fragments.begin(), band.fragments.end());
    for (size_t k = 0; k < to.components.size(); ++k)
      to.components[k].insert(to.components[k].end(), band.components[k].begin(),
                              band.components[k].end());
  };
  for (int y0 = 0; y0 < c.fb_height; y0 += rows) {
    const Expectation band =
        render_rows(c, Model{}, bits, threads, y0, std::min(rows, c.fb_height - y0));
    const size_t before = whole.frame.pixel_count();
    append(whole.frame, band.frame);
    if (bits) append(whole.allowed, band.allowed);
    whole.edges.insert(whole.edges.end(), band.edges.begin(), band.edges.end());
    for (Candidate k : band.candidates) {
      k.pixel += before;
      whole.candidates.push_back(k);
    }
  }
  return whole;
}

TEST(Tiles, RowsRenderedBandByBandAreTheWholeFrame) {
  std::vector<Case> cases;
  for (const auto& entry : std::filesystem::directory_iterator(GLRC_SOURCE_DIR "/cases"))
    if (entry.path().extension() == ".json") cases.push_back(casefile::load(entry.path()));
  ASSERT_GT(cases.size(), 40u);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string whole = expectation_digest(render(c, Model{}, 8, 2));
    EXPECT_EQ(expectation_digest(stacked(c, 8, 7, 2)), whole);
    EXPECT_EQ(expectation_digest(stacked(c, 8, 1 + c.fb_height / 2, 1)), whole);
    EXPECT_EQ(digest(stacked(c, std::nullopt, 5, 2).frame),
              digest(render(c, Model{}, std::nullopt, 1).frame));
  }
  const Case& c = cases.front();
  EXPECT_THROW(render_rows(c, Model{}, 8, 1, -1, 2), std::invalid_argument);
  EXPECT_THROW(render_rows(c, Model{}, 8, 1, c.fb_height - 1, 2), std::invalid_argument);
  EXPECT_EQ(render_rows(c, Model{}, 8, 1, c.fb_height, 0).frame.pixel_count(), 0u);
}

// render_frame, which `digest` hashes, leaves the edge bits out: the frame itself, fragment
// counts included, is render()'s, on any number of threads, for every committed case (shared
// edges and fans among them) and for contested overlapping triangles.
TEST(Tiles, TheFrameAloneIsRendersFrame) {
  std::vector<Case> cases;
  for (const auto& entry : std::filesystem::directory_iterator(GLRC_SOURCE_DIR "/cases"))
    if (entry.path().extension() == ".json") cases.push_back(casefile::load(entry.path()));
  ASSERT_GT(cases.size(), 40u);
  size_t fragments = 0;
  for (const Case& c : cases)
    for (int threads : {1, 3}) {
      SCOPED_TRACE(c.name + ", " + std::to_string(threads) + " threads");
      const Frame whole = render(c, Model{}, std::nullopt, threads).frame;
      const Frame alone = render_frame(c, Model{}, threads);
      EXPECT_EQ(digest(alone), digest(whole));
      EXPECT_EQ(alone.fragments, whole.fragments);
      for (uint16_t n : alone.fragments)
        fragments += n;
    }
  EXPECT_GT(fragments, 10000u);
}

}  // namespace
}  // namespace glrc::ref
