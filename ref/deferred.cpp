#include "ref/deferred.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace glrc::ref {

TriangleAllowance::TriangleAllowance(const Case& c, const TriangleSetup& t, int bits)
    : freedom_(c, t, bits), eye_(freedom_.reaches_eye()), clipped_(freedom_.generations() > 0) {}

void TriangleAllowance::set(const Case& c, const TriangleSetup& t,
                            const std::vector<ComponentPlane>& planes, const Plane& depth_forms,
                            const std::vector<bool>& smooth) {
  // The implementation's possible fan triangles, shared by every channel; and where its planes
  // may be anchored.
  // Its vertices' rounding, for planes from unsnapped positions.
  fan_ = FanTriangles(freedom_.polygon(), freedom_.largest(), freedom_.rounding());
  anchors_ = Anchors(freedom_.polygon(), freedom_.guard_band_triangle());
  const int generations = freedom_.generations();
  const PositionReach reach = PositionReach::of(freedom_.slope(), freedom_.largest());
  components_.clear();
  components_.reserve(planes.size());
  // gl_FrontFacing: the triangle's own facing unless some implementation's vertices may turn
  // it, or a piece of its clipped polygon (an implementation that sets up each piece takes
  // each piece's facing: llvmpipe), over: then either.
  const float facing = freedom_.may_turn_over() || !freedom_.turning_pieces().empty() ? 1.0f : 0.0f;
  for (const ComponentPlane& cp : planes) {
    Kind kind = cp.flat ? Kind::fixed : Kind::interpolated;
    float fixed = 0;
    if (cp.builtin == Builtin::front_facing) {
      fixed = facing;
    } else if (cp.builtin == Builtin::frag_coord) {
      // x and y are the pixel's centre, exact; z is the depth; w = 1/w_c.
      kind = cp.component < 2 ? Kind::fixed : cp.component == 2 ? Kind::depth : Kind::inverse_w;
    }
    // gl_FragCoord.w's values are the 1/w_c of the polygon's vertices, rounded each: as large
    // as the largest of them (PositionFreedom::largest_inverse_w), which a clip-made vertex
    // near the eye may make larger than any of the triangle's.
    const double scale =
        kind == Kind::inverse_w ? std::max(cp.scale, freedom_.largest_inverse_w()) : cp.scale;
    components_.emplace_back(cp.plane.numerator, cp.plane.denominator, cp.spread,
                             value_freedom(c, t, scale, generations), anchors_, reach);
    spread_.push_back(cp.spread);
    kind_.push_back(kind);
    fixed_.push_back(fixed);
    depth_component_ = depth_component_ || kind == Kind::depth;
  }
  smooth_.assign(smooth.begin(), smooth.end());
  offset_ = c.polygon_offset.has_value();
  clamped_ = c.depth_clamp || offset_;
  clamp_ = c.depth_clamp ? std::array<double, 2>{std::min(c.depth_near, c.depth_far),
                                                 std::max(c.depth_near, c.depth_far)}
                         : std::array<double, 2>{0.0, 1.0};
  // The depth range's bounds come through float arithmetic (a few ulps); [0, 1]'s are exact.
  clamp_margin_ =
      c.depth_clamp ? 0x1p-22 * std::max(std::fabs(clamp_[0]), std::fabs(clamp_[1])) : 0.0;
  plane_ = {depth_forms.numerator.a.get_d(),   depth_forms.numerator.b.get_d(),
            depth_forms.numerator.c.get_d(),   depth_forms.denominator.a.get_d(),
            depth_forms.denominator.b.get_d(), depth_forms.denominator.c.get_d()};
  // The depths' scale: the depth range's, or under GL_DEPTH_CLAMP the vertices' own (z_w is
  // not bounded by the range there).
  const double n = c.depth_near, f = c.depth_far;
  const double scale =
      std::max({std::fabs(n), std::fabs(f), c.depth_clamp ? freedom_.largest_depth() : 0.0});
  depth_ = Allowance(depth_forms.numerator, depth_forms.denominator, INFINITY,
                     value_freedom(c, t, scale, generations), anchors_, reach);
}

