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
