// Which triangles of a case are identical copies of an earlier one (core/case.hpp).
#include <algorithm>
#include <array>
#include <bit>
#include <numeric>

#include "core/case.hpp"
#include "core/primitive_assembly.hpp"

namespace glrc {

std::vector<int32_t> identical_triangles(const Case& c) {
  // The three clip positions' bits, in order, and the kind of primitive.
  using Key = std::array<uint32_t, 13>;
  const size_t n = c.triangles.size();
  // A case without draws has only GL_TRIANGLES triangles (kind 0).
  const std::vector<uint8_t> kinds =
      c.draws.empty() ? std::vector<uint8_t>(n, 0) : assemble(c.draws, c.provoking).kind;
  std::vector<Key> keys(n);
  for (size_t t = 0; t < n; ++t) {
    for (size_t v = 0; v < 3; ++v)
      for (size_t k = 0; k < 4; ++k)
        keys[t][v * 4 + k] = std::bit_cast<uint32_t>(c.vertices[c.triangles[t][v]].clip[k]);
    keys[t][12] = t < kinds.size() ? kinds[t] : 0;
  }
  // Sorted by key, ties by primitive: each run of equal keys starts with its first triangle.
  std::vector<int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int32_t a, int32_t b) { return keys[size_t(a)] < keys[size_t(b)]; });
  std::vector<int32_t> first(n);
  for (size_t k = 0; k < n; ++k) {
    const int32_t t = order[k];
    first[size_t(t)] =
        k > 0 && keys[size_t(order[k - 1])] == keys[size_t(t)] ? first[size_t(order[k - 1])] : t;
  }
  return first;
}

}  // namespace glrc