void TriangleAllowance::prepare(const double* px, const double* py, Block& b, bool depth) const {
  constexpr int n = kRowBlock;
  std::copy(px, px + n, b.x);
  std::copy(py, py + n, b.y);
  freedom_.at(b.x, b.y, b.delta);
  double centre_x[n], centre_y[n];
  for (int j = 0; j < n; ++j)
    centre_x[j] = b.x[j] + 0.5, centre_y[j] = b.y[j] + 0.5;
  fan_.condition(centre_x, centre_y, b.condition);
  fan_.outside_reach(centre_x, centre_y, b.outside);
  if (clipped_)
    freedom_.weight_at(b.x, b.y, b.weight);
  else
    std::fill(std::begin(b.weight), std::end(b.weight), 0.0);
  if (depth || depth_component_) {
    freedom_.depth_at(b.x, b.y, b.depth_extra);
    if (depth_freedom_ != 0)
      for (double& e : b.depth_extra)
        e += depth_freedom_;
  }
  anchors_.distances(b.x, b.y, b.distances);
}

void TriangleAllowance::depth_unclamped_at(const Block& b, const float* z, float* out) const {
  if (eye_) return (void)std::fill(out, out + kRowBlock, INFINITY);
  depth_.at_rounded_up(b.x, b.y, z, b.delta, b.depth_extra, b.condition, b.outside, b.distances,
                       out);
}

void TriangleAllowance::depth_at(const Block& b, const float* z, float* out) const {
  if (!clamped_) return depth_unclamped_at(b, z, out);
  // The depths z are clamped; an implementation's unclamped z_w within the allowance a of the
  // exact v is clamped too, so it lies in [clamp(v - a), clamp(v + a)]: beyond the range's ends
  // every implementation gives the end itself (an offset pushing a whole triangle past 1, or
  // depths clamped far beyond the range), where the unclamped allowance would excuse anything.
  // v in double, from the plane's forms: the margin below covers its rounding.
  double v[kRowBlock];
  float unclamped[kRowBlock], a[kRowBlock];
  for (int j = 0; j < kRowBlock; ++j) {
    const double num = plane_[0] * b.x[j] + plane_[1] * b.y[j] + plane_[2];
    const double den = plane_[3] * b.x[j] + plane_[4] * b.y[j] + plane_[5];
    v[j] = num / den;
    unclamped[j] = float(v[j]);
  }
  depth_unclamped_at(b, unclamped, a);
  // The bounds an implementation clamps to are its own arithmetic's (llvmpipe's and
  // softpipe's translate ∓ scale, in float: 0.19999999 for a range's 0.2): each within
  // clamp_margin_ of the exact one.
  const double e = clamp_margin_;
  for (int j = 0; j < kRowBlock; ++j) {
    if (!std::isfinite(v[j]) || std::isnan(a[j])) {
      out[j] = a[j];
      continue;
    }
    const double zj = z[j];
    const double lo = std::clamp(v[j] - double(a[j]), clamp_[0] - e, clamp_[1] - e);
    const double hi = std::clamp(v[j] + double(a[j]), clamp_[0] + e, clamp_[1] + e);
    const double allowed =
        std::max(zj - lo, hi - zj) + 0x1p-40 * (std::fabs(v[j]) + 1) + 0x1p-24 * std::fabs(zj);
    float up = float(std::min(allowed, double(a[j])));
    if (double(up) < std::min(allowed, double(a[j]))) up = std::nextafter(up, INFINITY);
    out[j] = up;
  }
}

