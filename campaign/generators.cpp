// The generators of generators.hpp. Positions are chosen in window coordinates (pixels) and
// turned into clip coordinates for the case's viewport, so that sizes, slivers, rim steps and
// pixel centres are what they say; values are rounded to float32 once, from doubles computed
// with +, -, * and / only (this folder is compiled with -ffp-contract=off), so every machine
// makes the same bits.
#include "campaign/generators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "campaign/random.hpp"
#include "casefile/transform.hpp"
#include "core/primitive_assembly.hpp"

namespace glrc::campaign {
namespace {

void set_framebuffer(Case& c, int width, int height) {
  c.fb_width = width, c.fb_height = height;
  c.viewport = {0, 0, width, height};
}

// The clip coordinates of window point (x_w, y_w) at NDC depth z_n with w_c = w, for the case's
// viewport: the inverse of the viewport transform, scaled by w.
std::array<float, 4> clip_at(const Case& c, double x_w, double y_w, double z_n, double w) {
  const double x_n = 2 * (x_w - c.viewport.x) / c.viewport.width - 1;
  const double y_n = 2 * (y_w - c.viewport.y) / c.viewport.height - 1;
  return {float(x_n * w), float(y_n * w), float(z_n * w), float(w)};
}

int largest_exponent_below(double x) {  // the e with 2^e <= x < 2^(e+1), x >= 1
  int e = 0;
  for (double p = 2; p <= x; p *= 2)
    ++e;
  return e;
}

double pixel_centre(double x) {
  return std::floor(x) + 0.5;
}

// A varying named v<k>.
void add_varying(Case& c, int size, Interpolation interpolation) {
  // Appended, not "v" + std::to_string(...): GCC 12 at -O3 reports a false -Wrestrict in
  // operator+ on a literal (../shared/DESIGN.md), which would stop a Release -Werror build.
  std::string name = "v";
  name += std::to_string(c.varyings.size());
  c.varyings.push_back({name, size, interpolation});
}
Interpolation any_interpolation(Random& r) {
  return Interpolation(r.below(3));  // smooth, flat, noperspective
}

// Every vertex's values: `value(r, component)` for each component of each varying.
template <class Value>
void fill_values(Case& c, Random& r, Value value) {
  const int n = c.component_count();
  for (Vertex& v : c.vertices) {
    v.values.resize(size_t(n));
    for (int k = 0; k < n; ++k)
      v.values[size_t(k)] = value(r, k);
  }
}
float moderate(Random& r) {
  return float(r.uniform(-8, 8));
}

void add_triangle(Case& c, const std::array<std::array<float, 4>, 3>& clip) {
  const auto first = uint32_t(c.vertices.size());
  for (const auto& p : clip)
    c.vertices.push_back({p, {}});
  c.triangles.push_back({first, first + 1, first + 2});
}

// w_c of one vertex: 1 (affine) or spread over four binades (perspective).
double some_w(Random& r, bool perspective) {
  return perspective ? r.binades(-2, 1) : 1.0;
}

// Every random draw of these generators is its own statement, in a fixed order: the order in
// which a compiler evaluates function arguments or the operands of * is unspecified, so
// f(r.uniform(..), r.uniform(..)) could give GCC and Clang builds different cases for one seed.

// A framebuffer (and viewport) of width in [w0, w1] and height in [h0, h1], the height drawn
// first.
void set_framebuffer_drawn(Case& c, Random& r, int w0, int w1, int h0, int h1) {
  const int height = r.between(h0, h1);
  const int width = r.between(w0, w1);
  set_framebuffer(c, width, height);
}

// A vertex anywhere within `margin` viewports of the viewport, z_n within ±depth, w from
// some_w; drawn w, z_n, y, then x.
std::array<float, 4> random_clip(const Case& c, Random& r, double margin, double depth,
                                 bool perspective) {
  const double vw = c.viewport.width, vh = c.viewport.height;
  const double w = some_w(r, perspective);
  const double z = r.uniform(-depth, depth);
  const double y = r.uniform(-margin * vh, (1 + margin) * vh);
  const double x = r.uniform(-margin * vw, (1 + margin) * vw);
  return clip_at(c, x, y, z, w);
}

Case sizes(Random& r) {
  Case c;
  const uint64_t shape = r.below(10);
  if (shape < 6) {
    set_framebuffer_drawn(c, r, 8, 128, 8, 128);
  } else if (shape < 8) {
    const int a = r.between(128, 512), b = r.between(8, 64);
    r.chance(0.5) ? set_framebuffer(c, a, b) : set_framebuffer(c, b, a);
  } else {  // far from the window origin: a long, narrow framebuffer
    const int a = r.between(1024, 4096), b = r.between(1, 16);
    r.chance(0.5) ? set_framebuffer(c, a, b) : set_framebuffer(c, b, a);
  }
  const double vw = c.viewport.width, vh = c.viewport.height;
  const int top = largest_exponent_below(4 * std::max(vw, vh));
  // 1 to 2,047 triangles, log-distributed: most cases have a few, some a crowd (with the depth
  // test, overlapping ones), and checking many at once keeps the campaign fast.
  const int count = int(r.binades(0, 10));
  const bool perspective = r.chance(0.4);
  // A crowd's triangles stay below 64 pixels, so that a case costs milliseconds, not seconds.
  const int largest = count > 16 ? std::min(top, 5) : top;
  for (int t = 0; t < count; ++t) {
    const double size = r.binades(-5, largest);  // pixels
    double cx = r.uniform(0, vw), cy = r.uniform(0, vh);
    if (r.chance(0.2)) cx = r.uniform(-0.25 * vw, 1.25 * vw), cy = r.uniform(-0.25 * vh, 1.25 * vh);
    std::array<std::array<double, 2>, 3> p;
    for (auto& q : p)
      q = {cx + size * r.uniform(-1, 1), cy + size * r.uniform(-1, 1)};
    if (r.chance(0.3)) {  // a sliver: the third vertex just off the line through the others
      const double t01 = r.uniform(-0.5, 1.5), tiny = r.binades(-24, -4);
      const double off = size * tiny * r.sign();
      const double dx = p[1][0] - p[0][0], dy = p[1][1] - p[0][1];
      p[2] = {p[0][0] + t01 * dx - off * dy, p[0][1] + t01 * dy + off * dx};
    }
    if (r.chance(0.2))  // on the 1/256 grid, as snapped positions are
      for (auto& q : p)
        q = {std::floor(q[0] * 256) / 256, std::floor(q[1] * 256) / 256};
    std::array<std::array<float, 4>, 3> clip;
    for (size_t k = 0; k < 3; ++k) {
      const double w = some_w(r, perspective), z = r.uniform(-0.99, 0.99);
      clip[k] = clip_at(c, p[k][0], p[k][1], z, w);
    }
    add_triangle(c, clip);
  }
  if (r.chance(0.3)) c.depth_func = DepthFunc::less;
  if (r.chance(0.8)) add_varying(c, 2, Interpolation::smooth);
  fill_values(c, r, [](Random& rr, int) { return float(rr.unit()); });
  return c;
}

Case clip(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 16, 96, 16, 96);
  const int count = r.between(1, 4);
  for (int t = 0; t < count; ++t) {
    std::array<std::array<float, 4>, 3> v;
    for (auto& p : v) {
      const uint64_t kind = r.below(10);
      double w = r.binades(-10, 10);
      if (kind >= 6 && kind < 8) w = -r.binades(-3, 3);
      if (kind == 8) {  // tiny, either side of the eye
        const double tiny = r.binades(-40, -20);
        w = tiny * r.sign();
      }
      p[3] = float(w);
      for (size_t axis = 0; axis < 3; ++axis) {
        double n;  // normalized device coordinate
        switch (r.below(8)) {
          case 0:
            n = 1;
            break;  // on the plane
          case 1:
            n = -1;
            break;
          case 2: {  // near it
            const double side = r.sign(), toward = r.sign();
            n = side * (1 + toward * r.binades(-24, -1) / 2);
            break;
          }
          case 3:
            n = r.uniform(-40, 40);
            break;
          default:
            n = r.uniform(-1.5, 1.5);
            break;
        }
        p[axis] = float(n * double(p[3]));
      }
    }
    if (r.chance(0.5)) {  // an edge on a clip plane: two vertices with x, y or z = ±w exactly
      const auto axis = size_t(r.below(3));
      const float s = float(r.sign());
      const auto skip = size_t(r.below(3));
      for (size_t k = 0; k < 3; ++k)
        if (k != skip) v[k][axis] = s * v[k][3];
    }
    add_triangle(c, v);
  }
  // 1 to 3 vec2 varyings of any qualifiers: 39 layouts, each compiled once per worker (sizes
  // are the attributes generator's business).
  const int varyings = r.between(1, 3);
  for (int k = 0; k < varyings; ++k)
    add_varying(c, 2, any_interpolation(r));
  fill_values(c, r, [](Random& rr, int) { return moderate(rr); });
  return c;
}

// A point of a circle: (cx, cy) + radius · (cos, sin)(degrees), from sincos_degrees (+, -, *,
// /, sqrt only: the same bits everywhere).
std::array<double, 2> on_circle(double cx, double cy, double radius, double degrees) {
  double s = 0, co = 0;
  casefile::sincos_degrees(degrees, s, co);
  return {cx + radius * co, cy + radius * s};
}

Case mesh(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 24, 96, 24, 96);
  const double vw = c.viewport.width, vh = c.viewport.height;
  // w over the mesh: 1, or an affine function of the window position (a tilted plane), so a
  // shared vertex keeps one w and the mesh stays watertight in clip space.
  const bool perspective = r.chance(0.4);
  const double wa = r.uniform(-0.5, 0.5) / vw, wb = r.uniform(-0.5, 0.5) / vh;
  const double za = r.uniform(-0.9, 0.9) / vw, zb = r.uniform(-0.9, 0.9) / vh;
  auto vertex = [&](double x, double y) {
    const double w = perspective ? 1.5 + wa * x + wb * y : 1.0;
    c.vertices.push_back({clip_at(c, x, y, za * (x - vw / 2) + zb * (y - vh / 2), w), {}});
    return uint32_t(c.vertices.size() - 1);
  };
  const uint64_t kind = r.below(4);
  if (kind < 2) {  // a fan around a random centre
    double cx = r.uniform(0, vw), cy = r.uniform(0, vh);
    if (r.chance(0.3)) cx = pixel_centre(cx), cy = pixel_centre(cy);
    const bool enclosing = kind == 1;  // piglit's overdraw fan: the rim outside the window
    const double radius = enclosing ? 1.5 * std::max(vw, vh) + r.uniform(0, vw)
                                    : r.binades(1, largest_exponent_below(std::max(vw, vh)));
    const double step = r.binades(-3, 0);  // rim step, pixels: sub-pixel
    const double arc = r.chance(0.3) && !enclosing ? r.uniform(30, 360) : 360;
    const int n = std::clamp(int(arc / 360 * 6.2832 * radius / step), 3, 3000);
    const uint32_t centre = vertex(cx, cy);
    const double turn = r.uniform(0, 360);
    uint32_t first = 0, previous = 0;
    for (int k = 0; k <= n; ++k) {
      uint32_t here;
      if (k == n && arc == 360) {
        here = first;
      } else {
        const auto p = on_circle(cx, cy, radius, turn + arc * k / n);
        here = vertex(p[0], p[1]);
      }
      if (k == 0) first = here;
      if (k > 0) c.triangles.push_back({centre, previous, here});
      previous = here;
    }
  } else {  // a grid: jittered, or its vertices on pixel centres
    const bool centres = kind == 3;
    const int step = r.between(1, 6);
    const int gx = centres ? std::max(1, int(vw - 1) / step) : r.between(2, 24);
    const int gy = centres ? std::max(1, int(vh - 1) / step) : r.between(2, 24);
    const double jitter = centres ? 0 : r.uniform(0, 0.45);
    std::vector<uint32_t> at;
    for (int j = 0; j <= gy; ++j)
      for (int i = 0; i <= gx; ++i) {
        double x, y;
        if (centres) {
          x = 0.5 + i * step, y = 0.5 + j * step;
        } else {
          const bool inner_x = i > 0 && i<gx, inner_y = j> 0 && j < gy;
          x = vw * (i + (inner_x ? jitter * r.uniform(-1, 1) : 0)) / gx;
          y = vh * (j + (inner_y ? jitter * r.uniform(-1, 1) : 0)) / gy;
        }
        at.push_back(vertex(x, y));
      }
    for (int j = 0; j < gy; ++j)
      for (int i = 0; i < gx; ++i) {
        const uint32_t a = at[size_t(j * (gx + 1) + i)], b = a + 1;
        const uint32_t d = at[size_t((j + 1) * (gx + 1) + i)], e = d + 1;
        if (r.chance(0.5)) {
          c.triangles.push_back({a, b, e}), c.triangles.push_back({a, e, d});
        } else {
          c.triangles.push_back({a, b, d}), c.triangles.push_back({b, e, d});
        }
      }
  }
  if (r.chance(0.7)) add_varying(c, 2, Interpolation::smooth);
  fill_values(c, r, [](Random& rr, int) { return float(rr.unit()); });
  return c;
}

