#include "driver_models/frame_writer.hpp"

namespace glrc::driver_models {

void write_builtins(const Case& c, int px, int py, float z, float w, bool front_facing,
                    float* values) {
  size_t k = 0;
  for (const Varying& v : c.varyings) {
    if (v.builtin == Builtin::front_facing) {
      values[k] = front_facing ? 1.0f : 0.0f;
    } else if (v.builtin == Builtin::frag_coord) {
      const float half = v.layout.pixel_center_integer ? 0.0f : 0.5f;
      values[k] = float(px) + half;
      values[k + 1] = v.layout.origin_upper_left ? float(c.fb_height) - float(py) - (1.0f - half)
                                                 : float(py) + half;
      values[k + 2] = z;
      values[k + 3] = w;
    }
    k += size_t(v.size);
  }
}

void FrameWriter::fragment(int x, int y, int32_t primitive, float depth, const float* values) {
  const size_t p = frame_.index(x, y);
  ++frame_.fragments[p];  // every fragment, as GL's counting pass counts them (core/frame.hpp)
  if (!depth_test(func_, depth, frame_.depth[p])) return;
  frame_.depth[p] = depth;
  frame_.primitive[p] = primitive;
  for (size_t k = 0; k < frame_.components.size(); ++k)
    frame_.components[k][p] = values[k];
}

}  // namespace glrc::driver_models
