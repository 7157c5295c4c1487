#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "core/case.hpp"

namespace glrc {

std::optional<std::string> outside_specified_range(const Case& c) {
  const std::vector<std::string> names = component_names(c);
  auto beyond = [](const std::string& what, float value) {
    char number[32];
    std::snprintf(number, sizeof number, "%g", double(value));
    return what + " = " + number +
           " is beyond 2^32, the largest magnitude GL guarantees (OpenGL 4.6 section 2.3.4.1)";
  };
  // Only what is computed on: the positions of vertices that triangles use, and the values that
  // are interpolated (flat values are copied, whatever their magnitude).
  const std::vector<int> owner = component_varying(c);
  std::vector<bool> used(c.vertices.size(), false);
  for (const auto& t : c.triangles)
    for (uint32_t v : t)
      if (v < used.size()) used[v] = true;
  for (size_t v = 0; v < c.vertices.size(); ++v) {
    if (!used[v]) continue;
    const Vertex& vertex = c.vertices[v];
    const std::string at = "vertices[" + std::to_string(v) + "].";
    for (size_t k = 0; k < 4; ++k) {
      const float x = vertex.clip[k];
      if (!(std::fabs(x) <= kSpecifiedMagnitude))
        return beyond(at + "clip[" + std::to_string(k) + "]", x);
      // A denormal position may be read as 0 (GLSL lets denormals flush), which moves the
      // vertex anywhere up to the eye: no picture is wrong then.
      if (x != 0 && std::fpclassify(x) == FP_SUBNORMAL) {
        char number[32];
        std::snprintf(number, sizeof number, "%g", double(x));
        return at + "clip[" + std::to_string(k) + "] = " + number +
               " is a denormal, which GLSL may flush to 0 (OpenGL 4.6 section 2.3.4.1)";
      }
    }
    for (size_t k = 0; k < vertex.values.size() && k < owner.size(); ++k)
      if (c.varyings[size_t(owner[k])].interpolation != Interpolation::flat &&
          !(std::fabs(vertex.values[k]) <= kSpecifiedMagnitude))
        return beyond(at + names[k], vertex.values[k]);
    // The distances as the positions: interpolated by the clipper (a difference of two near
    // FLT_MAX overflows), and compared with 0, which a flushed denormal is, whatever its sign
    // (a cull distance of -2^-149 at every vertex culls, or not).
    for (size_t k = 0; k < vertex.distances.size(); ++k) {
      const bool clip = int(k) < c.distances.clip;
      const std::string name = at + (clip ? "clip_distance[" : "cull_distance[") +
                               std::to_string(clip ? k : k - size_t(c.distances.clip)) + "]";
      const float x = vertex.distances[k];
      if (!(std::fabs(x) <= kSpecifiedMagnitude)) return beyond(name, x);
      if (x != 0 && std::fpclassify(x) == FP_SUBNORMAL) {
        char number[32];
        std::snprintf(number, sizeof number, "%g", double(x));
        return name + " = " + number +
               " is a denormal, which GLSL may flush to 0 (OpenGL 4.6 section 2.3.4.1)";
      }
    }
  }
  // The polygon offset's parameters are computed on as the positions are (m·factor overflows).
  if (const auto& o = c.polygon_offset) {
    if (!(std::fabs(o->factor) <= kSpecifiedMagnitude))
      return beyond("polygon_offset.factor", o->factor);
    if (!(std::fabs(o->units) <= kSpecifiedMagnitude))
      return beyond("polygon_offset.units", o->units);
    if (o->clamp && !(std::fabs(*o->clamp) <= kSpecifiedMagnitude))
      return beyond("polygon_offset.clamp", *o->clamp);
  }
  return std::nullopt;
}

}  // namespace glrc
