#include "selftest/faults.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <utility>

#include "core/primitive_assembly.hpp"
#include "selftest/assembly_faults.hpp"

namespace glrc::selftest {

namespace {

// The covered pixel with the largest |value| in component k (depth for k < 0), so that a
// relative change is visible; -1 when nothing is covered.
long largest_covered(const Frame& f, int k) {
  long best = -1;
  float best_value = -1;
  for (size_t i = 0; i < f.pixel_count(); ++i) {
    if (f.primitive[i] < 0) continue;
    const float v = std::fabs(k < 0 ? f.depth[i] : f.components[size_t(k)][i]);
    if (v > best_value) best = long(i), best_value = v;
  }
  return best;
}

// Window position (x_w, y_w) of a vertex with w_c > 0, in double: accurate enough to find the
// pixels next to an edge; the tests that must be exact (on a row of centres, inside a span)
// compare exact products instead.
std::array<double, 2> window_of(const Case& c, const std::array<float, 4>& clip) {
  const Viewport& vp = c.viewport;
  return {(double(clip[0]) / clip[3] + 1) * vp.width / 2 + vp.x,
          (window_y_c(c, clip[1]) / clip[3] + 1) * vp.height / 2 + vp.y};
}

// Whether GL draws triangle t at all: every w_c > 0 (the fault leaves clipped triangles alone),
// a non-zero area in window coordinates, and not culled.
bool drawn_unclipped(const Case& c, const std::array<uint32_t, 3>& t) {
  std::array<std::array<double, 2>, 3> p{};
  for (int k = 0; k < 3; ++k) {
    const std::array<float, 4>& clip = c.vertices[t[size_t(k)]].clip;
    if (!(clip[3] > 0)) return false;
    p[size_t(k)] = window_of(c, clip);
  }
  const double area =
      (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
  if (area == 0) return false;
  const bool front = ((area > 0) != facing_reversed(c)) == (c.front_face == FrontFace::ccw);
  switch (c.cull) {
    case CullFace::none:
      return true;
    case CullFace::front:
      return !front;
    case CullFace::back:
      return front;
    case CullFace::front_and_back:
      return false;
  }
  return true;
}

// z_w's plane over triangle t in window coordinates, in double, unclamped and without any
// polygon offset: {∂z_w/∂x_w, ∂z_w/∂y_w, z_w at the window origin}; nullopt unless every w_c > 0
// and the window area is not 0. Accurate to far below the faults' changes.
std::optional<std::array<double, 3>> depth_plane_of(const Case& c,
                                                    const std::array<uint32_t, 3>& t) {
  std::array<std::array<double, 3>, 3> p{};
  for (size_t k = 0; k < 3; ++k) {
    const std::array<float, 4>& clip = c.vertices[t[k]].clip;
    if (!(clip[3] > 0)) return std::nullopt;
    const auto xy = window_of(c, clip);
    const double z_n = double(clip[2]) / clip[3];
    const double n = c.depth_near, f = c.depth_far;
    p[k] = {xy[0], xy[1],
            c.clip_depth == ClipDepth::zero_to_one ? n + z_n * (f - n)
                                                   : (n + f) / 2 + z_n * (f - n) / 2};
  }
  const double dx1 = p[1][0] - p[0][0], dy1 = p[1][1] - p[0][1], dz1 = p[1][2] - p[0][2];
  const double dx2 = p[2][0] - p[0][0], dy2 = p[2][1] - p[0][1], dz2 = p[2][2] - p[0][2];
  const double area = dx1 * dy2 - dx2 * dy1;
  if (area == 0) return std::nullopt;
  const double gx = (dz1 * dy2 - dz2 * dy1) / area, gy = (dx1 * dz2 - dx2 * dz1) / area;
  return std::array<double, 3>{gx, gy, p[0][2] - gx * p[0][0] - gy * p[0][1]};
}

// Each covered pixel's depth replaced by change(plane, x, y, depth) (x, y its centre), for the
// pixels of triangles depth_plane_of gives a plane; whether any depth changed.
bool change_depth(
    const Case& c, Frame& f,
    const std::function<float(const std::array<double, 3>&, double, double, float)>& change) {
  std::vector<std::optional<std::array<double, 3>>> planes(c.triangles.size());
  std::vector<bool> made(c.triangles.size(), false);
  bool changed = false;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const size_t i = f.index(x, y);
      const int32_t p = f.primitive[i];
      if (p < 0 || size_t(p) >= c.triangles.size()) continue;
      if (!made[size_t(p)])
        planes[size_t(p)] = depth_plane_of(c, c.triangles[size_t(p)]), made[size_t(p)] = true;
      if (!planes[size_t(p)]) continue;
      const float z = change(*planes[size_t(p)], x + 0.5, y + 0.5, f.depth[i]);
      changed = changed || std::bit_cast<uint32_t>(z) != std::bit_cast<uint32_t>(f.depth[i]);
      f.depth[i] = z;
    }
  return changed;
}

// The sign of (pixel coordinate + 1/2) - (window coordinate of a vertex with w_c > 0), along one
// axis of the viewport (origin o, size n): exact, since c + 1/2 against (q_c/w_c + 1)·n/2 + o
// compares as (2·(c - o) + 1 - n)·w_c against q_c·n, products of a float and an integer below
// 2^14 that a double holds exactly.
int centre_minus_vertex(int pixel, int o, int n, float q, float w) {
  const double lhs = double(2 * (pixel - o) + 1 - n) * w, rhs = double(q) * n;
  return lhs > rhs ? 1 : lhs < rhs ? -1 : 0;
}

// Whether triangle t is thin in the window: its height over its longest edge under a pixel
// (unclipped: every w_c > 0; the double's window positions are close enough to tell).
bool thin(const Case& c, const std::array<uint32_t, 3>& t) {
  std::array<std::array<double, 2>, 3> p{};
  for (int k = 0; k < 3; ++k) {
    const std::array<float, 4>& clip = c.vertices[t[size_t(k)]].clip;
    if (!(clip[3] > 0)) return false;
    p[size_t(k)] = window_of(c, clip);
  }
  const double area2 = std::fabs((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                                 (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]));
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, std::hypot(p[size_t((k + 1) % 3)][0] - p[size_t(k)][0],
                                           p[size_t((k + 1) % 3)][1] - p[size_t(k)][1]));
  return longest > 0 && area2 / longest < 1.0;
}

// Pixels whose centre lies exactly on a horizontal edge that two drawn (unclipped) triangles
// share, lying on its two sides; the edge's ends excluded.
std::vector<size_t> centres_on_shared_horizontal_edges(const Case& c, const Frame& f) {
  // Edges by their ends' clip coordinates, smaller first: what GL sees as the same two points.
  using Key = std::pair<std::array<float, 4>, std::array<float, 4>>;
  std::map<Key, std::vector<size_t>> by_edge;  // -> triangles using it
  for (size_t t = 0; t < c.triangles.size(); ++t) {
    if (!drawn_unclipped(c, c.triangles[t])) continue;
    for (int i = 0; i < 3; ++i) {
      auto a = c.vertices[c.triangles[t][size_t(i)]].clip;
      auto b = c.vertices[c.triangles[t][size_t((i + 1) % 3)]].clip;
      if (b < a) std::swap(a, b);
      by_edge[{a, b}].push_back(t);
    }
  }
  const Viewport& vp = c.viewport;
  std::vector<size_t> pixels;
  for (const auto& [ends, users] : by_edge) {
    const auto& [a, b] = ends;
    // Horizontal: y_a/w_a == y_b/w_b, exact as products of two floats in double.
    if (users.size() < 2 || double(a[1]) * b[3] != double(b[1]) * a[3]) continue;  // either origin
    // The third vertices of two of the users on opposite sides of the edge.
    const auto [ax, ay] = window_of(c, a);
    bool above = false, below = false;
    for (size_t t : users)
      for (uint32_t k : c.triangles[t]) {
        const double y = window_of(c, c.vertices[k].clip)[1];
        above = above || y > ay;
        below = below || y < ay;
      }
    if (!above || !below) continue;
    // On a row of centres.
    const int py = int(std::floor(ay));
    if (py < 0 || py >= f.height ||
        centre_minus_vertex(py, vp.y, vp.height, float(window_y_c(c, a[1])), a[3]) != 0)
      continue;
    const double bx = window_of(c, b)[0];
    const int x0 = std::max(0, int(std::floor(std::min(ax, bx))) - 1);
    const int x1 = std::min(f.width - 1, int(std::ceil(std::max(ax, bx))) + 1);
    for (int px = x0; px <= x1; ++px) {
      const int sa = centre_minus_vertex(px, vp.x, vp.width, a[0], a[3]);
      const int sb = centre_minus_vertex(px, vp.x, vp.width, b[0], b[3]);
      if (sa * sb < 0) pixels.push_back(f.index(px, py));
    }
  }
  return pixels;
}

// Changes built-in b's components in every covered pixel of f: change(i, value) for its
// component i. Whether the case writes b (and anything was covered).
bool change_builtin(const Case& c, Frame& f, Builtin b,
                    const std::function<void(int, float&)>& change) {
  bool any = false;
  size_t first = 0;
  for (const Varying& v : c.varyings) {
    if (v.builtin == b)
      for (int i = 0; i < v.size; ++i)
        for (size_t p = 0; p < f.pixel_count(); ++p)
          if (f.primitive[p] >= 0) {
            change(i, f.components[first + size_t(i)][p]);
            any = true;
          }
    first += size_t(v.size);
  }
  return any;
}

std::vector<Fault> make_faults() {
  std::vector<Fault> list;

  list.push_back({"smooth-as-noperspective",
                  "perspective-correct varyings interpolated linearly in screen space",
                  [](Case& c) {
                    for (Varying& v : c.varyings)
                      if (v.interpolation == Interpolation::smooth)
                        v.interpolation = Interpolation::noperspective;
                  },
                  nullptr});

  list.push_back({"provoking-vertex-flipped",
                  "flat values taken from the other end of the triangle",
                  [](Case& c) {
                    c.provoking = c.provoking == ProvokingVertex::last ? ProvokingVertex::first
                                                                       : ProvokingVertex::last;
                    // GL assembles the draws under the flipped convention (what the harness
                    // checks c.triangles against).
                    assemble_triangles(c);
                  },
                  nullptr});

  list.push_back({"positions-shifted-half-pixel",
                  "window positions off by half a pixel in x (a pixel-centre convention error)",
                  [](Case& c) {
                    // x_w = (x_c / w_c + 1)·width/2 + x: half a pixel is w_c / width in x_c.
                    for (Vertex& v : c.vertices)
                      v.clip[0] =
                          float(double(v.clip[0]) +
                                double(v.clip[3]) / double(std::max(c.viewport.width, 1.0f)));
                  },
                  nullptr});

  list.push_back({"depth-range-nudged", "glDepthRange applied 1e-4 off",
                  [](Case& c) {
                    // Inward, so that GL's clamping of the range to [0, 1] keeps the change.
                    auto nudge = [](float d) { return d <= 0.5f ? d + 1e-4f : d - 1e-4f; };
                    c.depth_near = nudge(c.depth_near);
                    c.depth_far = nudge(c.depth_far);
                  },
                  nullptr});

  list.push_back({"one-value-off-1e-3", "one value in one pixel changed by 1e-3 relative", nullptr,
                  [](const Case& c, const Expectation&, Frame& f) {
                    // The first interpolated component, or depth when there is none.
                    int k = -1;
                    const auto owner = component_varying(c);
                    for (size_t j = 0; j < owner.size() && k < 0; ++j)
                      if (c.varyings[size_t(owner[j])].interpolation != Interpolation::flat)
                        k = int(j);
                    const long i = largest_covered(f, k);
                    if (i < 0) return false;
                    float& v = k < 0 ? f.depth[size_t(i)] : f.components[size_t(k)][size_t(i)];
                    if (v == 0) return false;
                    v = float(double(v) * (1 + 1e-3));
                    return true;
                  }});

  list.push_back({"varyings-11-mantissa-bits",
                  "varyings carried at 11 mantissa bits (a half-float path) instead of 23", nullptr,
                  [](const Case&, const Expectation&, Frame& f) {
                    bool any = false;
                    for (auto& component : f.components)
                      for (size_t i = 0; i < component.size(); ++i) {
                        if (f.primitive[i] < 0) continue;
                        const float kept = keep_mantissa_bits(component[i], 11);
                        any = any || kept != component[i];
                        component[i] = kept;
                      }
                    return any;
                  }});

  list.push_back({"components-swapped", "two components of a varying swapped (x and y)", nullptr,
                  [](const Case& c, const Expectation&, Frame& f) {
                    int first = 0;
                    for (const Varying& v : c.varyings) {
                      if (v.size >= 2) {
                        std::swap(f.components[size_t(first)], f.components[size_t(first) + 1]);
                        return true;
                      }
                      first += v.size;
                    }
                    return false;
                  }});

  list.push_back({"shared-edge-pixel-dropped",
                  "one pixel on an edge two triangles share left uncovered (a crack in a mesh)",
                  nullptr, [](const Case&, const Expectation& e, Frame& f) {
                    for (size_t i = 0; i < f.pixel_count(); ++i) {
                      const uint8_t bits = e.edges[i];
                      if (!(bits & edge::shared) || (bits & edge::snapping) || f.primitive[i] < 0)
                        continue;
                      f.primitive[i] = Frame::kNoPrimitive;
                      f.depth[i] = 1.0f;
                      for (auto& component : f.components)
                        component[i] = 0.0f;
                      if (!f.fragments.empty()) f.fragments[i] = 0;
                      return true;
                    }
                    return false;
                  }});
  list.push_back({"shared-horizontal-edge-drawn-twice",
                  "centres on a horizontal edge two triangles share drawn by both (no tie rule "
                  "for horizontal edges)",
                  nullptr, [](const Case& c, const Expectation& e, Frame& f) {
                    if (f.fragments.empty()) return false;
                    bool any = false;
                    for (size_t i : centres_on_shared_horizontal_edges(c, f)) {
                      // Only where the reference's edge bits let the comparator count
                      // fragments: on the shared edge and away from every outer edge.
                      const uint8_t bits = e.edges[i];
                      if (!(bits & edge::shared) || !(bits & edge::tie) ||
                          (bits & edge::snapping) || f.primitive[i] < 0 || f.fragments[i] == 2)
                        continue;
                      f.fragments[i] = 2;  // the values GL wrote stay: one of the two triangles'
                      any = true;
                    }
                    return any;
                  }});
  list.push_back({"thin-shared-edge-drawn-twice",
                  "a centre beside an edge two thin triangles share (a fan's sub-pixel rim "
                  "steps) rasterized by both of them",
                  nullptr, [](const Case& c, const Expectation& e, Frame& f) {
                    if (f.fragments.empty() || e.frame.fragments.size() != f.pixel_count())
                      return false;
                    for (size_t i = 0; i < f.pixel_count(); ++i) {
                      const int32_t p = e.frame.primitive[i];
                      // Where the count is decided on a shared edge, beside a thin triangle.
                      if (!(e.edges[i] & edge::shared) ||
                          (e.edges[i] & (edge::snapping | edge::unstable)) || p < 0 ||
                          size_t(p) >= c.triangles.size() || !thin(c, c.triangles[size_t(p)]) ||
                          f.fragments[i] != e.frame.fragments[i])
                        continue;
                      ++f.fragments[i];  // the kept fragment and its values stay
                      return true;
                    }
                    return false;
                  }});
  list.push_back({"hidden-fragment-dropped",
                  "one fragment of a triangle hidden beneath a nearer one not rasterized (a "
                  "crack the depth test hides)",
                  nullptr, [](const Case&, const Expectation& e, Frame& f) {
                    if (f.fragments.empty() || e.frame.fragments.size() != f.pixel_count())
                      return false;
                    for (size_t i = 0; i < f.pixel_count(); ++i) {
                      // Where the count is decided (no band of an outer edge, nothing that
                      // may turn over) and a fragment lies beneath the kept one.
                      if ((e.edges[i] & (edge::snapping | edge::unstable)) ||
                          e.frame.fragments[i] < 2 || f.fragments[i] != e.frame.fragments[i])
                        continue;
                      --f.fragments[i];  // the kept fragment and its values stay
                      return true;
                    }
                    return false;
                  }});
  list.push_back({"identical-copy-wins-depth-test",
                  "a bitwise-identical copy of an earlier triangle passes the depth test against "
                  "it where equal depths fail (its depths not invariant, as softpipe's Z "
                  "invariance bug of 2011)",
                  nullptr, [](const Case& c, const Expectation& e, Frame& f) {
                    if (depth_test(c.depth_func, 0.5f, 0.5f)) return false;  // a copy wins there
                    // Each triangle's last identical copy.
                    const std::vector<int32_t> first = identical_triangles(c);
                    std::vector<int32_t> last(first.size(), -1);
                    for (size_t t = 0; t < first.size(); ++t)
                      last[size_t(first[t])] = int32_t(t);
                    bool any = false;
                    for (size_t i = 0; i < f.pixel_count(); ++i) {
                      const int32_t p = e.frame.primitive[i];
                      if (p < 0 || size_t(p) >= first.size() || f.primitive[i] != p) continue;
                      const int32_t copy = last[size_t(first[size_t(p)])];
                      if (copy <= p) continue;
                      f.primitive[i] = copy;  // the values GL wrote stay: the copy's may be equal
                      any = true;
                    }
                    return any;
                  }});
  add_assembly_faults(list);

  list.push_back({"scissor-box-one-pixel-wider",
                  "the scissor box one pixel wider than glScissor asked (an inclusive right "
                  "bound)",
                  [](Case& c) {
                    if (c.scissor) ++c.scissor->width;
                  },
                  nullptr});
  list.push_back({"upper-left-facing-not-reversed",
                  "under glClipControl(GL_UPPER_LEFT) the sign of the window-space area is not "
                  "negated, so facing (and culling) follows the upside-down image",
                  [](Case& c) {
                    if (c.clip_origin == ClipOrigin::upper_left)
                      c.front_face =
                          c.front_face == FrontFace::ccw ? FrontFace::cw : FrontFace::ccw;
                  },
                  nullptr});
  list.push_back({"clip-distance-sign-flipped",
                  "every gl_ClipDistance taken with the wrong sign: the part a user clip plane "
                  "keeps is discarded and the part it discards drawn",
                  [](Case& c) {
                    for (Vertex& v : c.vertices)
                      for (int i = 0; i < c.distances.clip && size_t(i) < v.distances.size(); ++i)
                        v.distances[size_t(i)] = -v.distances[size_t(i)];
                  },
                  nullptr});
  list.push_back({"frag-coord-half-pixel-off",
                  "gl_FragCoord.xy without the half-pixel centre offset: (px, py) where the "
                  "layout asks for (px + 0.5, py + 0.5), and likewise under its qualifiers",
                  nullptr, [](const Case& c, const Expectation&, Frame& f) {
                    return change_builtin(c, f, Builtin::frag_coord, [](int i, float& v) {
                      if (i < 2) v -= 0.5f;
                    });
                  }});
  list.push_back({"frag-coord-w-not-inverted",
                  "gl_FragCoord.w holding the interpolated w_c instead of 1/w_c", nullptr,
                  [](const Case& c, const Expectation&, Frame& f) {
                    return change_builtin(c, f, Builtin::frag_coord, [](int i, float& v) {
                      if (i == 3) v = 1 / v;
                    });
                  }});
  list.push_back({"front-facing-inverted-under-cw",
                  "gl_FrontFacing ignoring glFrontFace(GL_CW): true on the counter-clockwise "
                  "triangles, which GL_CW makes back-facing",
                  nullptr, [](const Case& c, const Expectation&, Frame& f) {
                    if (c.front_face != FrontFace::cw) return false;
                    return change_builtin(c, f, Builtin::front_facing,
                                          [](int, float& v) { v = 1 - v; });
                  }});
  list.push_back({"zero-to-one-ignored",
                  "glClipControl's GL_ZERO_TO_ONE ignored: the near plane stays at z_c = -w_c and "
                  "z_w = z_d·(f - n)/2 + (n + f)/2",
                  [](Case& c) { c.clip_depth = ClipDepth::negative_one_to_one; }, nullptr});
  // The depth clamp and polygon offset faults change the depths GL wrote by what the fault
  // would make of them, computed in double from the triangle's own plane (depth_plane_of).
  list.push_back({"depth-clamp-not-applied",
                  "GL_DEPTH_CLAMP turning near and far clipping off without clamping: the depth "
                  "buffer gets z_w beyond the depth range",
                  nullptr, [](const Case& c, const Expectation&, Frame& f) {
                    if (!c.depth_clamp || c.polygon_offset) return false;
                    return change_depth(
                        c, f, [](const std::array<double, 3>& z, double x, double y, float) {
                          return float(z[2] + z[0] * x + z[1] * y);
                        });
                  }});
  list.push_back({"depth-clamp-to-unit-range",
                  "GL_DEPTH_CLAMP clamping z_w to [0, 1] instead of [min(n, f), max(n, f)]",
                  nullptr, [](const Case& c, const Expectation&, Frame& f) {
                    if (!c.depth_clamp || c.polygon_offset) return false;
                    return change_depth(
                        c, f, [](const std::array<double, 3>& z, double x, double y, float) {
                          return float(std::clamp(z[2] + z[0] * x + z[1] * y, 0.0, 1.0));
                        });
                  }});
  list.push_back({"polygon-offset-units-ignored",
                  "glPolygonOffset's units ignored: no r·units term",
                  [](Case& c) {
                    if (c.polygon_offset) c.polygon_offset->units = 0;
                  },
                  nullptr});
  list.push_back({"polygon-offset-slope-x-only",
                  "the polygon offset's slope taken as |dz_w/dx_w| alone instead of the larger of "
                  "|dz_w/dx_w| and |dz_w/dy_w| (or their length)",
                  nullptr, [](const Case& c, const Expectation&, Frame& f) {
                    if (!c.polygon_offset || c.polygon_offset->factor == 0 ||
                        c.polygon_offset->clamp)
                      return false;
                    const double factor = c.polygon_offset->factor;
                    return change_depth(
                        c, f, [&](const std::array<double, 3>& z, double, double, float depth) {
                          const double m = std::max(std::fabs(z[0]), std::fabs(z[1]));
                          return fragment_depth(c, float(depth + factor * (std::fabs(z[0]) - m)));
                        });
                  }});
  return list;
}

}  // namespace

const std::vector<Fault>& faults() {
  static const std::vector<Fault> list = make_faults();
  return list;
}

float keep_mantissa_bits(float x, int bits) {
  if (!std::isfinite(x) || bits >= 23) return x;
  // Round to nearest, ties to even, on the bit pattern: adding half of the dropped range (less
  // one when the kept part is even) carries into the kept bits exactly when rounding up.
  const uint32_t u = std::bit_cast<uint32_t>(x);
  const int drop = 23 - bits;
  const uint32_t half = (1u << (drop - 1)) - 1 + ((u >> drop) & 1);
  return std::bit_cast<float>((u + half) & ~((1u << drop) - 1));
}

}  // namespace glrc::selftest