Case attributes(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 16, 64, 16, 64);
  const bool perspective = r.chance(0.5);
  const int count = r.between(1, 3);
  for (int t = 0; t < count; ++t) {
    std::array<std::array<float, 4>, 3> v;
    for (auto& p : v)
      p = random_clip(c, r, 0.2, 0.9, perspective);
    add_triangle(c, v);
  }
  // The varyings' layout from a menu of 24 (1, 2, 4 or 7 varyings; all vec4 or sizes 1 to 4
  // in turn; qualifiers in turn from a random one): every qualifier and size still comes, and
  // a worker compiles each layout's shaders once, not once per case (compiling took four
  // fifths of a campaign of these).
  static constexpr int kCounts[] = {1, 2, 4, 7};
  const int varyings = kCounts[r.below(4)];
  const bool vec4 = r.chance(0.5);
  const auto first = uint64_t(r.below(3));
  for (int k = 0; k < varyings; ++k)
    add_varying(c, vec4 ? 4 : 1 + k % 4, Interpolation((first + uint64_t(k)) % 3));
  // Per component, a magnitude from 2^-100 (about 1e-30) to 2^100 (about 1e30), each vertex's
  // value within a few binades of it, either sign: mixed magnitudes within one vector.
  std::vector<int> exponent(size_t(c.component_count()));
  for (int& e : exponent)
    e = r.between(-100, 100);
  fill_values(c, r, [&](Random& rr, int k) {
    const uint64_t kind = rr.below(20);
    if (kind == 0) return 0.0f;
    if (kind == 1) {  // subnormal
      const double sign = rr.sign();
      return float(sign * rr.binades(-149, -127));
    }
    const int e = exponent[size_t(k)] + rr.between(-3, 3);
    const double sign = rr.sign();
    return float(sign * rr.binades(e, e));
  });
  return c;
}

