#include "identify/probes.hpp"

#include <fmt/core.h>

#include <stdexcept>
#include <utility>

namespace glrc::identify {

Case probe_case(const std::string& name, const std::string& description) {
  Case c;
  c.name = name;
  c.description = description;
  c.source_path = "(glrefcheck identify)";
  c.fb_width = c.fb_height = kFramebuffer;
  c.viewport = {-kFramebuffer, -kFramebuffer, 2 * kFramebuffer, 2 * kFramebuffer};
  return c;
}

float exact_float(double v, const char* what) {
  const float f = float(v);
  if (double(f) != v)
    throw std::logic_error(fmt::format("identify: inexact probe {} {:.17g}", what, v));
  return f;
}

Vertex window_vertex(Point p, double z_w, std::vector<float> values) {
  Vertex v;
  v.clip = {exact_float(p.x / kViewportScale, "x"), exact_float(p.y / kViewportScale, "y"),
            exact_float(2 * z_w - 1, "z"), 1.0f};
  v.values = std::move(values);
  return v;
}

void add_triangle(Case& c, const std::array<Vertex, 3>& v) {
  const auto first = uint32_t(c.vertices.size());
  for (const Vertex& x : v)
    c.vertices.push_back(x);
  c.triangles.push_back({first, first + 1, first + 2});
}

Point cell_origin(int cell, int cell_size) {
  const int per_row = kFramebuffer / cell_size;
  return {double(cell % per_row * cell_size), double(cell / per_row * cell_size)};
}

Frame render_gl(gl::Renderer& r, const Case& c) {
  try {
    return r.render(c);
  } catch (const gl::RenderError& e) {
    throw ProbeError(std::string("identify: GL could not render a probe: ") + e.what());
  }
}

std::vector<Probe> render_all(gl::Renderer& r, std::vector<Case> cases) {
  std::vector<Probe> probes;
  for (Case& c : cases) {
    Frame f = render_gl(r, c);
    probes.push_back({std::move(c), std::move(f)});
  }
  return probes;
}

size_t triangle_count(const std::vector<Probe>& probes) {
  size_t n = 0;
  for (const Probe& p : probes)
    n += p.c.triangles.size();
  return n;
}

}  // namespace glrc::identify