void TriangleAllowance::component_at(const Block& b, size_t k, const float* value,
                                     float* out) const {
  const Kind kind = kind_[k];
  if (kind == Kind::fixed) return (void)std::fill(out, out + kRowBlock, fixed_[k]);
  if (eye_) return (void)std::fill(out, out + kRowBlock, INFINITY);
  if (kind == Kind::depth) {
    depth_unclamped_at(b, value, out);
    // With a polygon offset, GL clamps the fragment's depth to [0, 1] after adding the offset
    // (OpenGL 4.6 section 14.6.5), and gl_FragCoord.z is "the depth value that would be used
    // for the fragment's depth" (GLSL 4.60 section 7.1.2): which of the two, before or after
    // that clamp, is not settled between them (llvmpipe gives it before, softpipe after, both
    // exactly where z_w + o is within [0, 1]). Beyond [0, 1] either is taken: the distance to it.
    if (offset_)
      for (int j = 0; j < kRowBlock; ++j) {
        const double beyond = std::max({0.0, double(value[j]) - 1.0, -double(value[j])});
        if (beyond == 0) continue;
        const double sum = double(out[j]) + beyond * (1 + 0x1p-20);
        float up = float(sum);
        if (double(up) < sum) up = std::nextafter(up, INFINITY);  // rounded up, as out[j] is
        out[j] = up;
      }
    return;
  }
  // A clipped vertex's 1/w_c error re-weights a smooth value (freedom.hpp). Of 1/w_c itself,
  // noperspective Σ λ_j/w_j, the errors ρ_j/w_j of the clip-made vertices move it by
  // Σ λ_j ρ_j/w_j, which weight_at bounds as a share of 1/w_c (its envelope over the
  // envelope of 1/w_j, exact for a value linear over the polygon): weight·|value|, and 2^-20
  // of it more for the value's rounding and the envelopes'.
  double extra[kRowBlock];
  for (int j = 0; j < kRowBlock; ++j)
    extra[j] = kind == Kind::inverse_w ? b.weight[j] * std::fabs(double(value[j])) * (1 + 0x1p-20)
               : smooth_[k]            ? b.weight[j] * spread_[k]
                                       : 0.0;
  components_[k].at_rounded_up(b.x, b.y, value, b.delta, extra, b.condition, b.outside, b.distances,
                               out);
}

std::array<double, 2> TriangleAllowance::component_range(size_t k, int px0, int px1, int py,
                                                         float value_lo, float value_hi) const {
  const Kind kind = kind_[k];
  if (kind == Kind::fixed) return {fixed_[k], fixed_[k]};
  if (eye_) return {0.0, INFINITY};
  if (kind == Kind::depth) {
    auto range = depth_unclamped_range(px0, px1, py, value_lo, value_hi);
    if (offset_)  // component_at's distance beyond [0, 1], at most at the run's extremes
      range[1] += std::max({0.0, double(value_hi) - 1.0, -double(value_lo)}) * (1 + 0x1p-20);
    return range;
  }
  const auto delta = freedom_.range(px0, px1, py);
  const auto condition = fan_.condition_range(px0 + 0.5, px1 + 0.5, py + 0.5);
  std::array<double, 2> extra{0.0, 0.0};
  if (kind == Kind::inverse_w && clipped_) {
    // component_at's weight·|value|·(1 + 2^-20), monotone in each factor >= 0.
    const auto weight = freedom_.weight_range(px0, px1, py);
    const double lo = std::fabs(value_lo) < std::fabs(value_hi) ? value_lo : value_hi;
    const double most = std::max(std::fabs(double(value_lo)), std::fabs(double(value_hi)));
    const double least = value_lo <= 0 && value_hi >= 0 ? 0.0 : std::fabs(lo);
    extra = {std::max(weight[0], 0.0) * least * (1 + 0x1p-20), weight[1] * most * (1 + 0x1p-20)};
  } else if (smooth_[k] && clipped_) {
    const auto weight = freedom_.weight_range(px0, px1, py);
    // weight·spread, monotone in the weight for a spread >= 0.
    if (!(spread_[k] >= 0)) return {0.0, INFINITY};
    extra = {weight[0] * spread_[k], weight[1] * spread_[k]};
  }
  if (!(delta[0] >= 0) || !(condition[0] >= 0) || !(extra[0] >= 0)) return {0.0, INFINITY};
  Anchors::RunDistances distances;
  anchors_.distances(px0, px1, py, distances);
  return beyond(
      px0, px1, py,
      components_[k].range(px0, px1, py, value_lo, value_hi, delta, extra, condition, distances));
}

std::array<double, 2> TriangleAllowance::depth_range(int px0, int px1, int py, float z_lo,
                                                     float z_hi) const {
  auto range = depth_unclamped_range(px0, px1, py, z_lo, z_hi);
  // Clamped (depth_at): no more than the unclamped allowance, and as little as 0.
  if (clamped_) range[0] = 0;
  return range;
}

