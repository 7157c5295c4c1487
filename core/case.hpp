// Case: one self-contained rasterization test, as read from cases/*.json. Everything the
// reference and a GL implementation need to draw the same triangles with the same bits.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/channel.hpp"
#include "core/draw.hpp"
#include "core/names.hpp"

namespace glrc {

enum class Interpolation { smooth, flat, noperspective };
template <>
struct Names<Interpolation> {
  static constexpr std::array<std::pair<Interpolation, std::string_view>, 3> table{{
      {Interpolation::smooth, "smooth"},
      {Interpolation::flat, "flat"},
      {Interpolation::noperspective, "noperspective"},
  }};
};

// A built-in input of the fragment shader written out in place of an interpolated varying
// (GLSL 4.60 section 7.1.2, OpenGL 4.6 sections 14.6.1 and 15.2.2), to a colour attachment of
// its own and judged like one:
//   gl_FragCoord   the fragment's window position (x_w, y_w) (the pixel centre, under
//                  FragCoordLayout), z_w and 1/w_c: 4 components, each a linear function of
//                  the window position (noperspective);
//   gl_FrontFacing whether the primitive is front-facing (glFrontFace, glClipControl's origin):
//                  1.0 or 0.0, one value for the whole primitive (flat).
// It has no value per vertex: its components hold 0 in every Vertex::values, so that component
// k of a frame is component k of every vertex.
enum class Builtin { none, frag_coord, front_facing };
template <>
struct Names<Builtin> {
  static constexpr std::array<std::pair<Builtin, std::string_view>, 2> table{{
      {Builtin::frag_coord, "gl_FragCoord"},
      {Builtin::front_facing, "gl_FrontFacing"},
  }};
};
// gl_FragCoord's layout qualifiers (GLSL 4.60 section 4.4.1.3): origin_upper_left gives
// y = H − y_w (H the framebuffer's height) instead of y_w; pixel_center_integer gives the
// centre of pixel (px, py) as (px, py) instead of (px + 1/2, py + 1/2).
struct FragCoordLayout {
  bool origin_upper_left = false;
  bool pixel_center_integer = false;
  friend bool operator==(const FragCoordLayout&, const FragCoordLayout&) = default;
};
// The fragment shader's redeclaration of gl_FragCoord with the layout's qualifiers, a line of
// GLSL; "" for the default layout, which needs none. Shared by the harness and the exports.
inline std::string frag_coord_redeclaration(const FragCoordLayout& l) {
  if (!l.origin_upper_left && !l.pixel_center_integer) return "";
  const char* qualifiers = !l.pixel_center_integer ? "origin_upper_left"
                           : !l.origin_upper_left  ? "pixel_center_integer"
                                                   : "origin_upper_left, pixel_center_integer";
  return std::string("layout(") + qualifiers + ") in vec4 gl_FragCoord;\n";
}

struct Varying {
  std::string name;  // a built-in's is its GLSL name
  int size = 4;      // 1..4 components
  Interpolation interpolation = Interpolation::smooth;
  Builtin builtin = Builtin::none;
  FragCoordLayout layout;  // gl_FragCoord's only
  bool is_builtin() const { return builtin != Builtin::none; }
};
// A built-in as a Varying: its name, size and the qualifier that says how it varies.
inline Varying builtin_varying(Builtin b, const FragCoordLayout& layout = {}) {
  if (b == Builtin::front_facing) return {"gl_FrontFacing", 1, Interpolation::flat, b, {}};
  return {"gl_FragCoord", 4, Interpolation::noperspective, b, layout};
}

struct Vertex {
  // Clip coordinates (x_c, y_c, z_c, w_c), float32: exactly what gl_Position receives.
  std::array<float, 4> clip{};
  // All varyings' components, concatenated in the order of Case::varyings.
  std::vector<float> values;
  // gl_ClipDistance[0 .. Distances::clip) then gl_CullDistance[0 .. Distances::cull), as the
  // vertex shader writes them; empty for a case without (Case::distances).
  std::vector<float> distances;
};

// The user clip and cull distances (OpenGL 4.6 section 13.7, GL_ARB_cull_distance): how many
// of each the vertex shader writes, and which clip planes are enabled (bit i: GL_CLIP_DISTANCEi;
// a distance written but not enabled clips nothing). A triangle keeps the points where every
// enabled clip distance, linear in clip space like the view volume's planes, is >= 0; it is
// discarded whole where one cull distance is negative at all three of its vertices. GL's limit
// for both together, GL_MAX_COMBINED_CLIP_AND_CULL_DISTANCES, is at least 8: kMaxDistances.
inline constexpr int kMaxDistances = 8;
struct Distances {
  int clip = 0, cull = 0;
  uint32_t enabled = 0;
  bool any() const { return clip + cull > 0; }
  bool plane_enabled(int i) const { return i < clip && (enabled >> i & 1u); }
  friend bool operator==(const Distances&, const Distances&) = default;
};

enum class CullFace { none, front, back, front_and_back };
enum class FrontFace { ccw, cw };
enum class ProvokingVertex { last, first };  // glProvokingVertex; GL's default is last
// glDepthFunc. always and less first: their numbers are the wire format's (casefile/wire.cpp).
enum class DepthFunc { always, less, never, equal, lequal, greater, notequal, gequal };
// Whether a fragment at depth z passes the depth test against the stored value (glDepthFunc,
// OpenGL 4.6 section 17.3.4: the incoming value compared with the stored one), both float32 as
// in a 32F depth buffer. The reference and the driver models test with it.
inline bool depth_test(DepthFunc f, float z, float stored) {
  switch (f) {
    case DepthFunc::always:
      return true;
    case DepthFunc::never:
      return false;
    case DepthFunc::less:
      return z < stored;
    case DepthFunc::lequal:
      return z <= stored;
    case DepthFunc::greater:
      return z > stored;
    case DepthFunc::gequal:
      return z >= stored;
    case DepthFunc::equal:
      return z == stored;
    case DepthFunc::notequal:
      return z != stored;
  }
  return false;
}
// The case file's names (cases/README.md).
template <>
struct Names<CullFace> {
  static constexpr std::array<std::pair<CullFace, std::string_view>, 4> table{{
      {CullFace::none, "none"},
      {CullFace::front, "front"},
      {CullFace::back, "back"},
      {CullFace::front_and_back, "front_and_back"},
  }};
};
template <>
struct Names<FrontFace> {
  static constexpr std::array<std::pair<FrontFace, std::string_view>, 2> table{{
      {FrontFace::ccw, "ccw"},
      {FrontFace::cw, "cw"},
  }};
};
template <>
struct Names<ProvokingVertex> {
  static constexpr std::array<std::pair<ProvokingVertex, std::string_view>, 2> table{{
      {ProvokingVertex::last, "last"},
      {ProvokingVertex::first, "first"},
  }};
};
template <>
struct Names<DepthFunc> {
  static constexpr std::array<std::pair<DepthFunc, std::string_view>, 8> table{{
      {DepthFunc::always, "always"},
      {DepthFunc::less, "less"},
      {DepthFunc::never, "never"},
      {DepthFunc::equal, "equal"},
      {DepthFunc::lequal, "lequal"},
      {DepthFunc::greater, "greater"},
      {DepthFunc::notequal, "notequal"},
      {DepthFunc::gequal, "gequal"},
  }};
};

// glClipControl(origin, depth) (OpenGL 4.6 sections 13.7, 13.8.1 and 14.6.1; GL 4.5 or
// ARB_clip_control). GL_UPPER_LEFT negates y_d in the viewport transform, and the sign of the
// area that decides facing with it, so a triangle keeps its facing while its image turns upside
// down inside the viewport. GL_ZERO_TO_ONE moves the near plane of the view volume from
// z_c = -w_c to z_c = 0 and maps z_d = z_c / w_c to z_w = z_d·(f − n) + n instead of
// z_d·(f − n)/2 + (n + f)/2.
enum class ClipOrigin { lower_left, upper_left };
enum class ClipDepth { negative_one_to_one, zero_to_one };
template <>
struct Names<ClipOrigin> {
  static constexpr std::array<std::pair<ClipOrigin, std::string_view>, 2> table{{
      {ClipOrigin::lower_left, "lower_left"},
      {ClipOrigin::upper_left, "upper_left"},
  }};
};
template <>
struct Names<ClipDepth> {
  static constexpr std::array<std::pair<ClipDepth, std::string_view>, 2> table{{
      {ClipDepth::negative_one_to_one, "negative_one_to_one"},
      {ClipDepth::zero_to_one, "zero_to_one"},
  }};
};

// glViewport(x, y, width, height): x and y may be negative and the rectangle may reach beyond
// the framebuffer (only the framebuffer's pixels are drawn). Window pixels, as the floats GL
// keeps: whole numbers for glViewport; any float through glViewportIndexedf
// (GL_ARB_viewport_array, OpenGL 4.6 section 13.6.1), which GL interprets to
// GL_VIEWPORT_SUBPIXEL_BITS of precision.
struct Viewport {
  Viewport() = default;
  // glViewport's integers, and glViewportIndexedf's floats.
  Viewport(int x_, int y_, int width_, int height_)
      : x(float(x_)), y(float(y_)), width(float(width_)), height(float(height_)) {}
  Viewport(float x_, float y_, float width_, float height_)
      : x(x_), y(y_), width(width_), height(height_) {}
  float x = 0, y = 0, width = 0, height = 0;
  // Whether every bound is a whole number (glViewport can give it).
  bool integral() const {
    return x == std::floor(x) && y == std::floor(y) && width == std::floor(width) &&
           height == std::floor(height);
  }
  friend bool operator==(const Viewport&, const Viewport&) = default;
};

// glPolygonOffset(factor, units) with GL_POLYGON_OFFSET_FILL enabled (OpenGL 4.6 section
// 14.6.5): every fragment of a filled polygon has o = m·factor + r·units added to its z_w, m the
// polygon's largest depth slope and r the depth buffer's minimum resolvable difference
// (ref/depth_offset.hpp derives both and their freedom). `clamp`, when set, is
// glPolygonOffsetClamp's (GL 4.6 or GL_ARB_polygon_offset_clamp): o is at most clamp when clamp
// > 0, at least clamp when clamp < 0; 0 clamps nothing.
struct PolygonOffset {
  float factor = 0, units = 0;
  std::optional<float> clamp;
  friend bool operator==(const PolygonOffset&, const PolygonOffset&) = default;
};

// glScissor(x, y, width, height) with GL_SCISSOR_TEST enabled: only fragments of pixels
// x <= x_w < x + width, y <= y_w < y + height are kept (OpenGL 4.6 section 14.9.2). x and y may
// be negative, the box may reach beyond the framebuffer, a width or height of 0 keeps nothing.
struct Scissor {
  int x = 0, y = 0, width = 0, height = 0;
  friend bool operator==(const Scissor&, const Scissor&) = default;
};

// A rectangle of pixels, bounds inclusive: pixel (px, py) is in it when x0 <= px <= x1 and
// y0 <= py <= y1; empty when x0 > x1 or y0 > y1.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};

// How the verdict judges values and coverage.
//   spec:  the default. Per pixel, the error the GL specification allows an implementation that
//          reports GL_SUBPIXEL_BITS = subpixel_bits (see ref/allowance.hpp and docs/allowance.md).
//   ulps:  fixed thresholds: varying errors in ULPs of the attribute's scale (the ulp of the
//          largest |v_i| among the covering triangle's vertices for that component), depth in
//          ULPs of 1.0 (2^-23). Chosen when a case file or the command line names a number.
//   exact: zero differing bits and identical coverage, for a bit-exact model of one driver.
enum class ToleranceMode { spec, ulps, exact };
template <>
struct Names<ToleranceMode> {
  static constexpr std::array<std::pair<ToleranceMode, std::string_view>, 3> table{{
      {ToleranceMode::spec, "spec"},
      {ToleranceMode::ulps, "ulps"},
      {ToleranceMode::exact, "exact"},
  }};
};

struct Tolerance {
  ToleranceMode mode = ToleranceMode::spec;
  int subpixel_bits = 4;  // spec: the position freedom (at least the 4 GL requires)
  double varying_ulps = 64;
  double depth_ulps = 16;
  // Coverage mismatches explained by the specification's freedom (a centre exactly on an
  // edge, or within the snapping band of an edge) do not fail; gaps and double hits on shared
  // edges always do.
  bool allow_boundary = true;
};

// Optional fields in a case file; each set one overrides the default tolerance. A number of
// ULPs turns the case to fixed thresholds.
struct ToleranceOverride {
  std::optional<double> varying_ulps;
  std::optional<double> depth_ulps;
  std::optional<bool> allow_boundary;
  Tolerance applied_to(Tolerance t) const {
    if (varying_ulps) t.varying_ulps = *varying_ulps;
    if (depth_ulps) t.depth_ulps = *depth_ulps;
    if ((varying_ulps || depth_ulps) && t.mode == ToleranceMode::spec) t.mode = ToleranceMode::ulps;
    if (allow_boundary) t.allow_boundary = *allow_boundary;
    return t;
  }
};

struct Case {
  std::string name;         // unique; defaults to the file's stem
  std::string description;  // one line
  std::string source_path;  // the file it came from, for messages

