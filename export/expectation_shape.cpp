#include "export/expectation_shape.hpp"

namespace glrc::reproducer {

std::string expectation_shape_error(const Case& c, const Expectation& e, const Tolerance& t) {
  const Frame& f = e.frame;
  const size_t pixels = f.pixel_count(), components = size_t(c.component_count());
  if (f.width != c.fb_width || f.height != c.fb_height || f.components.size() != components ||
      f.primitive.size() != pixels || f.depth.size() != pixels || e.edges.size() != pixels ||
      (!f.fragments.empty() && f.fragments.size() != pixels))
    return "the expectation is not of this case's framebuffer and varyings";
  for (const std::vector<float>& values : f.components)
    if (values.size() != pixels) return "the expectation's components are not the frame's size";
  if (const std::string why = e.allowance_shape_error(); !why.empty()) return why;
  // The reproducers embed the allowance at every pixel (complete_allowance).
  if (t.mode == ToleranceMode::spec && e.allowance_state() != AllowanceState::per_pixel)
    return "a spec tolerance needs the expectation's allowance at every pixel";
  for (size_t k = 0; k < e.candidates.size(); ++k) {
    const Candidate& o = e.candidates[k];
    // Primitive none: the clear value, where GL may keep nothing.
    if (o.pixel >= pixels || o.primitive < Frame::kNoPrimitive ||
        (o.primitive >= 0 && size_t(o.primitive) >= c.triangles.size()) ||
        o.values.size() != components ||
        (t.mode == ToleranceMode::spec && o.allowed.size() != components) ||
        (k > 0 && e.candidates[k - 1].pixel > o.pixel)) {
      std::string why = "depth-test candidate ";
      why += std::to_string(k);
      why += " is not one of this case's";
      return why;
    }
  }
  for (const Vertex& v : c.vertices)
    if (v.values.size() != components) return "a vertex has not every varying's components";
  for (const auto& tri : c.triangles)
    for (uint32_t i : tri)
      if (i >= c.vertices.size()) return "a triangle names a vertex past the last";
  return "";
}

}  // namespace glrc::reproducer
