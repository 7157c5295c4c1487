// One triangle's allowances, at a block of pixels or bounded over a run of one row: what a
// triangle prepared for drawing keeps once it is drawn, so that its components' allowances can
// be computed where a comparison asks for them (DeferredAllowance, core/frame.hpp) instead of
// at every pixel it draws. The per-pixel arithmetic is allowance.hpp's; this puts together
// what its channels share at a pixel (the position freedom, the fan's condition, the anchors'
// distances, the re-weighting of clipped vertices) once per block, and the same bounded over a
// run for range().
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"
#include "ref/allowance.hpp"
#include "ref/blocks.hpp"
#include "ref/freedom.hpp"
#include "ref/interpolation.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

class TriangleAllowance {
 public:
  // Triangle t's position freedom for an implementation reporting `bits` subpixel bits
  // (PositionFreedom), no allowance yet (set()).
  TriangleAllowance(const Case& c, const TriangleSetup& t, int bits);
  TriangleAllowance(const TriangleAllowance&) = delete;  // the allowances point to anchors_
  TriangleAllowance& operator=(const TriangleAllowance&) = delete;

  const PositionFreedom& freedom() const { return freedom_; }
  // PositionFreedom::reaches_eye: every allowance is infinite.
  bool eye() const { return eye_; }
  // Made by clipping: smooth values re-weighted by the clipped vertices' 1/w_c (weight_at).
  bool clipped() const { return clipped_; }

  // The allowances of the triangle's component planes and of its depth (`depth_forms`), each
  // component's smooth or not (`smooth`, Case component order).
  void set(const Case& c, const TriangleSetup& t, const std::vector<ComponentPlane>& planes,
           const Plane& depth_forms, const std::vector<bool>& smooth);

  // A freedom of z_w the same at every pixel, added to the depth's allowance (and
  // gl_FragCoord.z's): a polygon offset's (ref/depth_offset.hpp), z_w units.
  void add_depth_freedom(double extra) { depth_freedom_ += extra; }

  // What the channels share at kRowBlock pixels (px[j], py[j]) (integer window coordinates
  // as doubles).
  struct Block {
    double x[kRowBlock], y[kRowBlock], delta[kRowBlock], condition[kRowBlock], weight[kRowBlock],
        depth_extra[kRowBlock], outside[kRowBlock];
    Anchors::RowDistances distances;
  };
  // `depth`: depth_extra too (depth_at needs it; component_at does not).
  void prepare(const double* px, const double* py, Block& b, bool depth = true) const;
  // The depth's allowance and component k's, the block's values z[j] and value[j], rounded up
  // to floats (Allowance::at_rounded_up): infinite through the eye, 0 for a flat component
  // (its Kind below).
  void depth_at(const Block& b, const float* z, float* out) const;
  void component_at(const Block& b, size_t k, const float* value, float* out) const;
  // Bounds {lo, hi} of component_at() at pixels px0..px1 of row py whose values lie in
  // [value_lo, value_hi] (Allowance::range).
  std::array<double, 2> component_range(size_t k, int px0, int px1, int py, float value_lo,
                                        float value_hi) const;
  // The same of depth_at(), the depths z in [z_lo, z_hi] (depth_extra bounded by
  // PositionFreedom::depth_range).
  std::array<double, 2> depth_range(int px0, int px1, int py, float z_lo, float z_hi) const;

 private:
  PositionFreedom freedom_;
  bool eye_ = false, clipped_ = false;
  double depth_freedom_ = 0;  // add_depth_freedom's
  FanTriangles fan_;
  Anchors anchors_;  // the allowances point to it
  std::vector<Allowance> components_;
  Allowance depth_;
  std::vector<double> spread_;   // per component: what a re-weighting moves
  std::vector<uint8_t> smooth_;  // per component
  // How each component's allowance is had (component_at): its Allowance; a fixed one
  // (`fixed_`: 0 for a flat value and gl_FragCoord.xy, 0 or 1 for gl_FrontFacing); the depth's
  // (gl_FragCoord.z); or its Allowance with the clip-made vertices' 1/w_c errors
  // (gl_FragCoord.w).
  enum class Kind : uint8_t { interpolated, fixed, depth, inverse_w };
  std::vector<Kind> kind_;
  std::vector<float> fixed_;
  bool depth_component_ = false;  // some component is Kind::depth: prepare() needs depth_extra
  // A polygon offset: gl_FragCoord.z (Kind::depth) may be z_w + o before the clamp to [0, 1]
  // that the depth takes, or after (frag_coord_beyond).
  bool offset_ = false;
  // The depth is clamped (fragment_depth: GL_DEPTH_CLAMP's range, or [0, 1] after a polygon
  // offset) to clamp_: its allowance is that of the unclamped z_w (evaluated from plane_, the
  // depth plane's forms in double) taken through the same clamp.
  bool clamped_ = false;
  std::array<double, 2> clamp_{};
  double clamp_margin_ = 0;        // how far an implementation's bounds may be from clamp_
  std::array<double, 6> plane_{};  // numerator a, b, c; denominator a, b, c
  void depth_unclamped_at(const Block& b, const float* z, float* out) const;
  std::array<double, 2> depth_unclamped_range(int px0, int px1, int py, float z_lo,
                                              float z_hi) const;
  // A run's allowance range as Allowance::range gives it for pixels inside the polygon; its hi
  // unbounded where a pixel of the run may lie outside it (FanTriangles::outside_reach).
  std::array<double, 2> beyond(int px0, int px1, int py, const std::array<double, 2>& range) const;
};

// The DeferredAllowance of a frame whose row 0 is window row `row0`, from the triangles that
// drew it, by primitive: each added (add()) before anything asks for its pixels. `depth`: the
// depth's allowance deferred too (DeferredAllowance::defers_depth).
class TriangleAllowances final : public DeferredAllowance {
 public:
  TriangleAllowances(size_t triangles, int row0, bool depth)
      : triangles_(triangles), row0_(row0), depth_(depth) {}
  bool defers_depth() const override { return depth_; }
  int first_row() const override { return row0_; }
  // Primitive p's allowances; not while another thread asks for any.
  void add(size_t p, std::shared_ptr<const TriangleAllowance> t) {
    triangles_.at(p) = std::move(t);
  }
  using DeferredAllowance::at;  // one pixel
  void at(const Frame& frame, Channel ch, size_t first, int n, float* out) const override;
  // Up to kRowBlock lanes of one primitive in each block, wherever they are in the row.
  void at_lanes(const Frame& frame, Channel ch, size_t first, uint64_t lanes,
                float* out) const override;
  std::array<double, 2> range(Channel ch, int32_t p, int x0, int x1, int y, float value_lo,
                              float value_hi) const override;

 private:
  std::vector<std::shared_ptr<const TriangleAllowance>> triangles_;
  int row0_;
  bool depth_;
};

}  // namespace glrc::ref