  int fb_width = 64, fb_height = 64;
  Viewport viewport{0, 0, 64, 64};
  std::optional<Scissor> scissor;             // none: GL_SCISSOR_TEST disabled
  float depth_near = 0.0f, depth_far = 1.0f;  // glDepthRangef; n > f allowed
  ClipOrigin clip_origin = ClipOrigin::lower_left;
  ClipDepth clip_depth = ClipDepth::negative_one_to_one;
  // GL_DEPTH_CLAMP (OpenGL 4.6 sections 13.7 and 17.3.4): the near and far planes clip nothing,
  // and the depth test and the depth buffer take z_w clamped to [min(n, f), max(n, f)]
  // (fragment_depth).
  bool depth_clamp = false;
  // glPolygonOffset (GL_POLYGON_OFFSET_FILL enabled) or glPolygonOffsetClamp; none: disabled.
  std::optional<PolygonOffset> polygon_offset;

  CullFace cull = CullFace::none;
  FrontFace front_face = FrontFace::ccw;
  ProvokingVertex provoking = ProvokingVertex::last;
  DepthFunc depth_func = DepthFunc::always;
  // glClearDepth: the depth buffer's value before the first triangle, in [0, 1] (greater and
  // gequal draw nothing against 1.0).
  float depth_clear = 1.0f;
  // Whether the harness may work around a driver bug it finds in its first draw (gl_PrimitiveID
  // read without a geometry shader: gl_harness/first_draw.hpp). A case that checks the feature
  // itself turns this off, so that the bug is a failure of that case.
  bool work_arounds = true;

