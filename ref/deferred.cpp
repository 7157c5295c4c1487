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
  fan_ = FanTriangles(freedom_.polygon(), freedom_.largest());
  anchors_ = Anchors(freedom_.polygon(), freedom_.guard_band_triangle());
  const int generations = freedom_.generations();
  const PositionReach reach = PositionReach::of(freedom_.slope(), freedom_.largest());
  components_.clear();
  components_.reserve(planes.size());
  for (const ComponentPlane& cp : planes) {
    components_.emplace_back(cp.plane.numerator, cp.plane.denominator, cp.spread,
                             value_freedom(c, t, cp.scale, generations), anchors_, reach);
    spread_.push_back(cp.spread);
    flat_.push_back(cp.flat);
  }
  smooth_.assign(smooth.begin(), smooth.end());
  const double n = c.depth_near, f = c.depth_far;
  depth_ = Allowance(depth_forms.numerator, depth_forms.denominator, INFINITY,
                     value_freedom(c, t, std::max(std::fabs(n), std::fabs(f)), generations),
                     anchors_, reach);
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
  if (clipped_)
    freedom_.weight_at(b.x, b.y, b.weight);
  else
    std::fill(std::begin(b.weight), std::end(b.weight), 0.0);
  if (depth) freedom_.depth_at(b.x, b.y, b.depth_extra);
  anchors_.distances(b.x, b.y, b.distances);
}

void TriangleAllowance::depth_at(const Block& b, const float* z, float* out) const {
  if (eye_) return (void)std::fill(out, out + kRowBlock, INFINITY);
  depth_.at_rounded_up(b.x, b.y, z, b.delta, b.depth_extra, b.condition, b.distances, out);
}

void TriangleAllowance::component_at(const Block& b, size_t k, const float* value,
                                     float* out) const {
  if (flat_[k] || eye_) return (void)std::fill(out, out + kRowBlock, flat_[k] ? 0.0f : INFINITY);
  // A clipped vertex's 1/w_c error re-weights a smooth value (freedom.hpp).
  double extra[kRowBlock];
  for (int j = 0; j < kRowBlock; ++j)
    extra[j] = smooth_[k] ? b.weight[j] * spread_[k] : 0.0;
  components_[k].at_rounded_up(b.x, b.y, value, b.delta, extra, b.condition, b.distances, out);
}

std::array<double, 2> TriangleAllowance::component_range(size_t k, int px0, int px1, int py,
                                                         float value_lo, float value_hi) const {
  if (flat_[k]) return {0.0, 0.0};
  if (eye_) return {0.0, INFINITY};
  const auto delta = freedom_.range(px0, px1, py);
  const auto condition = fan_.condition_range(px0 + 0.5, px1 + 0.5, py + 0.5);
  std::array<double, 2> extra{0.0, 0.0};
  if (smooth_[k] && clipped_) {
    const auto weight = freedom_.weight_range(px0, px1, py);
    // weight·spread, monotone in the weight for a spread >= 0.
    if (!(spread_[k] >= 0)) return {0.0, INFINITY};
    extra = {weight[0] * spread_[k], weight[1] * spread_[k]};
  }
  if (!(delta[0] >= 0) || !(condition[0] >= 0) || !(extra[0] >= 0)) return {0.0, INFINITY};
  Anchors::RunDistances distances;
  anchors_.distances(px0, px1, py, distances);
  return components_[k].range(px0, px1, py, value_lo, value_hi, delta, extra, condition, distances);
}

std::array<double, 2> TriangleAllowance::depth_range(int px0, int px1, int py, float z_lo,
                                                     float z_hi) const {
  if (eye_) return {0.0, INFINITY};
  const auto delta = freedom_.range(px0, px1, py);
  const auto condition = fan_.condition_range(px0 + 0.5, px1 + 0.5, py + 0.5);
  const auto extra = freedom_.depth_range(px0, px1, py);
  if (!(delta[0] >= 0) || !(condition[0] >= 0) || !(extra[0] >= 0)) return {0.0, INFINITY};
  Anchors::RunDistances distances;
  anchors_.distances(px0, px1, py, distances);
  return depth_.range(px0, px1, py, z_lo, z_hi, delta, extra, condition, distances);
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
