// The per-fragment end of both pipelines: depth test against the 32F depth buffer (cleared to
// 1.0), then depth, primitive id and every component written, last writer wins; every fragment,
// passing the depth test or not, is counted per pixel (Frame::fragments), as GL's counting pass
// counts them.
#pragma once

#include <cstdint>

#include "core/case.hpp"
#include "core/frame.hpp"

namespace glrc::driver_models {

class FrameWriter {
 public:
  FrameWriter(Frame& frame, DepthFunc func) : frame_(frame), func_(func) {}
  // `values` holds one float per component. Both drivers compare float32 depth values
  // (llvmpipe in its fragment shader, softpipe as floats for Z32_FLOAT).
  void fragment(int x, int y, int32_t primitive, float depth, const float* values);

 private:
  Frame& frame_;
  DepthFunc func_;
};

}  // namespace glrc::driver_models