  std::vector<Varying> varyings;
  Distances distances;
  std::vector<Vertex> vertices;
  // The draw commands GL is given (core/draw.hpp), in order. Empty for a case that lists its
  // triangles: it is drawn as one glDrawElements(GL_TRIANGLES, GL_UNSIGNED_INT) of them
  // (draws_of, core/primitive_assembly.hpp).
  std::vector<Draw> draws;
  // The triangles GL rasterizes, indices into vertices, in drawing order: the case's own list,
  // or the assembly of its draws (assemble_triangles), each in an order with its primitive's
  // winding and its provoking vertex first or last as `provoking` says. Triangle t is the
  // frame's primitive t: gl_PrimitiveID plus the number of triangles of the earlier draws.
  std::vector<std::array<uint32_t, 3>> triangles;

  ToleranceOverride tolerance;

  int component_count() const {
    int n = 0;
    for (const auto& v : varyings)
      n += v.size;
    return n;
  }
};

// For each triangle of c, the first triangle (by primitive, possibly itself) whose three clip
// positions are bitwise the same as its own, in the same order. GL's invariance rules (OpenGL
// 4.6 appendix A.3, the corollaries of rule 2: fragment generation, and the window x, y and z of
// every fragment generated, do not depend on the framebuffer's contents; with A.1's
// repeatability, the same primitive under the same state generates the same fragments) make such
// copies rasterize identically with identical depths, so the depth test between a triangle and
// an earlier copy is decided as for
// equal depths, whatever rounding either involves (the reference's depth test, ref/render.cpp;
// selftest's fault of a copy that wins it). Only the same order counts: a copy with its
// vertices rotated is another primitive to GL (its attribute planes may be anchored at another
// vertex), and its depths may differ within the allowance. So does the kind of primitive: a
// strip's odd triangle and a GL_TRIANGLES triangle with the same vertex order are not taken for
// the same primitive, nor a fan's triangle and a strip's (AssembledTriangles::kind).
std::vector<int32_t> identical_triangles(const Case& c);
// The pixels a fragment may be written to whatever the triangle: the framebuffer's, within the
// scissor box when the case has one (pixel ownership and the scissor test, OpenGL 4.6 sections
// 14.9.1 and 14.9.2). The viewport is not in it: clipping keeps fragments inside the viewport,
// and an implementation that clips to a guard band instead scissors to the viewport as well
// (ref/ rasterizes within scissor_region ∩ the viewport; the driver models clip).
PixelRect scissor_region(const Case& c);
// The clip-space y the viewport transform reads (OpenGL 4.6 section 13.8.1): GL_UPPER_LEFT
// negates y_d = y_c / w_c, which is y_c negated, exactly, in float and in the rationals. So a
// case under GL_UPPER_LEFT draws what the same case under GL_LOWER_LEFT draws with every y_c
// negated and the facing reversed (facing_reversed).
inline double window_y_c(const Case& c, double y_c) {
  return c.clip_origin == ClipOrigin::upper_left ? -y_c : y_c;
}
// Whether the sign of a triangle's window-space area is negated before glFrontFace reads it
// (OpenGL 4.6 section 14.6.1, equation 14.8's note): under GL_UPPER_LEFT.
inline bool facing_reversed(const Case& c) {
  return c.clip_origin == ClipOrigin::upper_left;
}
// The distance of a clip-space point from the view volume's near plane, >= 0 inside (OpenGL
// 4.6 section 13.7): z_c + w_c, or z_c under GL_ZERO_TO_ONE. Exact for the float inputs of a
// case in double (a sum of two floats of exponents within the double's range is rounded at
// most once, and its sign is exact).
inline double near_distance(const Case& c, double z_c, double w_c) {
  return c.clip_depth == ClipDepth::zero_to_one ? z_c : z_c + w_c;
}
// Whether a clip-space vertex lies inside the view volume (OpenGL 4.6 section 13.7), every
// plane closed. The user clip distances are not in it (outside_clip_distances).
// Under GL_DEPTH_CLAMP the near and far planes are not in it.
inline bool inside_view_volume(const Case& c, const std::array<float, 4>& clip) {
  const double x = clip[0], y = clip[1], z = clip[2], w = clip[3];
  return w > 0 && std::fabs(x) <= w && std::fabs(y) <= w &&
         (c.depth_clamp || (near_distance(c, z, w) >= 0 && z <= w));
}
// The depth a fragment of window depth z_w (its polygon offset added) takes to the depth test
// and the depth buffer: under GL_DEPTH_CLAMP, clamped to [min(n, f), max(n, f)] (OpenGL 4.6
// section 17.3.4); with a polygon offset, clamped to [0, 1] after the offset is added (section
// 14.6.5, for floating-point depth buffers too); otherwise z_w itself, which clipping keeps
// within the depth range. The bounds are floats, so clamping a float rounding of z_w gives the
// float rounding of the clamped z_w. NaN stays NaN.
inline float fragment_depth(const Case& c, float z_w) {
  if (c.depth_clamp) {
    const float lo = std::min(c.depth_near, c.depth_far), hi = std::max(c.depth_near, c.depth_far);
    return z_w < lo ? lo : z_w > hi ? hi : z_w;
  }
  if (c.polygon_offset) return z_w < 0.0f ? 0.0f : z_w > 1.0f ? 1.0f : z_w;
  return z_w;
}
// Whether a vertex is outside an enabled user clip plane: a clip distance below 0 (NaN too: no
// implementation keeps it).
inline bool outside_clip_distances(const Case& c, const Vertex& v) {
  for (int i = 0; i < c.distances.clip; ++i)
    if (c.distances.plane_enabled(i) && !(v.distances[size_t(i)] >= 0)) return true;
  return false;
}
// Whether triangle t is discarded by a cull distance: one of them negative at all three
// vertices (GL_ARB_cull_distance; decided on the primitive's own vertices, before clipping).
inline bool culled_by_distance(const Case& c, const std::array<uint32_t, 3>& t) {
  for (int k = c.distances.clip; k < c.distances.clip + c.distances.cull; ++k) {
    bool all = true;
    for (uint32_t i : t)
      all = all && c.vertices[i].distances[size_t(k)] < 0;
    if (all) return true;
  }
  return false;
}
// How z_w changes per unit of z_d: (f − n)/2, or f − n under GL_ZERO_TO_ONE (section 13.8.1),
// in double (an error bound's factor, never a value compared).
inline double depth_range_scale(const Case& c) {
  const double range = double(c.depth_far) - double(c.depth_near);
  return c.clip_depth == ClipDepth::zero_to_one ? range : range / 2;
}

// Channel names of a case's frame, in Frame::components order: "name.x", "name.y", ...
std::vector<std::string> component_names(const Case& c);
// The name of channel ch of a case's frame: "depth", or its component's (component_names).
std::string channel_name(const Case& c, Channel ch);
// The varying each component belongs to.
std::vector<int> component_varying(const Case& c);
// The varying component k belongs to, and which of its components it is (0 for x .. 3 for w);
// without a vector (component_varying's) made per call.
struct VaryingComponent {
  size_t varying = 0;
  int component = 0;
};
VaryingComponent varying_component(const Case& c, int k);

// GL guarantees its floating-point arithmetic for magnitudes up to 2^32 only (OpenGL 4.6
// section 2.3.4.1, "Floating-Point Computation"): a case with a clip coordinate or a clip or
// cull distance of a vertex a triangle uses, or an interpolated (not flat) value, beyond that
// asks for something no implementation promises; so does a denormal clip coordinate or
// distance, which may be flushed to 0. The
// reason, naming the first such number, or nothing when every input computed on is within the
// range.
inline constexpr double kSpecifiedMagnitude = 0x1p32;
std::optional<std::string> outside_specified_range(const Case& c);

}  // namespace glrc
