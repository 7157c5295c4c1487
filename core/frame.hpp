// Frame: what a renderer produced, per pixel. The reference and every GL backend fill the very
// same layout, so the comparator needs to know nothing of either. Row 0 is the bottom row
// (GL window coordinates, y up).
#pragma once

#include <cstdint>
#include <vector>

namespace glrc {

struct Frame {
  static constexpr int32_t kNoPrimitive = -1;

  int width = 0, height = 0;
  std::vector<int32_t> primitive;  // gl_PrimitiveID of the covering triangle, or kNoPrimitive
  std::vector<float> depth;        // z_w; 1.0 (the clear value) where not covered
  // components[k][pixel]: varying component k (Case component order); 0 where not covered.
  std::vector<std::vector<float>> components;

  Frame() = default;
  Frame(int w, int h, int component_count)
      : width(w),
        height(h),
        primitive(size_t(w) * h, kNoPrimitive),
        depth(size_t(w) * h, 1.0f),
        components(component_count, std::vector<float>(size_t(w) * h, 0.0f)) {}

  size_t index(int x, int y) const { return size_t(y) * width + x; }
  size_t pixel_count() const { return size_t(width) * height; }
};

}  // namespace glrc