Case states(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 16, 200, 16, 200);
  if (r.chance(0.7)) {
    c.viewport.x = r.between(0, c.fb_width - 1);
    c.viewport.y = r.between(0, c.fb_height - 1);
    c.viewport.width = r.between(1, c.fb_width - c.viewport.x);
    c.viewport.height = r.between(1, c.fb_height - c.viewport.y);
  }
  c.cull = CullFace(r.below(4));
  c.front_face = FrontFace(r.below(2));
  c.provoking = ProvokingVertex(r.below(2));
  c.depth_func = DepthFunc(r.below(2));
  c.depth_near = float(r.unit()), c.depth_far = float(r.unit());
  if (r.chance(0.3)) c.depth_near = 0, c.depth_far = 1;
  const bool perspective = r.chance(0.4);
  const int count = r.between(2, 8);
  for (int t = 0; t < count; ++t) {
    std::array<std::array<float, 4>, 3> v;
    for (auto& p : v)
      p = random_clip(c, r, 0.3, 1.2, perspective);
    add_triangle(c, v);
  }
  add_varying(c, 2, Interpolation::flat);
  add_varying(c, 1, r.chance(0.5) ? Interpolation::smooth : Interpolation::noperspective);
  fill_values(c, r, [](Random& rr, int) { return moderate(rr); });
  return c;
}

// The dense generator's size classes, in pixels: the sizes at which drivers change rasterizer
// paths (llvmpipe's 4x4, 16x16 and 64x64 blocks among them) each get shared edges.
enum class SizeClass { tiny, small, medium, large };
SizeClass any_size_class(Random& r) {
  return SizeClass(r.below(4));
}
double size_in(Random& r, SizeClass size) {
  switch (size) {
    case SizeClass::tiny:
      return r.binades(-4, -1);  // 1/16 to 1 pixel: sub-pixel
    case SizeClass::small:
      return r.uniform(1, 4);
    case SizeClass::medium:
      return r.uniform(16, 64);
    case SizeClass::large:
      break;
  }
  return r.uniform(64, 384);
}

// w_c of one vertex of a dense scene: within [0.2, 3.2], the range of the clip-heavy scenes
// that showed issue 44's false failures, so noperspective stays loadable everywhere.
double dense_w(Random& r) {
  return r.uniform(0.2, 3.2);
}

// Three window points around (cx, cy), at radii within [0.4, 1] of `size`, a third of a turn
// apart give or take 25 degrees: no two are half a turn apart, so the triangle contains the
// centre, and triangles made this way around one centre overlap there.
std::array<std::array<double, 2>, 3> around(Random& r, double cx, double cy, double size) {
  const double turn = r.uniform(0, 360);
  std::array<std::array<double, 2>, 3> p;
  for (int k = 0; k < 3; ++k) {
    const double radius = size * r.uniform(0.4, 1);
    const double jitter = r.uniform(-25, 25);
    p[size_t(k)] = on_circle(cx, cy, radius, turn + 120 * k + jitter);
  }
  return p;
}

double on_grid(double x, double units) {
  return std::floor(x * units + 0.5) / units;
}

