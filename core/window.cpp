// The window region of a case (core/case.hpp: scissor_region).
#include <algorithm>

#include "core/case.hpp"

namespace glrc {

PixelRect scissor_region(const Case& c) {
  PixelRect r{0, 0, c.fb_width - 1, c.fb_height - 1};
  if (c.scissor) {
    // In 64 bits: x + width may pass INT_MAX for a hostile wire case.
    const Scissor& s = *c.scissor;
    r.x0 = std::max(r.x0, s.x);
    r.y0 = std::max(r.y0, s.y);
    r.x1 = int(std::min<int64_t>(r.x1, int64_t(s.x) + s.width - 1));
    r.y1 = int(std::min<int64_t>(r.y1, int64_t(s.y) + s.height - 1));
  }
  return r;
}

}  // namespace glrc
