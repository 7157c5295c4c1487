#include "driver_models/frame_writer.hpp"

namespace glrc::driver_models {

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
