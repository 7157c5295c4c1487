#include "export/coverage_probes.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "export/shader_test_text.hpp"

namespace glrc::reproducer {
namespace {

// Rectangles (x, y, w, h) of pixels with equal expectation, covering exactly the pixels whose
// value is given: runs of each row, merged with identical runs of the rows above.
struct Rect {
  int x, y, w, h;
  std::pair<int, int> value;  // fragments, triangle
};
using Grid = std::vector<std::optional<std::pair<int, int>>>;

std::vector<Rect> rectangles(int width, int height, const Grid& grid) {
  std::vector<Rect> done;
  std::map<std::tuple<int, int, std::pair<int, int>>, Rect> open;  // (x, w, value) -> rect
  for (int y = 0; y < height; ++y) {
    std::map<std::tuple<int, int, std::pair<int, int>>, Rect> next;
    for (int x = 0; x < width;) {
      const auto& v = grid[size_t(y) * size_t(width) + size_t(x)];
      if (!v) {
        ++x;
        continue;
      }
      int end = x + 1;
      while (end < width && grid[size_t(y) * size_t(width) + size_t(end)] == v)
        ++end;
      const auto key = std::make_tuple(x, end - x, *v);
      auto it = open.find(key);
      if (it != open.end()) {
        Rect r = it->second;
        ++r.h;
        next.emplace(key, r);
        open.erase(it);
      } else {
        next.emplace(key, Rect{x, y, end - x, 1, *v});
      }
      x = end;
    }
    for (auto& [key, r] : open)
      done.push_back(r);
    open = std::move(next);
  }
  for (auto& [key, r] : open)
    done.push_back(r);
  std::sort(done.begin(), done.end(),
            [](const Rect& a, const Rect& b) { return std::tie(a.y, a.x) < std::tie(b.y, b.x); });
  return done;
}

struct Group {
  const char* heading;
  const char* tolerance;
  Grid grid;
  std::vector<Rect> rects;
};

// The groups of probes, as two grids or three groups.
std::vector<Group> groups_of(const Frame& f, const std::vector<Decided>& decided, bool grids) {
  std::vector<Group> groups;
  if (grids) {
    groups.push_back(
        {"# Coverage: fragments (first channel) wherever the reference decides them "
         "(the others are not compared here).\n",
         "tolerance 0.25 1e9 1e9 0.25\n",
         {},
         {}});
    groups.push_back(
        {"# Kept triangle (second channel, -1: none) wherever the reference decides "
         "it (the others are not compared here).\n",
         "tolerance 1e9 0.25 1e9 0.25\n",
         {},
         {}});
  } else {
    groups.push_back(
        {"# Coverage: fragments (first) and kept triangle (second, -1: none) where "
         "the reference decides both.\n",
         "tolerance 0.25 0.25 1e9 0.25\n",
         {},
         {}});
    groups.push_back(
        {"# Fragments only, where the kept triangle is free (an edge within the "
         "specification's freedom).\n",
         "tolerance 0.25 1e9 1e9 0.25\n",
         {},
         {}});
    groups.push_back(
        {"# Kept triangle only, where the fragment count is free (the snapping "
         "band of an outer edge).\n",
         "tolerance 1e9 0.25 1e9 0.25\n",
         {},
         {}});
  }
  for (Group& g : groups)
    g.grid.assign(f.pixel_count(), std::nullopt);
  for (size_t i = 0; i < f.pixel_count(); ++i) {
    const Decided d = decided[i];
    const int count = f.fragments.empty() ? 0 : int(f.fragments[i]), triangle = f.primitive[i];
    if (grids) {
      if (d.fragments) groups[0].grid[i] = std::pair{count, 0};
      if (d.primitive) groups[1].grid[i] = std::pair{0, triangle};
    } else {
      const int group = d.fragments && d.primitive ? 0 : d.fragments ? 1 : d.primitive ? 2 : -1;
      if (group >= 0) groups[size_t(group)].grid[i] = std::pair{count, triangle};
    }
  }
  for (Group& g : groups)
    g.rects = rectangles(f.width, f.height, g.grid);
  return groups;
}

size_t probes_of(const std::vector<Group>& groups) {
  size_t n = 0;
  for (const Group& g : groups)
    n += g.rects.size();
  return n;
}

}  // namespace

CoverageProbes coverage_probes(const Frame& f, const std::vector<Decided>& decided) {
  std::vector<Group> groups = groups_of(f, decided, false);
  if (std::vector<Group> other = groups_of(f, decided, true); probes_of(other) < probes_of(groups))
    groups = std::move(other);
  CoverageProbes out;
  for (const Decided& d : decided)
    if (d.fragments || d.primitive) ++out.pixels_decided;
  for (const Group& g : groups) {
    if (g.rects.empty()) continue;
    out.text += "\n";
    out.text += g.heading;
    out.text += g.tolerance;
    for (const Rect& r : g.rects) {
      out.text +=
          cat("probe rect rgba (", std::to_string(r.x), ", ", std::to_string(r.y), ", ",
              std::to_string(r.w), ", ", std::to_string(r.h), ") (", std::to_string(r.value.first),
              ", ", std::to_string(r.value.second), ", 0, 1)\n");
      ++out.probes;
    }
  }
  return out;
}

}  // namespace glrc::reproducer
