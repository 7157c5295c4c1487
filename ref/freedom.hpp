// Position freedom: how far the vertices an implementation actually rasterizes may lie from the
// exact ones, per pixel. It is derived from the polygon an implementation rasterizes, not from
// the triangle the case gives, because a vertex the clipper throws away is never turned into a
// window position by anybody: it only matters through the new vertices clipping makes.
//
// Which polygon. Mesa's clipper cuts the triangle against all six planes of the view volume,
// x and y first, then near and far: that polygon, each vertex with its own rounding. A
// guard-band rasterizer draws a triangle whose vertices lie inside its guard band
// (kGuardBandPixels from the viewport's centre) without clipping it: then the triangle itself,
// each vertex with its window position's rounding, is taken too, and the freedom is the larger.
// Not covered: an implementation that clips near and far first and builds attribute planes from
// the vertices it computes there, where w_c cancels near the eye (hardware that clips near and
// far keeps its planes from the triangle's own vertices).
//
// Each vertex's freedom (pixels, in x and in y):
//   snapping   2^-bits: any grid of at least the GL_SUBPIXEL_BITS reported, any rounding;
//   rounding   c_p·u·(max(|x_w|, |y_w|) + M), the divide and viewport transform in float32 (M:
//              the largest viewport coordinate);
//   clipping   for a vertex made by clipping edge A-B at C = A + t·(B - A): whatever t an
//              implementation computes, the point A + t·(B - A) lies on the triangle's own plane,
//              with values consistent with it, so an error in t only slides the vertex along the
//              edge, which changes no value. What does leave the plane is the rounding of each
//              component of C on its own: 2u·τ·|B_k - A_k| + u·|C_k| with τ the part of the edge
//              stepped over from the endpoint interpolated from. Mesa's clipper (draw_pipe_clip.c)
//              interpolates from the endpoint nearer the plane, τ = min(t, 1 - t), so no
//              cancellation; e_k = u·(c_c·τ·|B_k - A_k| + |C_k|) with c_c = 2, plus the errors A
//              and B already carry, (1 - t)·e_A + t·e_B (a corner made by two planes). In the
//              window that is (e_x + |x_c/w_c|·e_w)/w_c times half the viewport width, likewise y.
// z_w moves likewise by (e_z + |z_c/w_c|·e_w)/w_c·|f - n|/2, and 1/w_c by a relative e_w/w_c.
//
// Per pixel. Moving the polygon's vertex j by d_j moves the value at a pixel by -λ_j ∇v·d_j, with
// λ_j the pixel's barycentric weight in the polygon's triangle (the implementation's fan) that
// holds it; so the freedom at a pixel is Σ λ_j δ_j. The largest of that over every way to cut the
// polygon into triangles is the least concave majorant of the δ_j (ConcaveEnvelope), which needs
// no knowledge of the fan. A far vertex therefore counts in proportion to its weight at the pixel,
// and the bound is continuous in the vertices: no jump when w_c crosses 0.
//
// What the two principles give: one vertex at w_c = 2^-20 is clipped away; the new vertices are
// made from clip coordinates of magnitude 1 and lie inside the view volume, so the freedom stays
// near 2^-bits (tight). A triangle whose clip coordinates reach 2^21 gets new vertices computed
// from magnitudes of 2^21: e_k ~ 2^-1, tens of pixels in the window (wide).
#pragma once

#include <array>
#include <vector>

#include "core/case.hpp"
#include "ref/blocks.hpp"
#include "ref/setup.hpp"
#include "ref/viewport.hpp"