// A depth plane z_c = a·x_c + b·y_c + c·w_c, homogeneous, so that every point on it has z_n =
// a·x_n + b·y_n + c: two triangles of its points lie in one depth plane in the window, however
// the implementation interpolates, and so contest every pixel they share. Every number is on a
// grid that keeps the plane exact in float32: a, b, c multiples of 1/64 (|a|, |b| <= 1/4, |c|
// <= 25/64), x_n and y_n of 2^-10 (|x_n|, |y_n| <= 3), w_c of 1/8 (2/8 to 25/8); x_c then
// has at most 17 significant bits and z_c is a multiple of 2^-19 below 2^3, so computing z_c
// rounds nothing.
struct DepthPlane {
  double a = 0, b = 0, c = 0;
};
DepthPlane any_depth_plane(Random& r) {
  DepthPlane p;
  if (r.chance(0.7)) {  // else parallel to the window: equal z_n at every vertex
    p.a = r.between(-16, 16) / 64.0;
    p.b = r.between(-16, 16) / 64.0;
  }
  p.c = r.between(-25, 25) / 64.0;
  return p;
}
// The point of `plane` nearest window point (x_w, y_w) on the grids, with w_c = w (a multiple
// of 1/8).
std::array<float, 4> on_plane(const Case& c, const DepthPlane& plane, double x_w, double y_w,
                              double w) {
  const double x_n =
      std::clamp(on_grid(2 * (x_w - c.viewport.x) / c.viewport.width - 1, 1024), -3.0, 3.0);
  const double y_n =
      std::clamp(on_grid(2 * (y_w - c.viewport.y) / c.viewport.height - 1, 1024), -3.0, 3.0);
  const double x_c = x_n * w, y_c = y_n * w;
  const double z_c = plane.a * x_c + plane.b * y_c + plane.c * w;
  return {float(x_c), float(y_c), float(z_c), float(w)};
}

// One float `steps` ulps from x, towards `direction`'s sign.
float ulps_away(float x, int steps, double direction) {
  for (int k = 0; k < steps; ++k)
    x = std::nextafter(x, direction > 0 ? INFINITY : -INFINITY);
  return x;
}

// The triangles of a dense scene, and the nearer triangles still to come over its pairs.
struct DenseScene {
  Case& c;
  std::vector<std::array<std::array<float, 4>, 3>> covers;

  int triangles() const { return int(c.triangles.size() + covers.size()); }
  uint32_t vertex(const std::array<float, 4>& clip) {
    c.vertices.push_back({clip, {}});
    return uint32_t(c.vertices.size() - 1);
  }
};

// Two different triangles of one depth plane overlapping around a centre, the second one's
// z_c moved `ulps` ulps up or down at each vertex (0: exactly on the plane; a z_c of 0 stays,
// since a denormal beside it is outside GL's specified range), and then, later in the scene, a
// triangle clearly nearer over the centre, which hides their depth contest there: issue 44's
// smallest false failure, two triangles in one depth plane and a nearer one over both.
void coplanar_pair(DenseScene& s, Random& r, int ulps) {
  const Case& c = s.c;
  const double vw = c.viewport.width, vh = c.viewport.height;
  const SizeClass size = SizeClass(r.between(1, 3));  // sub-pixel pairs rarely share a centre
  const double extent = size_in(r, size);
  const double cx = r.uniform(0, vw), cy = r.uniform(0, vh);
  const DepthPlane plane = any_depth_plane(r);
  const bool perspective = r.chance(0.6);
  double nearest = INFINITY;  // the least z_n of the pair's vertices
  for (int t = 0; t < 2; ++t) {
    const auto p = around(r, cx, cy, extent);
    std::array<std::array<float, 4>, 3> clip;
    for (size_t k = 0; k < 3; ++k) {
      const double w = perspective ? r.between(2, 25) / 8.0 : 1.0;
      clip[k] = on_plane(c, plane, p[k][0], p[k][1], w);
      if (t == 1 && ulps > 0) {
        const double direction = r.sign();
        if (clip[k][2] != 0) clip[k][2] = ulps_away(clip[k][2], ulps, direction);
      }
      nearest = std::min(nearest, double(clip[k][2]) / double(clip[k][3]));
    }
    add_triangle(s.c, clip);
  }
  // Clearly nearer than the pair wherever they meet: a constant z_n below its least vertex
  // depth (the least over a triangle is at a vertex), by 0.01 to 0.2, and above -1 while the
  // pair's nearest vertex is, so the near plane leaves it.
  const double margin = r.uniform(0.01, 0.2);
  const double z = std::max(nearest - margin, (nearest - 1) / 2);
  const double cover_extent = size_in(r, SizeClass(r.between(1, 3)));
  const auto p = around(r, cx, cy, cover_extent);
  std::array<std::array<float, 4>, 3> cover;
  for (size_t k = 0; k < 3; ++k) {
    const double w = dense_w(r);
    cover[k] = clip_at(c, p[k][0], p[k][1], z, w);
  }
  s.covers.push_back(cover);
}

// A bitwise-identical copy of an earlier triangle: the same clip positions in the same order,
// new vertices with their own values. Mostly one of the last few, which nothing has hidden yet.
void identical_copy(DenseScene& s, Random& r) {
  const auto n = uint64_t(s.c.triangles.size());
  const uint64_t t = r.chance(0.5) ? n - 1 - r.below(std::min<uint64_t>(n, 8)) : r.below(n);
  const auto original = s.c.triangles[t];
  std::array<std::array<float, 4>, 3> clip;
  for (size_t k = 0; k < 3; ++k)
    clip[k] = s.c.vertices[original[k]].clip;
  add_triangle(s.c, clip);
}

// z_n over a fan or strip: affine in the window position around (cx, cy), from -1.1 to 1.1 at
// the centre (so some cross the near or far plane), changing by up to 0.5 over `extent`.
struct DepthSlope {
  double z0, zx, zy, cx, cy;
  double at(double x, double y) const { return z0 + zx * (x - cx) + zy * (y - cy); }
};
DepthSlope any_slope(Random& r, double cx, double cy, double extent) {
  DepthSlope d{0, 0, 0, cx, cy};
  d.z0 = r.uniform(-1.1, 1.1);
  d.zx = r.uniform(-0.5, 0.5) / extent;
  d.zy = r.uniform(-0.5, 0.5) / extent;
  return d;
}

