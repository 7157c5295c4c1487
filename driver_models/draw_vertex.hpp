// What Mesa's draw module hands a driver's setup: vertices with their clip and window
// positions, and the interface each driver model implements to receive triangles.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/case.hpp"

namespace glrc::driver_models {

// struct vertex_header in draw_private.h, reduced to what our shaders produce.
struct DrawVertex {
  std::array<float, 4> clip{};    // clip_pos: gl_Position as the vertex shader wrote it
  std::array<float, 4> window{};  // data[pos]: x_w, y_w, z_w, 1/w_c after the viewport
  uint32_t clipmask = 0;          // bit i: outside view-volume plane i (draw_pipe_clip order)
  std::vector<float> values;      // every varying component, in Case component order
  // gl_ClipDistance then gl_CullDistance outputs (Vertex::distances): clip mask bit 6 + i is
  // clip distance i below 0 (enabled planes only); the clipper interpolates them all as a
  // perspective output.
  std::vector<float> distances;
};

// The interpolation qualifier of each varying component, in Case component order.
std::vector<Interpolation> component_interpolation(const Case& c);

// A driver's setup and rasterizer: draw calls triangle() once per triangle, in draw order.
// `primitive` is gl_PrimitiveID (the index of the case's triangle the piece came from).
class TriangleSink {
 public:
  virtual ~TriangleSink() = default;
  virtual void triangle(const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2,
                        int32_t primitive) = 0;
};

}  // namespace glrc::driver_models
