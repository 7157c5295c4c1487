// identify, finding 5: how 24-bit depth is rounded. Window positions on a 1/64 grid and window
// depths multiples of 2^-23, w_c = 1: every GL stage before the depth plane is exact, and the
// ideal z·(2^24 - 1) at a pixel centre is a ratio of integers, against which GL's stored integer
// is round or floor.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/model.hpp"

#include "identify/probes.hpp"

namespace glrc::identify {

// Window positions on a 1/64 grid and window depths multiples of 2^-23, w_c = 1: every GL
// stage before the depth plane is exact, and the ideal z·(2^24 - 1) at a pixel centre is a
// ratio of integers.
struct DepthTriangle {
  std::array<long, 3> x{}, y{};  // window position · 64
  std::array<long, 3> z{};       // window depth · 2^23
};

struct DepthCategory {
  std::string name;
  uint64_t pixels = 0, informative = 0, round = 0, truncate = 0, neither = 0;
};

struct DepthFinding {
  std::string identified = "round";
  std::vector<DepthCategory> categories;
  DepthCategory total;
  std::vector<DepthCategory> rows() const {  // the categories, then the total
    std::vector<DepthCategory> r = categories;
    r.push_back(total);
    return r;
  }
};

// Probe of `category` (0: constant z < 0.5, 1: sloped z < 1/16, 2: sloped z < 1), drawn from
// `rnd`; appends its triangles in exact integers to `exact`.
Case depth_triangles(Random& rnd, int category, std::vector<DepthTriangle>& exact);
// Counts, per category, the covered pixels whose stored integer is round(z·(2^24 - 1)) or
// floor(z·(2^24 - 1)) of the exact depth at the pixel centre; informative pixels are those
// where the two differ (the fraction is above one half).
DepthFinding identify_depth(const std::vector<Probe>& probes,
                            const std::vector<std::vector<DepthTriangle>>& exact);

}  // namespace glrc::identify