// A fan of up to `room` triangles of one size class around a centre in the viewport: every
// rim vertex but the ends shared by two triangles, the centre by all, by index.
void fan(DenseScene& s, Random& r, int room) {
  const Case& c = s.c;
  const double vw = c.viewport.width, vh = c.viewport.height;
  const double radius = size_in(r, any_size_class(r));
  const double cx = r.uniform(0, vw), cy = r.uniform(0, vh);
  const DepthSlope depth = any_slope(r, cx, cy, radius);
  const bool perspective = r.chance(0.6);
  const int n = r.between(2, std::min(room, 16));
  const bool closed = n >= 3 && r.chance(0.5);
  const double arc = closed ? 360 : r.uniform(30, 300);
  const double turn = r.uniform(0, 360);
  auto vertex = [&](double x, double y) {
    const double w = perspective ? dense_w(r) : 1.0;
    return s.vertex(clip_at(c, x, y, depth.at(x, y), w));
  };
  const uint32_t centre = vertex(cx, cy);
  uint32_t first = 0, previous = 0;
  for (int k = 0; k <= n; ++k) {
    uint32_t here;
    if (k == n && closed) {
      here = first;
    } else {
      const auto p = on_circle(cx, cy, radius, turn + arc * k / n);
      here = vertex(p[0], p[1]);
    }
    if (k == 0) first = here;
    if (k > 0) s.c.triangles.push_back({centre, previous, here});
    previous = here;
  }
}

// A strip drawn as a triangle list, up to `room` triangles of one size class: two rows of
// vertices along a random direction, each inner vertex shared by three triangles, by index.
void strip(DenseScene& s, Random& r, int room) {
  const Case& c = s.c;
  const double vw = c.viewport.width, vh = c.viewport.height;
  const double step = size_in(r, any_size_class(r));
  const double width = step * r.uniform(0.5, 1.5);
  const double x0 = r.uniform(0, vw), y0 = r.uniform(0, vh);
  const int segments = r.between(1, std::min(room / 2, 16));
  const DepthSlope depth = any_slope(r, x0, y0, step * segments);
  const bool perspective = r.chance(0.6);
  double dy = 0, dx = 0;
  casefile::sincos_degrees(r.uniform(0, 360), dy, dx);
  auto vertex = [&](double along, double across) {
    const double x = x0 + along * dx - across * dy, y = y0 + along * dy + across * dx;
    const double w = perspective ? dense_w(r) : 1.0;
    return s.vertex(clip_at(c, x, y, depth.at(x, y), w));
  };
  uint32_t a = vertex(0, 0);
  const double shift = r.uniform(-0.3, 0.3);
  uint32_t b = vertex(shift * step, width);
  for (int k = 1; k <= segments; ++k) {
    const uint32_t next_a = vertex(k * step, 0);
    const double next_shift = r.uniform(-0.3, 0.3);
    const uint32_t next_b = vertex((k + next_shift) * step, width);
    s.c.triangles.push_back({a, b, next_a});
    s.c.triangles.push_back({next_a, b, next_b});
    a = next_a, b = next_b;
  }
}

// One triangle of issue 44's clip-heavy scenes: x_c, y_c within ±3 w_c, z_c within ±1.2 w_c.
void clip_heavy(DenseScene& s, Random& r) {
  std::array<std::array<float, 4>, 3> clip;
  for (auto& p : clip) {
    const double w = dense_w(r);
    const double z = r.uniform(-1.2, 1.2) * w;
    const double y = r.uniform(-3, 3) * w;
    const double x = r.uniform(-3, 3) * w;
    p = {float(x), float(y), float(z), float(w)};
  }
  add_triangle(s.c, clip);
}

// One triangle of a size class near the viewport (a quarter of it beyond each side), each
// vertex with its own z_n within ±1.2 and w_c: clipped by the near or far plane at times.
void loose(DenseScene& s, Random& r) {
  const Case& c = s.c;
  const double vw = c.viewport.width, vh = c.viewport.height;
  const double size = size_in(r, any_size_class(r));
  const double cx = r.uniform(-0.25 * vw, 1.25 * vw), cy = r.uniform(-0.25 * vh, 1.25 * vh);
  std::array<std::array<float, 4>, 3> clip;
  for (auto& p : clip) {
    const double x = cx + size * r.uniform(-1, 1);
    const double y = cy + size * r.uniform(-1, 1);
    const double z = r.uniform(-1.2, 1.2);
    const double w = dense_w(r);
    p = clip_at(c, x, y, z, w);
  }
  add_triangle(s.c, clip);
}

Case dense(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 64, 512, 64, 512);
  c.depth_func = DepthFunc::less;
  const int count = r.between(100, 800);
  DenseScene s{c, {}};
  while (s.triangles() < count) {
    // The pairs' nearer triangles come after a random number of others.
    while (!s.covers.empty() && r.chance(0.5)) {
      add_triangle(c, s.covers.front());
      s.covers.erase(s.covers.begin());
    }
    const int room = count - s.triangles();
    uint64_t kind = r.below(20);
    // A pair and its cover take three triangles, a copy an earlier one; else a loose one.
    if (room < 3 || (kind >= 7 && kind < 9 && c.triangles.empty())) kind = 19;
    if (kind < 5) {
      coplanar_pair(s, r, 0);
    } else if (kind < 7) {
      coplanar_pair(s, r, r.between(1, 4));
    } else if (kind < 9) {
      identical_copy(s, r);
    } else if (kind < 13) {
      fan(s, r, room);
    } else if (kind < 16) {
      strip(s, r, room);
    } else if (kind < 18) {
      clip_heavy(s, r);
    } else {
      loose(s, r);
    }
  }
  for (const auto& cover : s.covers)
    add_triangle(c, cover);
  add_varying(c, 2, any_interpolation(r));
  if (r.chance(0.5)) add_varying(c, 1, any_interpolation(r));
  fill_values(c, r, [](Random& rr, int) { return moderate(rr); });
  return c;
}

