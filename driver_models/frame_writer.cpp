#include "driver_models/frame_writer.hpp"

namespace glrc::driver_models {

void FrameWriter::fragment(int x, int y, int32_t primitive, float depth, const float* values) {
  const size_t p = frame_.index(x, y);
  if (func_ == DepthFunc::less && !(depth < frame_.depth[p])) return;
  ++frame_.fragments[p];
  frame_.depth[p] = depth;
  frame_.primitive[p] = primitive;
  for (size_t k = 0; k < frame_.components.size(); ++k)
    frame_.components[k][p] = values[k];
}

}  // namespace glrc::driver_models
