// The probes of identify: small cases built to tell candidate models apart, drawn on GL. Most are
// drawn in a viewport of (-64, -64, 128, 128) on a 64x64 framebuffer: there the viewport
// transform is x_w = 64·x_c with no rounding at all (a power-of-two scale, offset 0), so GL and
// the reference start from the very same window positions, and a position chosen on a fine grid
// reaches the rasterizer unchanged.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <random>
#include <stdexcept>
#include "core/case.hpp"
#include "core/frame.hpp"
#include "core/model.hpp"

#include "gl_harness/gl_harness.hpp"

namespace glrc::identify {

constexpr int kFramebuffer = 64;
constexpr double kViewportScale = 64;  // x_w = 64·x_c in the probe viewport

// GL could not draw a probe (its gl::RenderError's text): identification is impossible.
struct ProbeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Deterministic on every platform (the standard distributions are not).
class Random {
 public:
  explicit Random(uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(rng_() >> 11) * 0x1p-53; }
  int integer(int lo, int hi) { return lo + int(rng_() % uint64_t(hi - lo + 1)); }  // inclusive
  bool coin() { return (rng_() >> 63) != 0; }

 private:
  std::mt19937_64 rng_;
};

struct Point {
  double x = 0, y = 0;
};
struct FPoint {  // a window position that is a float32 by its type
  float x = 0, y = 0;
  operator Point() const { return {x, y}; }
};

// An empty case on the probe framebuffer and viewport.
Case probe_case(const std::string& name, const std::string& description);

// `v` as a float; std::logic_error when it is not one exactly (a probe built wrongly).
float exact_float(double v, const char* what);

// A vertex at window position p (each coordinate a float that x_c = x_w / 64 keeps exactly),
// window depth z_w (depth range 0..1: z_c = 2·z_w - 1, exact for the values used) and w_c = 1.
Vertex window_vertex(Point p, double z_w = 0.5, std::vector<float> values = {});

void add_triangle(Case& c, const std::array<Vertex, 3>& v);

// Cells of a square grid over the framebuffer, one probe each, so that probes never overlap.
Point cell_origin(int cell, int cell_size);

// A probe case and GL's frame of it.
struct Probe {
  Case c;
  Frame gl;
};

// GL's frame of `c`; ProbeError when GL cannot draw it.
Frame render_gl(gl::Renderer& r, const Case& c);
std::vector<Probe> render_all(gl::Renderer& r, std::vector<Case> cases);
size_t triangle_count(const std::vector<Probe>& probes);

}  // namespace glrc::identify