// One random draw over vertices [base, base + n): a list, strip or fan; glDrawArrays or
// glDrawElements of 8-, 16- or 32-bit indices, shuffled a little (repeats make degenerate
// triangles), with primitive restart (the fixed index or glPrimitiveRestartIndex) cutting it
// into several primitives now and then.
Draw random_draw(Random& r, uint32_t base, uint32_t n) {
  Draw d;
  d.mode = PrimitiveMode(r.below(3));
  if (r.chance(0.25)) {
    d.first = base, d.count = n;
    return d;
  }
  // 8-bit indices only while every vertex index is below 255, the fixed restart index.
  d.index_type = base + n > 255 ? IndexType(2 + r.below(2)) : IndexType(1 + r.below(3));
  for (uint32_t k = 0; k < n; ++k)
    d.indices.push_back(base + (r.chance(0.1) ? uint32_t(r.below(n)) : k));
  if (r.chance(0.5)) {
    d.restart = r.chance(0.5) ? Restart::fixed_index : Restart::index;
    if (d.restart == Restart::index)
      d.restart_index = base + n + uint32_t(r.below(max_index(d.index_type) - base - n + 1));
    const int cuts = r.between(1, 3);
    for (int k = 0; k < cuts; ++k) {
      const size_t at = size_t(r.below(d.indices.size() + 1));
      d.indices.insert(d.indices.begin() + ptrdiff_t(at), d.restart_value());
    }
  }
  return d;
}

// Strips, fans and lists in one to four draws: array and indexed draws with every index type,
// primitive restart, degenerate triangles, both provoking-vertex conventions, culling, and
// vertices beyond the x, y, near and far planes; flat varyings always (the provoking vertex),
// smooth ones, and noperspective where nothing is clipped (clipped noperspective varyings hit a
// known clipper bug, cases/known-failures.txt, which the clip generator already reaches).
// A built-in appended to c's varyings, its components 0 in every vertex (core/case.hpp).
void add_builtin(Case& c, const Varying& v) {
  c.varyings.push_back(v);
  for (Vertex& vertex : c.vertices)
    vertex.values.insert(vertex.values.end(), size_t(v.size), 0.0f);
}

Case assembly(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 16, 128, 16, 128);
  c.provoking = ProvokingVertex(r.below(2));
  c.cull = r.chance(0.3) ? CullFace(r.below(4)) : CullFace::none;
  c.front_face = FrontFace(r.below(2));
  const bool perspective = r.chance(0.6);
  const double margin = r.chance(0.4) ? 0.4 : 0.0;  // beyond the x and y planes
  const double depth = r.chance(0.3) ? 1.3 : 0.9;   // beyond the near and far planes
  const int draws = r.between(1, 4);
  for (int k = 0; k < draws; ++k) {
    const uint32_t base = uint32_t(c.vertices.size()), n = uint32_t(r.between(3, 12));
    for (uint32_t v = 0; v < n; ++v)
      c.vertices.push_back({random_clip(c, r, margin, depth, perspective), {}});
    c.draws.push_back(random_draw(r, base, n));
  }
  assemble_triangles(c);
  if (c.triangles.empty()) {  // every primitive incomplete: one more strip makes sure
    const uint32_t base = uint32_t(c.vertices.size());
    for (uint32_t v = 0; v < 3; ++v)
      c.vertices.push_back({random_clip(c, r, margin, depth, perspective), {}});
    Draw strip;
    strip.mode = PrimitiveMode::triangle_strip, strip.first = base, strip.count = 3;
    c.draws.push_back(strip);
    assemble_triangles(c);
  }
  const bool clipped = margin > 0 || depth > 1;
  add_varying(c, 1, Interpolation::flat);
  add_varying(c, r.between(1, 3),
              clipped || r.chance(0.5) ? Interpolation::smooth : Interpolation::noperspective);
  fill_values(c, r, [](Random& rr, int) { return moderate(rr); });
  // The facing, drawn last: glFrontFace, culling now and then, and gl_FrontFacing half of the
  // time (a strip's odd triangles reversed, a fan's hub reset after a restart, both decide it).
  c.front_face = FrontFace(r.below(2));
  if (r.chance(0.25)) c.cull = r.chance(0.5) ? CullFace::back : CullFace::front;
  if (r.chance(0.5)) add_builtin(c, builtin_varying(Builtin::front_facing));
  return c;
}