std::array<double, 2> TriangleAllowance::depth_unclamped_range(int px0, int px1, int py, float z_lo,
                                                               float z_hi) const {
  if (eye_) return {0.0, INFINITY};
  const auto delta = freedom_.range(px0, px1, py);
  const auto condition = fan_.condition_range(px0 + 0.5, px1 + 0.5, py + 0.5);
  auto extra = freedom_.depth_range(px0, px1, py);
  extra[0] += depth_freedom_, extra[1] += depth_freedom_;
  if (!(delta[0] >= 0) || !(condition[0] >= 0) || !(extra[0] >= 0)) return {0.0, INFINITY};
  Anchors::RunDistances distances;
  anchors_.distances(px0, px1, py, distances);
  return beyond(px0, px1, py,
                depth_.range(px0, px1, py, z_lo, z_hi, delta, extra, condition, distances));
}

std::array<double, 2> TriangleAllowance::beyond(int px0, int px1, int py,
                                                const std::array<double, 2>& range) const {
  if (fan_.holds_run(px0 + 0.5, px1 + 0.5, py + 0.5)) return range;
  return {range[0], INFINITY};
}

namespace {

// Channel ch's allowances (TriangleAllowance's component or depth) of `count` pixels of triangle
// t (1 to kRowBlock) in row y, columns x0 + offset[l], whose values are values[offset[l]], into
// allowed[l]: one block, its lanes past `count` repeating the last (each lane is computed on its
// own, so any pixels of one triangle may share a block).
void block_of(const TriangleAllowance& t, Channel ch, int x0, int y, const float* values,
              const int* offset, int count, float* allowed) {
  constexpr int m = kRowBlock;
  const bool depth = ch.is_depth();
  double px[m], py[m];
  float value[m], out[m];
  for (int l = 0; l < m; ++l) {
    const int q = offset[std::min(l, count - 1)];
    px[l] = double(x0 + q), py[l] = double(y), value[l] = values[q];
  }
  TriangleAllowance::Block block;
  t.prepare(px, py, block, depth);
  if (depth)
    t.depth_at(block, value, out);
  else
    t.component_at(block, size_t(ch.component()), value, out);
  std::copy(out, out + count, allowed);
}

}  // namespace

void TriangleAllowances::at(const Frame& frame, Channel ch, size_t first, int n, float* out) const {
  // Every lane of each 64 pixels: at_lanes' blocks, bit for bit the same per lane however the
  // lanes are grouped.
  for (int j = 0; j < n; j += 64) {
    const int count = std::min(64, n - j);
    at_lanes(frame, ch, first + size_t(j), count == 64 ? ~uint64_t(0) : (uint64_t(1) << count) - 1,
             out + j);
  }
}

void TriangleAllowances::at_lanes(const Frame& frame, Channel ch, size_t first, uint64_t lanes,
                                  float* out) const {
  constexpr int m = kRowBlock;
  const int y = int(first / size_t(frame.width)) + row0_;
  const int x0 = int(first % size_t(frame.width));
  const bool depth = ch.is_depth();
  const float* values = frame.values(ch).data() + first;
  const int32_t* primitive = frame.primitive.data() + first;
  while (lanes != 0) {
    // The lanes of the primitive of the first lane left, a block at most.
    const int32_t p = primitive[std::countr_zero(lanes)];
    const TriangleAllowance* t =
        p >= 0 && size_t(p) < triangles_.size() ? triangles_[size_t(p)].get() : nullptr;
    int lane[m], count = 0;
    for (uint64_t rest = lanes; rest != 0 && count < m; rest &= rest - 1) {
      const int j = std::countr_zero(rest);
      if (primitive[j] == p) lane[count++] = j;
    }
    for (int l = 0; l < count; ++l)
      lanes &= ~(uint64_t(1) << lane[l]);
    float allowed[m];
    if (t)
      block_of(*t, ch, x0, y, values, lane, count, allowed);
    else
      std::fill(allowed, allowed + count, depth ? 1.0f : 0.0f);  // nothing drawn (the clear value)
    for (int l = 0; l < count; ++l)
      out[lane[l]] = allowed[l];
  }
}

std::array<double, 2> TriangleAllowances::range(Channel ch, int32_t p, int x0, int x1, int y,
                                                float value_lo, float value_hi) const {
  const TriangleAllowance* t =
      p >= 0 && size_t(p) < triangles_.size() ? triangles_[size_t(p)].get() : nullptr;
  if (!t) return {0.0, INFINITY};
  if (ch.is_depth()) return t->depth_range(x0, x1, y + row0_, value_lo, value_hi);
  return t->component_range(size_t(ch.component()), x0, x1, y + row0_, value_lo, value_hi);
}

}  // namespace glrc::ref
