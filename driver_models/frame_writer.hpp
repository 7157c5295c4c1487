// The per-fragment end of both pipelines: depth test against the 32F depth buffer (cleared to
// 1.0), then depth, primitive id and every component written, last writer wins; every fragment,
// passing the depth test or not, is counted per pixel (Frame::fragments), as GL's counting pass
// counts them.
#pragma once

#include <cstdint>

#include "core/case.hpp"
#include "core/frame.hpp"

namespace glrc::driver_models {

// The built-ins' components of one fragment of pixel (px, py) into values (Case component
// order; varyings' components untouched): gl_FragCoord's x and y the pixel's centre under its
// layout, exact in float as both drivers compute it (softpipe's setup_fragcoord_coeff, llvmpipe's
// pixel offsets), z and w the driver's own planes of window z and 1/w_c at the pixel (`z`,
// `w`); gl_FrontFacing the driver's facing of the triangle it set up.
void write_builtins(const Case& c, int px, int py, float z, float w, bool front_facing,
                    float* values);
// Whether c writes a built-in: whether its fragments need write_builtins.
inline bool writes_builtins(const Case& c) {
  for (const Varying& v : c.varyings)
    if (v.is_builtin()) return true;
  return false;
}

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