// The window beyond the framebuffer: viewports with negative origins, larger than the
// framebuffer (up to 16384, the case format's limit; fractional ones too), partly or wholly
// outside it, and the scissor test with boxes inside, across and beyond the framebuffer (empty
// ones too); a few triangles anywhere in the viewport and beyond its clip planes.
Case window(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 1, 96, 1, 96);
  const int extent = r.chance(0.1) ? 16384 : r.between(1, 4 * std::max(c.fb_width, c.fb_height));
  const int vh = r.chance(0.5) ? extent : r.between(1, extent);
  const int vw = r.chance(0.5) ? extent : r.between(1, extent);
  // Origins that put the framebuffer anywhere from the viewport's left edge to its right.
  const int vy = c.fb_height / 2 - r.between(0, vh);
  const int vx = c.fb_width / 2 - r.between(0, vw);
  c.viewport = {vx, vy, vw, vh};
  if (r.chance(0.6)) {
    Scissor s;
    s.height = r.between(0, c.fb_height + 8);
    s.width = r.between(0, c.fb_width + 8);
    s.y = r.between(-8, c.fb_height);
    s.x = r.between(-8, c.fb_width);
    c.scissor = s;
  }
  c.provoking = ProvokingVertex(r.below(2));
  const bool perspective = r.chance(0.5);
  const int count = r.between(1, 8);
  for (int t = 0; t < count; ++t) {
    std::array<std::array<float, 4>, 3> v;
    for (auto& p : v) {
      // Near the framebuffer's part of the viewport: window positions within 32 pixels of it.
      const double w = some_w(r, perspective);
      const double z = r.uniform(-1.1, 1.1);
      const double y = r.uniform(-32, c.fb_height + 32);
      const double x = r.uniform(-32, c.fb_width + 32);
      p = clip_at(c, x, y, z, w);
    }
    add_triangle(c, v);
  }
  add_varying(c, 1, Interpolation::flat);
  add_varying(c, 2, Interpolation::smooth);
  fill_values(c, r, [](Random& rr, int) { return moderate(rr); });
  // glClipControl and the facing it decides, drawn last. Under GL_UPPER_LEFT every y_c is
  // negated, exactly, which keeps each triangle's window image where it was chosen above and
  // turns its winding there, so that culling checks the area's negated sign. Under
  // GL_ZERO_TO_ONE the near plane at z_c = 0 cuts the triangles that reach z_n < 0.
  c.clip_origin = ClipOrigin(r.below(2));
  c.clip_depth = ClipDepth(r.below(2));
  if (c.clip_origin == ClipOrigin::upper_left)
    for (Vertex& v : c.vertices)
      v.clip[1] = -v.clip[1];
  c.cull = CullFace(r.below(3));  // none, front or back
  c.front_face = FrontFace(r.below(2));
  // The built-ins, drawn after everything else: gl_FragCoord under a random layout and
  // gl_FrontFacing, each half of the time.
  if (r.chance(0.5))
    add_builtin(c, builtin_varying(Builtin::frag_coord, {r.chance(0.5), r.chance(0.5)}));
  if (r.chance(0.5)) add_builtin(c, builtin_varying(Builtin::front_facing));
  // Fractional viewports (glViewportIndexedf), drawn last too: each bound moved by up to 255/256
  // of a pixel, on the 1/256 grid (the triangles move with the viewport).
  if (r.chance(0.3)) {
    const auto fraction = [&r] { return float(r.between(0, 255)) / 256.0f; };
    c.viewport.x += fraction(), c.viewport.y += fraction();
    // Below 16384 (GL_MAX_VIEWPORT_DIMS and the case format's limit).
    if (c.viewport.width < 16384) c.viewport.width += fraction();
    if (c.viewport.height < 16384) c.viewport.height += fraction();
  }
  return c;
}

// Clip and cull distances: 1 to 8 of them together, each clip distance a random plane through
// the triangles' region (a·x_c + b·y_c + c·z_c + d·w_c, or values on and near 0 at the
// vertices), every written one enabled: a plane written but not enabled is left to the suite's
// cases, as every Mesa driver here clips by it where none is enabled (and zink always), a known
// bug (cases/known-failures.txt) that would drown what else a campaign finds; cull distances
// negative at a random subset
// of vertices (all three now and then, exactly 0 too); triangles near the window and beyond
// its clip planes, strips and fans now and then; smooth, flat and noperspective varyings
// (noperspective only where nothing is clipped, as in assembly: the known clipper bug).
Case distances(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 8, 96, 8, 96);
  c.provoking = ProvokingVertex(r.below(2));
  const bool perspective = r.chance(0.6);
  const int count = r.between(1, 6);
  for (int t = 0; t < count; ++t) {
    std::array<std::array<float, 4>, 3> v;
    for (auto& p : v) {
      const double w = some_w(r, perspective);
      const double z = r.chance(0.2) ? r.uniform(-1.3, 1.3) : r.uniform(-0.99, 0.99);
      const double y = r.uniform(-0.3, 1.3) * c.fb_height;
      const double x = r.uniform(-0.3, 1.3) * c.fb_width;
      p = clip_at(c, x, y, z, w);
    }
    add_triangle(c, v);
  }
  if (r.chance(0.3)) {  // the same vertices as one strip or fan
    Draw d;
    d.mode = r.chance(0.5) ? PrimitiveMode::triangle_strip : PrimitiveMode::triangle_fan;
    d.first = 0, d.count = uint32_t(c.vertices.size());
    c.draws = {d};
    assemble_triangles(c);
  }
  c.distances.clip = int(r.below(kMaxDistances + 1));
  c.distances.cull = int(r.below(uint64_t(kMaxDistances - c.distances.clip) + 1));
  if (!c.distances.any()) c.distances.clip = 1;
  // Never cull distances running from the packed clip-and-cull array's first vec4 into its
  // second (1 + 4, 2 + 3, 3 + 2 or more): zink draws nothing then, a known bug
  // (cases/cull_distances_after_clip_distances.json) that would drown the rest of a campaign.
  if (c.distances.clip > 0 && c.distances.clip < 4 && c.distances.clip + c.distances.cull > 4)
    c.distances.cull = 4 - c.distances.clip;
  c.distances.enabled = (1u << c.distances.clip) - 1u;
  for (int k = 0; k < c.distances.clip; ++k) {
    const bool plane = r.chance(0.8);
    std::array<double, 4> coefficients{};
    for (double& a : coefficients)
      a = r.uniform(-1, 1);
    for (Vertex& v : c.vertices) {
      double d = 0;
      if (plane) {
        for (size_t i = 0; i < 4; ++i)
          d += coefficients[i] * v.clip[i];
      } else {
        d = r.chance(0.3) ? 0.0 : r.uniform(-1, 1) * r.binades(-20, 0);
      }
      v.distances.push_back(float(d));
    }
  }
  for (int k = 0; k < c.distances.cull; ++k)
    for (Vertex& v : c.vertices)
      v.distances.push_back(r.chance(0.1)   ? 0.0f
                            : r.chance(0.5) ? -float(r.uniform(0, 2))
                                            : float(r.uniform(0, 2)));
  c.cull = r.chance(0.2) ? CullFace(r.below(3)) : CullFace::none;
  add_varying(c, 2, Interpolation::smooth);
  add_varying(c, 1, Interpolation::flat);
  if (r.chance(0.5)) add_varying(c, 1, Interpolation::noperspective);
  fill_values(c, r, [](Random& rr, int) { return moderate(rr); });
  return c;
}

// What casefile::load demands and a generator may not have ensured: noperspective only where
// every vertex a triangle uses has w_c > 0 (cases/README.md); such varyings become smooth.
void make_loadable(Case& c) {
  bool w_positive = true;
  for (const auto& t : c.triangles)
    for (const uint32_t k : t)
      w_positive = w_positive && c.vertices[k].clip[3] > 0;
  if (!w_positive)
    for (Varying& v : c.varyings)
      if (v.interpolation == Interpolation::noperspective) v.interpolation = Interpolation::smooth;
}

}  // namespace