namespace glrc::ref {

inline constexpr double kClipRoundings = 2;
// An implementation's guard band, pixels from the viewport's centre. Its size matters little: a
// vertex's rounding grows with its distance, and its weight at the visible pixels shrinks.
inline constexpr double kGuardBandPixels = 65536;

// The least concave function over the plane that is at least `value` at each point (x, y,
// value): at a point inside the points' hull, the largest Σ λ_j value_j over all triangles of
// the points that hold it. Evaluated as the minimum of its facets' planes, clamped to the
// values' range outside the hull. Fewer than three points not on one line: the largest value.
class ConcaveEnvelope {
 public:
  ConcaveEnvelope() = default;
  explicit ConcaveEnvelope(const std::vector<std::array<double, 3>>& points);
  double at(double x, double y) const;
  // at() of kRowBlock points (x[j], y[j]) at once, bit for bit (ref/blocks.hpp).
  void at(const double* x, const double* y, double* out) const;
  // Bounds of what at(x, y) computes for every x in [x0, x1] on the line y: lo <= at(x, y) <= hi
  // (ref/deferred.hpp's runs). The minimum of planes is concave, so along a segment it is
  // least at an end, and no larger than any one plane, which is largest at an end; each plane's
  // rounding is allowed for.
  std::array<double, 2> range(double x0, double x1, double y) const;
  double largest() const { return hi_; }
  // The largest |a| + |b| of its planes (0 for none): at() at (x', y') is at most at() at
  // (x, y) plus slope()·max(|x' - x|, |y' - y|), since the plane that is least at (x, y)
  // bounds every plane's least at (x', y') from above, and at() is the least plane clamped to
  // [lo, hi], so never below lo.
  double slope() const { return slope_; }

