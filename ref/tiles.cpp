#include "ref/tiles.hpp"

#include <algorithm>

namespace glrc::ref {

std::vector<Tile> tiles(int y0, int y1, int threads) {
  std::vector<Tile> out;
  const int rows = y1 - y0 + 1;
  if (rows <= 0) return out;
  // Four tiles per thread balance an uneven scene; tiles of fewer than 8 rows cost more in
  // per-tile overhead (each walks every triangle's list) than they gain.
  const int count = std::clamp(std::min(4 * threads, rows / 8), 1, rows);
  for (int k = 0; k < count; ++k)
    out.push_back(
        {y0 + int(int64_t(rows) * k / count), y0 + int(int64_t(rows) * (k + 1) / count) - 1});
  return out;
}

}  // namespace glrc::ref