// Depth state: GL_DEPTH_CLAMP half the time, with triangles reaching well beyond the near and
// far planes (z_n within ±3) and behind the eye now and then; polygon offsets (glPolygonOffset
// and glPolygonOffsetClamp) with factors and units of either sign, from none to ones that push
// fragments past 0 and 1; depth ranges full, partial and reversed; both glClipControl depth
// modes; every depth function against a random clear; overlapping triangles; gl_FragCoord now
// and then.
Case depth(Random& r) {
  Case c;
  set_framebuffer_drawn(c, r, 8, 128, 8, 128);
  c.depth_clamp = r.chance(0.5);
  c.clip_depth = ClipDepth(r.below(2));
  c.depth_func = DepthFunc(r.below(8));
  c.depth_clear = r.chance(0.5) ? 1.0f : r.chance(0.5) ? 0.0f : float(r.unit());
  const uint64_t range = r.below(10);
  if (range >= 4) {
    c.depth_near = float(r.unit()), c.depth_far = float(r.unit());  // reversed half the time
  }
  if (r.chance(0.7)) {
    PolygonOffset& o = c.polygon_offset.emplace();
    // Each term: none, moderate, or large enough to move a fragment by a good part of the range.
    const auto term = [&r](double moderate, double large) {
      const uint64_t kind = r.below(5);
      const double sign = r.chance(0.5) ? 1.0 : -1.0;
      return kind == 0  ? 0.0f
             : kind < 4 ? float(sign * r.uniform(0, moderate))
                        : float(sign * r.uniform(moderate, large));
    };
    o.factor = term(4, 200);
    o.units = term(64, 4e5);
    if (r.chance(0.25)) o.clamp = float((r.chance(0.5) ? 1 : -1) * r.uniform(1e-4, 2e-2));
  }
  const bool perspective = r.chance(0.5);
  const int count = r.between(1, 6);
  for (int t = 0; t < count; ++t) {
    std::array<std::array<float, 4>, 3> v;
    for (auto& p : v) {
      p = random_clip(c, r, 0.3, c.depth_clamp ? 3.0 : 1.2, perspective);
      // Behind the eye now and then, where only x and y clip under GL_DEPTH_CLAMP.
      if (c.depth_clamp && r.chance(0.05))
        for (float& k : p)
          k = -k;
    }
    add_triangle(c, v);
  }
  add_varying(c, 2, Interpolation::smooth);
  fill_values(c, r, [](Random& rr, int) { return moderate(rr); });
  if (r.chance(0.25)) add_builtin(c, builtin_varying(Builtin::frag_coord));
  return c;
}

const std::vector<Generator>& generators() {
  static const std::vector<Generator> all{
      {"sizes",
       "triangles from sub-pixel to several times the viewport, slivers, far from the window "
       "origin",
       sizes},
      {"clip", "w over orders of magnitude, w <= 0, vertices and edges on and near clip planes",
       clip},
      {"mesh", "shared edges: fans with sub-pixel rim steps, jittered grids, pixel-centre meshes",
       mesh},
      {"attributes", "values from 1e-30 to 1e30, mixed magnitudes and signs, every qualifier",
       attributes},
      {"states",
       "cull, front face, provoking vertex, depth range (reversed too), depth function, "
       "viewports",
       states},
      {"dense",
       "hundreds of triangles with the depth test: coplanar and near-coplanar pairs under nearer "
       "triangles, identical copies, clipped ones, shared edges of every size",
       dense},
      {"assembly",
       "strips, fans and lists in several draws: 8-, 16- and 32-bit indices, primitive restart, "
       "both provoking vertices, clipped primitives, both front faces with gl_FrontFacing",
       assembly},
      {"window",
       "viewports beyond the framebuffer (negative origins, up to 16384 wide, fractional "
       "ones through glViewportIndexedf), scissor boxes "
       "inside, across and beyond it, glClipControl's origins and depth modes with culling, "
       "gl_FragCoord under its layouts and gl_FrontFacing",
       window},
      {"distances",
       "gl_ClipDistance and gl_CullDistance: up to 8 together, planes through the triangles, "
       "cull distances negative at some or all vertices",
       distances},
      {"depth",
       "GL_DEPTH_CLAMP with triangles far beyond the near and far planes, polygon offsets "
       "(glPolygonOffsetClamp too) of either sign up to saturating ones, depth ranges full, "
       "partial and reversed, both depth modes, every depth function",
       depth},
  };
  return all;
}

const Generator* find_generator(std::string_view name) {
  for (const Generator& g : generators())
    if (g.name == name) return &g;
  return nullptr;
}

const Generator& generator_for(const std::vector<const Generator*>& chosen, uint64_t index) {
  if (chosen.empty()) throw std::invalid_argument("generator_for: no generator chosen");
  return *chosen[index % chosen.size()];
}

Case generate(const std::vector<const Generator*>& chosen, uint64_t seed, uint64_t index) {
  const Generator& g = generator_for(chosen, index);
  Random random(stream_seed(seed, index, g.name));
  Case c = g.make(random);
  make_loadable(c);
  // Appended piece by piece (see add_varying on GCC 12's -Wrestrict).
  const std::string seed_text = std::to_string(seed), index_text = std::to_string(index);
  std::string where = seed_text;
  where += ':';
  where += index_text;
  c.name = "fuzz_";
  for (const std::string_view part : {g.name, std::string_view("_"), std::string_view(seed_text),
                                      std::string_view("_"), std::string_view(index_text)})
    c.name += part;
  c.description = "Random case of generator ";
  for (const std::string_view part :
       {g.name, std::string_view(" ("), g.aims_at, std::string_view("), seed:index "),
        std::string_view(where), std::string_view(": glrefcheck fuzz --generator "), g.name,
        std::string_view(" --replay "), std::string_view(where), std::string_view(" --emit FILE")})
    c.description += part;
  return c;
}

}  // namespace glrc::campaign