 private:
  std::vector<std::array<double, 3>> planes_;  // a·x + b·y + c
  double lo_ = 0, hi_ = 0, slope_ = 0;
};

// One vertex of the polygon an implementation rasterizes, with the freedom it has.
struct PolygonVertex {
  double x_w = 0, y_w = 0;  // window position (pixels)
  double delta = 0;         // position freedom, pixels, in x and in y
  double viewport = 0;      // the part of delta from the viewport's precision (viewport_shift)
  double depth = 0;         // freedom of z_w from clipping arithmetic (z_w units)
  double z_w = 0;           // window depth, unclamped (z_w units)
  double weight = 0;        // relative freedom of 1/w_c from clipping arithmetic
  double w_c = 1;
  int generation = 0;  // clip planes that made it; 0 for a vertex of the case
};

// Triangle t clipped in clip space against the view volume in Mesa's order (x, y, then near
// and far), each vertex with its freedom for an implementation reporting `subpixel_bits`.
// Empty when nothing of the triangle is left. With `z_clip`, also the vertices of the polygon
// clipped against x and y only, as {x_w, y_w, (e_z + e_w)/w_c} (window pixels, z_n units; vertices
// with w_c <= 0 left out): the freedom of the near and far planes' cut (PositionFreedom); and,
// where the case enables clip distances, the vertices of the polygon the view volume leaves, as
// {x_w, y_w, max e_d/w_c} (units of d/w_c), the freedom of the user planes' cut. With
// `reaches_eye`, whether the polygon left has a vertex at w_c <= 0 (then it is returned empty:
// the triangle's plane holds the eye, its window image is a line, and that vertex's window
// position, x_c/w_c with w_c = 0, is not defined), or one whose w_c is no larger than the
// rounding error of its own computation (e_w >= w_c: a vertex made by cutting an edge that
// passes within rounding of the eye, whose w_c an implementation may compute as 0 or less).
std::vector<PolygonVertex> clipped_polygon(const Case& c, const TriangleSetup& t, int subpixel_bits,
                                           std::vector<std::array<double, 3>>* z_clip = nullptr,
                                           bool* reaches_eye = nullptr);

// Whether a triangle with window positions p (pixels, each within rounding[j] of where an
// implementation computes it in float32, in x and in y) may have a doubled area of the other
// sign, or 0, as some conforming implementation rasterizes it: one that does not snap (its
// positions anywhere within their rounding), or one that snaps every vertex with one function
// onto a grid of 2^-b pixels, b >= subpixel_bits: one offset for all three vertices and one
// rule (down, up, or to the nearest, a tie either way), after the rounding. Snapped
// differences are whole grid steps, which the box of ±2^-b around each vertex does not know:
// two rim vertices of a thin fan triangle 0.3 pixels apart snap to the same side of each other
// whatever the grid's offset. Exact for each grid (every pair of snapped differences along x
// and y, a handful each, enumerated), in every grid down to the one where a first-order bound
// on the vertices' moves decides it; a grid finer than a vertex's rounding (4 steps or more)
// that the bound does not decide is taken as free.
bool orientation_may_change(const std::array<std::array<double, 2>, 3>& p,
                            const std::array<double, 3>& rounding, int subpixel_bits);

// A piece of a clipped polygon that may turn over or vanish: three of its vertices (window
// pixels), each within `delta` of where an implementation puts it, in x and in y.
struct TurningPiece {
  std::array<std::array<double, 2>, 3> p{};
  double delta = 0;
};
// The pieces of a clipped polygon (window positions in order, each vertex with its freedom
// PolygonVertex::delta) that may turn over or vanish as some conforming implementation snaps
// and rounds its vertices: any three of its vertices (every triangle of some fan of it: each
// of a convex polygon's triangulations is an implementation's choice), each judged by
// orientation_may_change. A clip plane that cuts within rounding of another vertex makes a
// vertex beside it, and a sliver piece that, turned over, covers centres its neighbours cover
// too (or, culled, leaves them): llvmpipe drew a shared edge's centre twice that way, found by
// a `distances` campaign (tests/ref/test_freedom.cpp). The centres such a piece may cover
// (Sliver) are free, not the rest of the triangle.
std::vector<TurningPiece> turning_pieces(const std::vector<PolygonVertex>& polygon,
                                         int subpixel_bits);

// The freedom of one triangle, per pixel: the largest of the polygons' envelopes (see above).
class PositionFreedom {
 public:
  PositionFreedom() = default;
  PositionFreedom(const Case& c, const TriangleSetup& t, int subpixel_bits);
  // δ at the centre of pixel (px, py), pixels.
  double at(int px, int py) const;
  // at(), depth_at() and weight_at() of kRowBlock pixels (px[j], py[j]) (integer pixel
  // coordinates as doubles) at once, bit for bit (ref/blocks.hpp).
  void at(const double* px, const double* py, double* out) const;
  void depth_at(const double* px, const double* py, double* out) const;
  void weight_at(const double* px, const double* py, double* out) const;
  // Bounds {lo, hi} of what at(), weight_at() and depth_at() give at the centres of pixels px0..px1
  // of row py (px0 <= px1): lo <= each <= hi. The weight's hi is infinite where the envelope of
  // 1/w_c may reach 0 on the run.
  std::array<double, 2> range(int px0, int px1, int py) const;
  std::array<double, 2> weight_range(int px0, int px1, int py) const;
  // The same of depth_at().
  std::array<double, 2> depth_range(int px0, int px1, int py) const {
    return depth_.range(px0 + 0.5, px1 + 0.5, py + 0.5);
  }
  // Freedom of z_w at the pixel from the clipping of depth (0 for an unclipped triangle).
  double depth_at(int px, int py) const;
  // Freedom of z_n at the pixel where the near and far planes decide coverage: clipping
  // against x and y (first, as Mesa does) makes vertices whose z_c and w_c are rounded
  // (e_z, e_w of the polygon's vertices), so the sign of w_c ∓ z_c of the polygon the near and
  // far planes then cut may differ from the exact one within Σ λ_j (e_z,j + e_w,j)/w_c,j, the
  // least concave majorant of those over that polygon's vertices. 0 where no vertex was made.
  double z_clip_at(int px, int py) const { return z_clip_.at(px + 0.5, py + 0.5); }
  double z_clip_largest() const { return z_clip_.largest(); }
  // How much a smooth value may move at the pixel, as a share of the triangle's spread, from
  // the relative errors ρ_j of clipped vertices' 1/w_c: a value is Σ μ_j v_j with perspective
  // weights μ_j = λ_j (1/w_j) / (1/w), and re-weighting vertex j by 1 + ρ_j moves it by at most
  // Σ μ_j ρ_j·spread = (Σ λ_j ρ_j/w_j)·w at the pixel, the sum taken as an envelope again.
  double weight_at(int px, int py) const;
  // The largest 1/w_c of the clipped polygon's vertices (0 when nothing is left).
  double largest_inverse_w() const { return largest_inverse_w_; }
  // How many clip planes made the polygon's newest vertex (0 when nothing is clipped).
  int generations() const { return generations_; }
  // The largest δ of any vertex: how far any edge can move.
  double largest() const;
  // The largest float rounding of any vertex's window position: its δ less the snapping and
  // the viewport's precision (what an implementation with planes from its unsnapped positions
  // moves each vertex by on its own).
  double rounding() const { return rounding_; }
  // The largest slope() of the δ envelopes at() takes the larger of.
  double slope() const { return std::max(delta_[0].slope(), delta_[1].slope()); }
  // What an implementation may rasterize, as window positions: the clipped polygon (the
  // triangle itself when nothing is clipped; empty when nothing is left), and the triangle
  // itself when a guard-band rasterizer would draw it unclipped (else empty).
  const std::vector<std::array<double, 2>>& polygon() const { return polygon_; }
  const std::vector<std::array<double, 2>>& guard_band_triangle() const { return whole_; }
  // The clipped polygon's vertices with their freedoms (clipped_polygon; empty when nothing is
  // left).
  const std::vector<PolygonVertex>& polygon_vertices() const { return vertices_; }
  // The largest |z_w| (unclamped) of any vertex an implementation may set up: the clipped
  // polygon's, and the whole triangle's where a guard-band rasterizer draws it unclipped. The
  // scale of the float rounding of depth (under GL_DEPTH_CLAMP z_w is not bounded by the depth
  // range).
  double largest_depth() const { return largest_depth_; }
  // Whether the triangle's orientation can change (it may turn over, or become degenerate)
  // as some implementation snaps and rounds its vertices (orientation_may_change, from the
  // triangle's own vertices): then the coverage of the pixels it may reach is
  // not decided by the specification. Needs every w_c > 0; a triangle reaching behind the eye
  // is never that thin: unless its plane holds the eye, its window image reaches the window's
  // sides where the polygon's vertices have w_c as small as the plane's distance from the eye,
  // and the freedom as large as their rounding over that (a plane that holds it: zero area,
  // sliver_sources).
  bool may_turn_over() const { return may_turn_over_; }
  // The pieces of the clipped polygon that may turn over (turning_pieces; none where no clip
  // plane made a vertex): coverage near them, within Sliver's reach of each, is not decided.
  const std::vector<TurningPiece>& turning_pieces() const { return turning_pieces_; }
  // For a triangle of zero area (det = 0 in setup_triangle: its window image is a segment, or a
  // point), which the exact rasterization never draws but an implementation's rounded vertices
  // may turn into a sliver: the window positions that sliver's vertices come from, each moved by
  // at most largest() in x and in y. They are the clipped polygon's vertices, the guard-band
  // triangle's, and, where the near or far plane cuts the triangle, the vertices of the polygon
  // clipped against x and y only (where that cut lies has a freedom of its own, z_clip_at: the
  // whole polygon before the cut bounds it). All on one line, up to the rounding of doubles.
  // Empty for a triangle with edges (TriangleSetup::has_edges).
  const std::vector<std::array<double, 2>>& sliver_sources() const { return sliver_sources_; }
  // Whether the clipped polygon reaches the eye, exactly or within the rounding of its vertices
  // (clipped_polygon): a vertex an implementation computes there in float32 may have w_c <= 0,
  // so its window position, z_w and 1/w_c may be anything (an infinite 1/w_c makes NaN of a
  // value of 0): the pixels the triangle may cover, and its smooth and noperspective values and
  // depth, are not determined. Exactly only a triangle whose plane holds the eye (zero area in
  // the window) reaches it; within rounding, one with an edge that passes that near the eye.
  bool reaches_eye() const { return reaches_eye_; }

 private:
  // The clipped polygon, the whole triangle in a guard band.
  std::array<ConcaveEnvelope, 2> delta_;
  ConcaveEnvelope depth_, weight_, inverse_w_, z_clip_;
  std::vector<std::array<double, 2>> polygon_, whole_, sliver_sources_;
  std::vector<PolygonVertex> vertices_;
  double largest_depth_ = 0;
  std::vector<TurningPiece> turning_pieces_;
  int generations_ = 0;
  double largest_inverse_w_ = 0, rounding_ = 0;
  bool may_turn_over_ = false, reaches_eye_ = false;
};

}  // namespace glrc::ref
