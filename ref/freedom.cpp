#include "ref/freedom.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "ref/allowance.hpp"
#include "ref/exact.hpp"

namespace glrc::ref {

namespace {

// A vertex in clip space with the absolute error bound of each component.
struct ClipVertex {
  std::array<double, 4> p{}, e{};
  // The enabled user clip planes' distances and their errors (empty for a case without).
  std::vector<double> d, ed;
  int generation = 0;
};

// The largest magnitude of the viewport's centre: x_w = x_n·w/2 + (x + w/2) rounds the product
// and the sum, an error of u·(|x_w| + |x + w/2|) at most.
double viewport_magnitude(const Viewport& vp) {
  return std::max(std::fabs(vp.x + vp.width / 2.0), std::fabs(vp.y + vp.height / 2.0));
}

double snap_and_round(double x_w, double y_w, double m, int bits) {
  return std::ldexp(1.0, -bits) +
         kPositionRoundings * kFloatUnitRoundoff * (std::max(std::fabs(x_w), std::fabs(y_w)) + m);
}

// The snapped differences (S_1 - S_0, S_2 - S_0) of three positions along one axis, in grid
// steps, that one snapping function can give: the positions t_j (grid steps, relative to t_0)
// each anywhere in [t_j - r_j, t_j + r_j] (the float rounding before snapping), one offset
// a in [0, 1) for all three, and one rule: S = floor(a + t), ceil(a + t), or the nearest
// integer (a tie either way, per vertex: a rule like ties-to-even goes both ways). Each S_j is
// monotone in t_j, so over its interval it takes every integer from the rule at the low end to
// the rule at the high end; as a moves, those ends change only where a + t_j ± r_j crosses an
// integer (or a half), so a at every such crossing (each vertex's values on both sides of it,
// the ends widened by kSlack) and between them gives every pair there is.
std::vector<std::array<int64_t, 2>> snapped_differences(const std::array<double, 3>& t,
                                                        const std::array<double, 3>& r) {
  // Grid steps of widening: the doubles t_j and r_j are within this of the exact values.
  constexpr double kSlack = 0x1p-20;
  std::vector<std::array<int64_t, 2>> out;
  for (int rule = 0; rule < 3; ++rule) {
    const double shift = rule == 2 ? 0.5 : 0.0;  // nearest: floor(x + 1/2), ceil(x - 1/2)
    std::vector<double> offsets{0.0};
    for (size_t j = 0; j < 3; ++j)
      for (double end : {t[j] - r[j], t[j] + r[j]}) {
        const double a = shift - end - std::floor(shift - end);  // where a + end hits the grid
        offsets.push_back(a);
      }
    std::sort(offsets.begin(), offsets.end());
    const size_t crossings = offsets.size();
    for (size_t k = 0; k + 1 < crossings; ++k)
      offsets.push_back((offsets[k] + offsets[k + 1]) / 2);
    offsets.push_back((offsets[crossings - 1] + 1) / 2);
    for (double a : offsets) {
      std::array<int64_t, 3> lo{}, hi{};
      for (size_t j = 0; j < 3; ++j) {
        const double x0 = a + t[j] - r[j] - kSlack, x1 = a + t[j] + r[j] + kSlack;
        switch (rule) {
          case 0:
            lo[j] = int64_t(std::floor(x0)), hi[j] = int64_t(std::floor(x1));
            break;
          case 1:
            lo[j] = int64_t(std::ceil(x0)), hi[j] = int64_t(std::ceil(x1));
            break;
          default:
            lo[j] = int64_t(std::ceil(x0 - 0.5)), hi[j] = int64_t(std::floor(x1 + 0.5));
            break;
        }
      }
      for (int64_t s0 = lo[0]; s0 <= hi[0]; ++s0)
        for (int64_t s1 = lo[1]; s1 <= hi[1]; ++s1)
          for (int64_t s2 = lo[2]; s2 <= hi[2]; ++s2)
            out.push_back({s1 - s0, s2 - s0});
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

bool orientation_may_change(const std::array<std::array<double, 2>, 3>& p,
                            const std::array<double, 3>& rounding, int subpixel_bits) {
  const double area2 =
      (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
  // Each vertex within h_j of its place in x and in y moves 2·area by at most
  // Σ_j h_j·(|E_j.x| + |E_j.y|) to first order (E_j the edge opposite vertex j: the gradient of
  // 2·area in vertex j is E_j turned by 90 degrees), and by at most 8·h² more (the cross
  // product of two moves of up to 2h per axis), h the largest h_j. The doubles' own rounding
  // of p is allowed for by 2^-30 of the magnitudes.
  double magnitude = 0;
  for (const auto& v : p)
    magnitude = std::max({magnitude, std::fabs(v[0]), std::fabs(v[1])});
  const double slack = std::ldexp(1 + magnitude, -30);
  auto moves = [&](double step) {
    double bound = 0, largest = 0;
    for (size_t j = 0; j < 3; ++j) {
      const auto& a = p[(j + 1) % 3];
      const auto& b = p[(j + 2) % 3];
      const double h = step + rounding[j] + slack;
      bound += h * (std::fabs(b[0] - a[0]) + std::fabs(b[1] - a[1]));
      largest = std::max(largest, h);
    }
    return bound + 8 * largest * largest;
  };
  // Rounding alone (an implementation that does not snap, or snaps as finely as it likes).
  if (!(std::fabs(area2) > moves(0))) return true;
  // Each grid of 2^-b pixels, b from the bits up: a finer grid moves each vertex less, so once
  // the bound holds for one it holds for all finer ones. Within the bound, the area each grid
  // gives is computed exactly, from every pair of snapped differences along x and along y.
  for (int b = std::max(subpixel_bits, 0); b <= 48; ++b) {
    const double step = std::ldexp(1.0, -b);
    if (std::fabs(area2) > moves(step)) return false;
    std::array<std::vector<std::array<int64_t, 2>>, 2> axis;
    for (size_t k = 0; k < 2; ++k) {
      std::array<double, 3> t{}, r{};
      for (size_t j = 0; j < 3; ++j)
        t[j] = (p[j][k] - p[0][k]) / step, r[j] = (rounding[j] + slack) / step;
      // A grid finer than the rounding (each vertex anywhere over several steps) adds nothing
      // the first-order bound, which did not decide, leaves out; and its enumeration grows with
      // the steps the rounding spans, its integers past 2^52 far from the first vertex. Taken
      // as free.
      for (size_t j = 0; j < 3; ++j)
        if (!(r[j] <= 4 && std::fabs(t[j]) < 0x1p52)) return true;
      axis[k] = snapped_differences(t, r);
    }
    for (const auto& x : axis[0])
      for (const auto& y : axis[1]) {
        const int128 snapped = int128(x[0]) * y[1] - int128(x[1]) * y[0];
        if (snapped == 0 || (snapped > 0) != (area2 > 0)) return true;
      }
  }
  return true;  // not decided within 2^-48 pixels: taken as free
}

ConcaveEnvelope::ConcaveEnvelope(const std::vector<std::array<double, 3>>& points) {
  if (points.empty()) return;
  lo_ = hi_ = points[0][2];
  for (const auto& p : points)
    lo_ = std::min(lo_, p[2]), hi_ = std::max(hi_, p[2]);
  const size_t n = points.size();
  // At most nine vertices (a triangle clipped by six planes): every triple is cheap. A triple's
  // plane is a facet of the upper hull when no point lies above it.
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        const auto &p = points[i], &q = points[j], &r = points[k];
        const double ux = q[0] - p[0], uy = q[1] - p[1], uv = q[2] - p[2];
        const double wx = r[0] - p[0], wy = r[1] - p[1], wv = r[2] - p[2];
        const double nz = ux * wy - uy * wx;
        if (!(std::fabs(nz) > 1e-12 * std::hypot(ux, uy) * std::hypot(wx, wy))) continue;
        const double a = -(uy * wv - uv * wy) / nz, b = -(uv * wx - ux * wv) / nz;
        const double c = p[2] - a * p[0] - b * p[1];
        bool facet = true;
        for (const auto& s : points) {
          const double plane = a * s[0] + b * s[1] + c;
          const double slack =
              1e-9 * (std::fabs(a * s[0]) + std::fabs(b * s[1]) + std::fabs(c) + std::fabs(s[2]));
          if (s[2] > plane + slack) {
            facet = false;
            break;
          }
        }
        if (facet) {
          planes_.push_back({a, b, c});
          slope_ = std::max(slope_, std::fabs(a) + std::fabs(b));
        }
      }
}

double ConcaveEnvelope::at(double x, double y) const {
  if (planes_.empty()) return hi_;
  double v = INFINITY;
  for (const auto& p : planes_)
    v = std::min(v, p[0] * x + p[1] * y + p[2]);
  return std::clamp(v, lo_, hi_);
}

GLRC_BLOCK_FORM void ConcaveEnvelope::at(const double* x, const double* y, double* out) const {
  constexpr int n = kRowBlock;
  if (planes_.empty()) return (void)std::fill(out, out + n, hi_);
  double v[n];
  std::fill(v, v + n, INFINITY);
  for (const auto& p : planes_)
    for (int j = 0; j < n; ++j) {
      const double t = p[0] * x[j] + p[1] * y[j] + p[2];
      v[j] = t < v[j] ? t : v[j];  // std::min(v, t)
    }
  for (int j = 0; j < n; ++j)  // std::clamp(v, lo_, hi_)
    out[j] = v[j] < lo_ ? lo_ : hi_ < v[j] ? hi_ : v[j];
}

std::array<double, 2> ConcaveEnvelope::range(double x0, double x1, double y) const {
  if (planes_.empty()) return {hi_, hi_};
  // Each plane's value a·x + b·y + c computed in double is within two roundings (one when
  // fused) of the exact one, 2^-52 of its terms' magnitudes: s below, four times that. The
  // exact minimum is concave along the segment, at least its ends' least value; the computed
  // one is within s of it; and no computed plane exceeds its exact value at either end by more.
  double lo = INFINITY, hi = INFINITY, slack = 0;
  const double x = std::max(std::fabs(x0), std::fabs(x1));
  for (const auto& p : planes_) {
    const double a0 = p[0] * x0 + p[1] * y + p[2], a1 = p[0] * x1 + p[1] * y + p[2];
    const double s = 0x1p-50 * (std::fabs(p[0]) * x + std::fabs(p[1] * y) + std::fabs(p[2]));
    lo = std::min({lo, a0, a1});
    hi = std::min(hi, std::max(a0, a1) + 2 * s);
    slack = std::max(slack, s);
  }
  lo -= 2 * slack;
  // std::clamp(v, lo_, hi_), as at() applies it, is monotone.
  return {std::clamp(lo, lo_, hi_), std::clamp(hi, lo_, hi_)};
}

std::vector<PolygonVertex> clipped_polygon(const Case& c, const TriangleSetup& t, int subpixel_bits,
                                           std::vector<std::array<double, 3>>* z_clip,
                                           bool* reaches_eye) {
  if (reaches_eye) *reaches_eye = false;
  std::vector<ClipVertex> poly;
  for (uint32_t index : t.index) {
    ClipVertex v;
    for (int k = 0; k < 4; ++k)
      v.p[size_t(k)] = double(c.vertices[index].clip[size_t(k)]);
    v.p[1] = window_y_c(c, v.p[1]);  // GL_UPPER_LEFT: the y planes are symmetric
    for (int k = 0; k < c.distances.clip; ++k)
      if (c.distances.plane_enabled(k)) v.d.push_back(c.vertices[index].distances[size_t(k)]);
    v.ed.assign(v.d.size(), 0.0);
    poly.push_back(v);
  }
  const int planes = 6 + int(poly.front().d.size());
  // Signed distances to the six planes of the view volume, >= 0 inside, in Mesa's order:
  // x >= -w_c, x <= w_c, y likewise, then z (the near plane as glClipControl puts it), then
  // the enabled user clip planes.
  auto distance = [&](const ClipVertex& v, int plane) {
    const double w = v.p[3];
    if (plane >= 6) return v.d[size_t(plane - 6)];
    // Under GL_DEPTH_CLAMP the near and far planes cut nothing (every vertex is inside).
    if (plane >= 4 && c.depth_clamp) return 1.0;
    if (plane == 4) return near_distance(c, v.p[2], w);
    const size_t axis = size_t(plane / 2);
    return plane % 2 == 0 ? w + v.p[axis] : w - v.p[axis];
  };
  // A vertex of the polygon a plane cuts, with w_c > 0, into z_clip: its window position and
  // the error of its distance to that plane (`error`, clip units) over w_c.
  auto add_z_clip = [&](const ClipVertex& v, double error) {
    const double w = v.p[3];
    if (!(w > 0)) return;
    const Viewport& vp = c.viewport;
    z_clip->push_back({vp.x + vp.width / 2.0 * (1 + v.p[0] / w),
                       vp.y + vp.height / 2.0 * (1 + v.p[1] / w), error / w});
  };
  for (int plane = 0; plane < planes && !poly.empty(); ++plane) {
    if (plane == 6 && z_clip) {
      // The polygon the user clip planes cut (after the view volume, as in Mesa's clipper):
      // the sign of a distance d at a vertex may differ from the exact one within its error
      // e_d, e_d/w_c in units of d/w_c, the largest over the planes. Added to the near and
      // far planes' points below: the envelope over both bounds each.
      for (const ClipVertex& v : poly)
        add_z_clip(v, *std::max_element(v.ed.begin(), v.ed.end()));
    }
    if (plane == 4 && z_clip && !c.depth_clamp) {
      // The polygon the near and far planes cut: each vertex's z_c and w_c carry e_z and e_w,
      // so the sign of w_c ∓ z_c may differ from the exact one within (e_z + e_w)/w_c in z_n
      // (e_z + |z_n|·e_w would be the error of z_n itself; the sign is of the difference).
      // Under GL_ZERO_TO_ONE the near plane's z_c alone is within e_z/w_c: the same bound
      // holds it.
      for (const ClipVertex& v : poly)
        add_z_clip(v, v.e[2] + v.e[3]);
    }
    std::vector<ClipVertex> out;
    for (size_t i = 0; i < poly.size(); ++i) {
      const ClipVertex& a = poly[i];
      const ClipVertex& b = poly[(i + 1) % poly.size()];
      const double da = distance(a, plane), db = distance(b, plane);
      if (da >= 0) out.push_back(a);
      if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
        const double s = da / (da - db);
        ClipVertex m;
        m.generation = std::max(a.generation, b.generation) + 1;
        // Interpolated from the endpoint nearer the plane, as Mesa's clipper does: the step
        // taken is the shorter part of the edge, so no cancellation.
        const double step = std::min(s, 1 - s);
        for (size_t k = 0; k < 4; ++k) {
          m.p[k] = a.p[k] + s * (b.p[k] - a.p[k]);
          m.e[k] = (1 - s) * a.e[k] + s * b.e[k] +
                   kFloatUnitRoundoff *
                       (kClipRoundings * step * std::fabs(b.p[k] - a.p[k]) + std::fabs(m.p[k]));
        }
        // The clip distances are interpolated as the position is (Mesa: with the same t).
        m.d.resize(a.d.size()), m.ed.resize(a.d.size());
        for (size_t k = 0; k < a.d.size(); ++k) {
          m.d[k] = a.d[k] + s * (b.d[k] - a.d[k]);
          m.ed[k] = (1 - s) * a.ed[k] + s * b.ed[k] +
                    kFloatUnitRoundoff *
                        (kClipRoundings * step * std::fabs(b.d[k] - a.d[k]) + std::fabs(m.d[k]));
        }
        out.push_back(m);
      }
    }
    poly = std::move(out);
  }
  std::vector<PolygonVertex> result;
  if (poly.size() < 3) return result;
  const Viewport& vp = c.viewport;
  const double half_w = vp.width / 2.0, half_h = vp.height / 2.0;
  const double m = viewport_magnitude(vp);
  for (const ClipVertex& v : poly) {
    const double w = v.p[3];
    // After the six planes, only the eye itself: nothing the exact rasterization draws.
    if (!(w > 0)) {
      if (reaches_eye) *reaches_eye = true;
      return {};
    }
    const double xn = v.p[0] / w, yn = v.p[1] / w, zn = v.p[2] / w;
    PolygonVertex out;
    out.x_w = vp.x + half_w + xn * half_w;
    out.y_w = vp.y + half_h + yn * half_h;
    out.generation = v.generation;
    const double clip_x = half_w * (v.e[0] + std::fabs(xn) * v.e[3]) / w;
    const double clip_y = half_h * (v.e[1] + std::fabs(yn) * v.e[3]) / w;
    out.viewport = viewport_shift(vp, out.x_w, out.y_w);
    out.delta = snap_and_round(out.x_w, out.y_w, m, subpixel_bits) + std::max(clip_x, clip_y) +
                out.viewport;
    out.depth = std::fabs(depth_range_scale(c)) * (v.e[2] + std::fabs(zn) * v.e[3]) / w;
    out.z_w = approximate_depth(c, zn);
    out.weight = v.e[3] / w;
    out.w_c = w;
    // Within its rounding of the eye: the w_c an implementation computes may be 0 or negative.
    if (reaches_eye && !(v.e[3] < w)) *reaches_eye = true;
    result.push_back(out);
  }
  return result;
}

std::vector<TurningPiece> turning_pieces(const std::vector<PolygonVertex>& polygon,
                                         int subpixel_bits) {
  std::vector<TurningPiece> out;
  const size_t n = polygon.size();
  const double snapping = std::ldexp(1.0, -subpixel_bits);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        TurningPiece piece;
        std::array<double, 3> rounding{};
        const std::array<size_t, 3> corners{i, j, k};
        for (size_t v = 0; v < 3; ++v) {
          const PolygonVertex& q = polygon[corners[v]];
          piece.p[v] = {q.x_w, q.y_w};
          // The freedom less the snapping it counts, and the viewport's precision: one
          // transform for all the vertices, which turns nothing over.
          rounding[v] = q.delta - snapping - q.viewport;
          piece.delta = std::max(piece.delta, q.delta);
        }
        if (orientation_may_change(piece.p, rounding, subpixel_bits)) out.push_back(piece);
      }
  return out;
}

PositionFreedom::PositionFreedom(const Case& c, const TriangleSetup& t, int subpixel_bits) {
  const Viewport& vp = c.viewport;
  const double m = viewport_magnitude(vp);
  bool clipped = false, in_guard_band = true, depth_clipped = false;
  double whole_depth = 0;
  std::vector<std::array<double, 3>> whole;
  for (uint32_t index : t.index) {
    const auto& p = c.vertices[index].clip;
    const double w = p[3];
    // A user clip plane cuts as the near and far planes do (z_clip_at holds both's freedom).
    const bool user_clipped = outside_clip_distances(c, c.vertices[index]);
    clipped = clipped || !inside_view_volume(c, p) || user_clipped;
    depth_clipped = depth_clipped || !(w > 0) ||
                    (!c.depth_clamp && (near_distance(c, p[2], w) < 0 || p[2] > w)) || user_clipped;
    if (!(w > 0)) {
      in_guard_band = false;
      continue;
    }
    const auto [x_w, y_w] = approximate_window(c, p);
    const double centre_distance = std::max(std::fabs(x_w - (vp.x + vp.width / 2.0)),
                                            std::fabs(y_w - (vp.y + vp.height / 2.0)));
    in_guard_band = in_guard_band && centre_distance <= kGuardBandPixels;
    whole.push_back(
        {x_w, y_w, snap_and_round(x_w, y_w, m, subpixel_bits) + viewport_shift(vp, x_w, y_w)});
    whole_depth = std::max(whole_depth, std::fabs(approximate_depth(c, double(p[2]) / w)));
  }
  bool any = false;
  std::vector<std::array<double, 3>> z_clip;
  vertices_ = clipped_polygon(c, t, subpixel_bits, &z_clip, &reaches_eye_);
  if (!z_clip.empty()) z_clip_ = ConcaveEnvelope(z_clip);
  if (const std::vector<PolygonVertex>& polygon = vertices_; !polygon.empty()) {
    any = true;
    std::vector<std::array<double, 3>> delta, depth, weight, inverse_w;
    for (const PolygonVertex& v : polygon) {
      delta.push_back({v.x_w, v.y_w, v.delta});
      rounding_ = std::max(rounding_, v.delta - std::ldexp(1.0, -subpixel_bits) - v.viewport);
      depth.push_back({v.x_w, v.y_w, v.depth});
      weight.push_back({v.x_w, v.y_w, v.weight / v.w_c});
      inverse_w.push_back({v.x_w, v.y_w, 1 / v.w_c});
      largest_inverse_w_ = std::max(largest_inverse_w_, 1 / v.w_c);
      largest_depth_ = std::max(largest_depth_, std::fabs(v.z_w));
      generations_ = std::max(generations_, v.generation);
    }
    delta_[0] = ConcaveEnvelope(delta);
    for (const auto& d : delta)
      polygon_.push_back({d[0], d[1]});
    depth_ = ConcaveEnvelope(depth);
    if (generations_ > 0)
      weight_ = ConcaveEnvelope(weight), inverse_w_ = ConcaveEnvelope(inverse_w);
  }
  // A guard-band rasterizer draws a triangle whose vertices all lie inside its guard band
  // without clipping it in x and y.
  if (clipped && in_guard_band && whole.size() == 3) {
    delta_[1] = ConcaveEnvelope(whole), any = true;
    largest_depth_ = std::max(largest_depth_, whole_depth);
    for (const auto& d : whole) {
      whole_.push_back({d[0], d[1]});
      rounding_ = std::max(rounding_,
                           d[2] - std::ldexp(1.0, -subpixel_bits) - viewport_shift(vp, d[0], d[1]));
    }
  }
  if (!any) delta_[0] = ConcaveEnvelope({{0, 0, snap_and_round(0, 0, m, subpixel_bits)}});
  // Only a triangle of zero area (no edges) becomes a sliver; the others need no copies.
  if (!t.has_edges) {
    sliver_sources_ = polygon_;
    sliver_sources_.insert(sliver_sources_.end(), whole_.begin(), whole_.end());
    if (depth_clipped && !polygon_.empty())
      for (const auto& v : z_clip)
        sliver_sources_.push_back({v[0], v[1]});
  }

  // Orientation: whether some conforming implementation's snapped vertices give a doubled
  // area of the other sign, or 0 (orientation_may_change), for the triangle itself; and the
  // pieces of its clipped polygon that may (turning_pieces).
  if (generations_ > 0) turning_pieces_ = ref::turning_pieces(vertices_, subpixel_bits);
  std::array<std::array<double, 2>, 3> p{};
  std::array<double, 3> rounding{};
  for (size_t j = 0; j < 3; ++j) {
    const auto& v = c.vertices[t.index[j]].clip;
    if (!(v[3] > 0)) return;
    p[j] = approximate_window(c, v);
    rounding[j] =
        snap_and_round(p[j][0], p[j][1], m, subpixel_bits) - std::ldexp(1.0, -subpixel_bits);
  }
  may_turn_over_ = orientation_may_change(p, rounding, subpixel_bits);
}

double PositionFreedom::at(int px, int py) const {
  const double x = px + 0.5, y = py + 0.5;
  return std::max(delta_[0].at(x, y), delta_[1].at(x, y));
}

double PositionFreedom::depth_at(int px, int py) const {
  return depth_.at(px + 0.5, py + 0.5);
}

double PositionFreedom::weight_at(int px, int py) const {
  const double inverse_w = inverse_w_.at(px + 0.5, py + 0.5);
  return inverse_w > 0 ? weight_.at(px + 0.5, py + 0.5) / inverse_w : 0.0;
}

namespace {

// The centres of kRowBlock pixels: px + 1/2, as the single-pixel forms compute them.
void centres(const double* px, const double* py, double* x, double* y) {
  for (int j = 0; j < kRowBlock; ++j)
    x[j] = px[j] + 0.5, y[j] = py[j] + 0.5;
}

}  // namespace

GLRC_BLOCK_FORM void PositionFreedom::at(const double* px, const double* py, double* out) const {
  double x[kRowBlock], y[kRowBlock], a[kRowBlock], b[kRowBlock];
  centres(px, py, x, y);
  delta_[0].at(x, y, a);
  delta_[1].at(x, y, b);
  for (int j = 0; j < kRowBlock; ++j)
    out[j] = a[j] < b[j] ? b[j] : a[j];  // std::max(a, b)
}

GLRC_BLOCK_FORM void PositionFreedom::depth_at(const double* px, const double* py,
                                               double* out) const {
  double x[kRowBlock], y[kRowBlock];
  centres(px, py, x, y);
  depth_.at(x, y, out);
}

GLRC_BLOCK_FORM void PositionFreedom::weight_at(const double* px, const double* py,
                                                double* out) const {
  double x[kRowBlock], y[kRowBlock], inverse_w[kRowBlock], weight[kRowBlock];
  centres(px, py, x, y);
  inverse_w_.at(x, y, inverse_w);
  weight_.at(x, y, weight);
  // The quotient in a loop of its own, the choice in another: a division inside the choice
  // would become a branch (it might trap), which is not vectorized.
  for (int j = 0; j < kRowBlock; ++j)
    weight[j] = weight[j] / inverse_w[j];
  for (int j = 0; j < kRowBlock; ++j)
    out[j] = inverse_w[j] > 0 ? weight[j] : 0.0;
}

std::array<double, 2> PositionFreedom::range(int px0, int px1, int py) const {
  const double x0 = px0 + 0.5, x1 = px1 + 0.5, y = py + 0.5;
  const auto a = delta_[0].range(x0, x1, y), b = delta_[1].range(x0, x1, y);
  return {std::max(a[0], b[0]), std::max(a[1], b[1])};
}

std::array<double, 2> PositionFreedom::weight_range(int px0, int px1, int py) const {
  const double x0 = px0 + 0.5, x1 = px1 + 0.5, y = py + 0.5;
  const auto [ilo, ihi] = inverse_w_.range(x0, x1, y);
  const auto [wlo, whi] = weight_.range(x0, x1, y);
  // weight_at: w/i where i > 0, else 0; the rounded quotient is monotone in each.
  if (!(ilo > 0)) return {std::min(0.0, wlo >= 0 ? 0.0 : -INFINITY), INFINITY};
  return {wlo >= 0 ? wlo / ihi : wlo / ilo, whi >= 0 ? whi / ilo : whi / ihi};
}

double PositionFreedom::largest() const {
  return std::max(delta_[0].largest(), delta_[1].largest());
}

}  // namespace glrc::ref
