#include "driver_models/viewport.hpp"

#include "driver_models/float_ops.hpp"

namespace glrc::driver_models {

ViewportXform viewport_xform(const Case& c) {
  ViewportXform v;
  const float x = float(c.viewport.x), y = float(c.viewport.y);
  const float half_width = 0.5f * float(c.viewport.width);
  const float half_height = 0.5f * float(c.viewport.height);
  // glDepthRange clamps to [0, 1] and stores floats.
  auto clamp01 = [](float f) { return f < 0.0f ? 0.0f : f > 1.0f ? 1.0f : f; };
  const double n = clamp01(c.depth_near), f = clamp01(c.depth_far);
  // GL_UPPER_LEFT: scale[1] = -half_height, translate[1] unchanged.
  const float scale_y = c.clip_origin == ClipOrigin::upper_left ? -half_height : half_height;
  if (c.clip_depth == ClipDepth::zero_to_one) {
    v.scale = {half_width, scale_y, float(f - n)};
    v.translate = {half_width + x, half_height + y, float(n)};
  } else {
    v.scale = {half_width, scale_y, float(0.5 * (f - n))};
    v.translate = {half_width + x, half_height + y, float(0.5 * (n + f))};
  }
  return v;
}

std::array<float, 4> window_position_llvm(const std::array<float, 4>& clip, const ViewportXform& vp,
                                          bool fma) {
  const float oow = 1.0f / clip[3];
  std::array<float, 4> w{};
  for (int i = 0; i < 3; ++i)
    w[i] = fmuladd(clip[i] * oow, vp.scale[i], vp.translate[i], fma);
  w[3] = oow;
  return w;
}

std::array<float, 4> window_position_c(const std::array<float, 4>& clip, const ViewportXform& vp) {
  const float oow = 1.0f / clip[3];
  std::array<float, 4> w{};
  for (int i = 0; i < 3; ++i)
    w[i] = clip[i] * oow * vp.scale[i] + vp.translate[i];
  w[3] = oow;
  return w;
}

uint32_t clip_mask(const std::array<float, 4>& clip, ClipDepth depth, bool clip_z) {
  const float x = clip[0], y = clip[1], z = clip[2], w = clip[3];
  uint32_t mask = 0;
  if (!(-x + w >= 0)) mask |= 1u << 0;
  if (!(x + w >= 0)) mask |= 1u << 1;
  if (!(-y + w >= 0)) mask |= 1u << 2;
  if (!(y + w >= 0)) mask |= 1u << 3;
  if (!clip_z) return mask;
  // clip_halfz (GL_ZERO_TO_ONE): plane 4 is z >= 0.
  if (!((depth == ClipDepth::zero_to_one ? z : z + w) >= 0)) mask |= 1u << 4;
  if (!(-z + w >= 0)) mask |= 1u << 5;
  return mask;
}

}  // namespace glrc::driver_models
