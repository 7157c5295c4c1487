#include "identify/viewport_precision.hpp"

#include <cmath>

#include "ref/reference.hpp"

namespace glrc::identify {

Case viewport_triangles(Random& rnd) {
  Case c = probe_case("identify_viewport",
                      "triangles at random float positions in a viewport of quarter-pixel bounds "
                      "(glViewportIndexedf)");
  // Every bound a quarter pixel off the whole: rounding down and to the nearest differ.
  c.viewport = Viewport{0.75f, 0.25f, float(c.fb_width) - 1.5f, float(c.fb_height) - 0.75f};
  for (int cell = 0; cell < 16; ++cell) {
    const Point o = cell_origin(cell, 16);
    std::array<Vertex, 3> v;
    for (int i = 0; i < 3; ++i) {
      // On a 1/64 pixel grid: exact in x_c = x_w / 64.
      const Point p{o.x + rnd.integer(64, 960) / 64.0, o.y + rnd.integer(64, 960) / 64.0};
      v[size_t(i)] = window_vertex(p);
    }
    add_triangle(c, v);
  }
  return c;
}

ViewportFinding identify_viewport(const Probe& p, const Model& m, int reported) {
  ViewportFinding f;
  f.available = true;
  f.reported = reported;
  const Viewport& vp = p.c.viewport;
  const auto rounded = [&](float (*round)(float)) {
    return Viewport{round(vp.x), round(vp.y), round(vp.width), round(vp.height)};
  };
  f.candidates = {{"float", vp, 0},
                  {"nearest", rounded([](float x) { return std::nearbyint(x); }), 0},
                  {"floor", rounded([](float x) { return std::floor(x); }), 0}};
  for (size_t i = 0; i < p.gl.pixel_count(); ++i)
    f.pixels += p.gl.primitive[i] >= 0;
  size_t best = 0;
  for (size_t k = 0; k < f.candidates.size(); ++k) {
    ViewportCandidate& candidate = f.candidates[k];
    Case c = p.c;
    c.viewport = candidate.viewport;
    const Frame frame = ref::render_frame(c, m);
    for (size_t i = 0; i < frame.pixel_count(); ++i)
      candidate.mismatches += frame.primitive[i] != p.gl.primitive[i];
    if (candidate.mismatches < f.candidates[best].mismatches) best = k;
  }
  f.identified = f.candidates[best].name;
  return f;
}

}  // namespace glrc::identify
