#include "gl_harness/first_draw.hpp"

#include <cstdio>
#include <utility>

namespace glrc::gl {
namespace {

constexpr int kSize = 4;

std::string value_text(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(v));
  return text;
}

std::string primitive_text(int32_t p) {
  return p == Frame::kNoPrimitive ? std::string("none") : std::to_string(p);
}

}  // namespace

Case first_draw_case() {
  Case c;
  c.name = "gl_harness_first_draw";
  c.fb_width = c.fb_height = kSize;
  c.viewport = {0, 0, kSize, kSize};
  c.varyings = {Varying{"v", 1, Interpolation::flat}};
  for (auto [x, y] : {std::pair{-1.0f, -1.0f}, {3.0f, -1.0f}, {-1.0f, 3.0f}})
    c.vertices.push_back(Vertex{{x, y, 0.0f, 1.0f}, {1.0f}});
  c.triangles = {{0, 1, 2}};
  return c;
}

FirstDrawVerdict judge_first_draw(const Frame& f) {
  FirstDrawVerdict v;
  if (f.width != kSize || f.height != kSize || f.components.size() != 1 ||
      f.primitive.size() != f.pixel_count() || f.components[0].size() != f.pixel_count()) {
    v.wrong_pixels = kFirstDrawPixels;
    v.fault = "a " + std::to_string(f.width) + "x" + std::to_string(f.height) + " frame with " +
              std::to_string(f.components.size()) + " components, expected 4x4 with 1";
    return v;
  }
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t i = f.index(x, y);
      const int32_t primitive = f.primitive[i];
      const float value = f.components[0][i];
      if (primitive == 0 && value == 1.0f) continue;
      if (v.wrong_pixels++ == 0)
        v.fault = "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                  ") expected primitive 0 and flat value 1, got primitive " +
                  primitive_text(primitive) + " and value " + value_text(value);
    }
  if (v.wrong_pixels > 0)
    v.fault += " (" + std::to_string(v.wrong_pixels) + " of " + std::to_string(kFirstDrawPixels) +
               " pixels wrong)";
  return v;
}

FirstDrawChoice choose_first_draw(const FirstDrawVerdict& plain,
                                  const std::optional<FirstDrawVerdict>& with_geometry_shader) {
  FirstDrawChoice choice;
  if (plain.right()) return choice;
  const FirstDrawVerdict* gs = with_geometry_shader ? &*with_geometry_shader : nullptr;
  if (gs && gs->right()) {
    // The softpipe case (piglit's primitive-id-no-gs): a driver bug, worked around so that
    // every other case checks what it is about; reported all the same, and the cases that
    // turn work-arounds off check the feature itself.
    choice.geometry_shader = true;
    choice.warning =
        "gl_PrimitiveID read in a fragment shader without a geometry shader is wrong (the first "
        "draw, one triangle covering a 4x4 framebuffer: " +
        plain.fault +
        "); worked around: cases are drawn with a pass-through geometry shader, except those "
        "with \"work_arounds\": false";
    return choice;
  }
  choice.geometry_shader = gs && gs->wrong_pixels < plain.wrong_pixels;
  choice.warning =
      "the first draw (one triangle covering a 4x4 framebuffer) is wrong: " + plain.fault;
  if (gs)
    choice.warning += "; with a pass-through geometry shader for gl_PrimitiveID: " + gs->fault;
  choice.warning += std::string("; cases are drawn ") +
                    (choice.geometry_shader ? "with" : "without") +
                    " a geometry shader and each passes or fails on its own";
  return choice;
}

}  // namespace glrc::gl
