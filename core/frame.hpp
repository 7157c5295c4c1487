// Frame: what a renderer produced, per pixel. The reference and every GL backend fill the very
// same layout, so the comparator needs to know nothing of either. Row 0 is the bottom row
// (GL window coordinates, y up).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/large_buffer.hpp"
#include "core/parallel.hpp"

namespace glrc {

struct Frame {
  static constexpr int32_t kNoPrimitive = -1;

  int width = 0, height = 0;
  std::vector<int32_t> primitive;  // gl_PrimitiveID of the covering triangle, or kNoPrimitive
  std::vector<float> depth;        // z_w; the clear value (Case::depth_clear) where not covered
  // components[k][pixel]: varying component k (Case component order); 0 where not covered.
  std::vector<std::vector<float>> components;
  // How many fragments rasterization produced at each pixel, every drawn (not culled, not
  // clipped) triangle's, whether or not they pass the depth test: 1 inside a watertight mesh
  // drawn once, 0 in a gap, 2 where a shared edge was drawn twice, one more for each triangle
  // hidden beneath another. Counted without the depth test because the count checks coverage,
  // and which of two fragments whose depths are within rounding of each other passes is free
  // (a later, nearer fragment may then hide either): a count taken with the depth test would
  // depend on that order. Empty when unknown.
  std::vector<uint16_t> fragments;

  Frame() = default;
  // w×h pixels, every one cleared (no primitive, depth 1, components 0). `threads`: how many
  // threads fill the buffers (each buffer by one thread; parallel_for's count), for a large
  // frame of many channels, whose filling is otherwise a serial part of drawing it.
  Frame(int w, int h, int component_count, int threads = 1) {
    reset(w, h, component_count, threads);
  }

  // Makes this frame what Frame(w, h, component_count, threads) makes, field for field
  // (fragments empty), in the buffers it has where they are large enough (assign_large): a
  // frame made again for each case a worker checks reuses the last case's memory, instead of
  // the kernel faulting in and zeroing fresh pages for each (with jemalloc's default decay,
  // freed frames are given back to the kernel between cases; measured on a 2-core VM: the
  // 1024x1024 quad's check spent 14% of its CPU in the kernel zeroing pages).
  void reset(int w, int h, int component_count, int threads = 1) {
    make(w, h, component_count, threads, Clear::everything);
  }
  // reset(), except that the components are only sized (resize_large): they hold whatever their
  // buffers held until their user writes them. For a renderer that writes every component of
  // every pixel it covers and then clears the others (the exact reference, ref/render.cpp):
  // clearing the components of a frame it covers whole first wrote each of its bytes twice (the
  // 1024x1024 quad of 16 components: 64 MB of its frame and 64 MB of its allowance's, about 18
  // ms of the 360 ms of CPU its check took, measured on a 2-core VM).
  void reset_uncleared_components(int w, int h, int component_count, int threads = 1) {
    make(w, h, component_count, threads, Clear::primitive_and_depth);
  }
  // reset(), except that no buffer is filled, only sized: primitive, depth and the components
  // hold whatever their buffers held (fragments empty). For a reader that writes every value
  // of each of them (GL's readback, gl_harness/framebuffer.cpp): filling them first wrote each
  // byte twice (the 1024x1024 quad of 16 components: 72 MB, about 9 ms of its check's CPU,
  // measured on a 2-core VM).
  void reset_uncleared(int w, int h, int component_count, int threads = 1) {
    make(w, h, component_count, threads, Clear::nothing);
  }

  size_t index(int x, int y) const { return size_t(y) * width + x; }
  size_t pixel_count() const { return size_t(width) * height; }
  // Rows [y0, y0 + n) as a frame n rows high (its row 0 is row y0): one slice of a frame checked
  // slice by slice. Requires 0 <= y0, 0 <= n, y0 + n <= height.
  Frame rows(int y0, int n) const {
    Frame slice;
    slice.width = width, slice.height = n;
    const auto a = ptrdiff_t(index(0, y0)), b = ptrdiff_t(index(0, y0 + n));
    slice.primitive.assign(primitive.begin() + a, primitive.begin() + b);
    slice.depth.assign(depth.begin() + a, depth.begin() + b);
    if (fragments.size() == pixel_count())
      slice.fragments.assign(fragments.begin() + a, fragments.begin() + b);
    for (const std::vector<float>& c : components)
      slice.components.emplace_back(c.begin() + a, c.begin() + b);
    return slice;
  }

 private:
  enum class Clear { everything, primitive_and_depth, nothing };
  void make(int w, int h, int component_count, int threads, Clear clear) {
    width = w, height = h;
    components.resize(size_t(std::max(component_count, 0)));
    fragments.clear();
    // Each buffer filled with its clear value, or only sized.
    const auto make_buffer = [&](auto& v, auto clear_value, bool filled) {
      if (filled)
        assign_large(v, pixel_count(), clear_value);
      else
        resize_large(v, pixel_count());
    };
    parallel_for(2 + int(components.size()), threads, [&](int b) {
      if (b == 0)
        make_buffer(primitive, kNoPrimitive, clear != Clear::nothing);
      else if (b == 1)
        make_buffer(depth, 1.0f, clear != Clear::nothing);
      else
        make_buffer(components[size_t(b - 2)], 0.0f, clear == Clear::everything);
    });
  }
};

// What is known about the reference's edges near a pixel centre: bits of one byte per pixel,
// for judging coverage mismatches.
namespace edge {
inline constexpr uint8_t tie = 1;       // the centre lies exactly on an edge
inline constexpr uint8_t snapping = 2;  // within the snapping band of an outer edge or clip plane
inline constexpr uint8_t shared = 4;    // within the snapping band of an edge two triangles share
// Within the reach of a triangle whose orientation the position freedom can change (it may turn
// over, vanish or appear): which primitives cover the pixel, and how often, is not decided.
inline constexpr uint8_t unstable = 8;
// Another triangle's fragment is within the depth allowance of the winner's: either may win the
// depth test (Expectation::candidates holds the others).
inline constexpr uint8_t depth_order = 16;
}  // namespace edge

// A fragment a conforming implementation may keep at a pixel instead of the reference's: its
// depth is within the depth allowances of the winner's, so the depth test may go either way.
struct Candidate {
  size_t pixel = 0;
  int32_t primitive = Frame::kNoPrimitive;
  float depth = 0, allowed_depth = 0;
  std::vector<float> values, allowed;  // per component, as in Frame::components
};

// The allowances of a frame's components (and of its depth, where no depth test needs them
// while drawing) computed where they are asked for, not at every pixel: most of a comparison
// needs only bounds of them over a run of pixels (a pixel's error below the run's least
// allowance is within it). Made by the reference (ref::render_deferred) for the frame it draws;
// asked by the comparator (compare/).
class DeferredAllowance {
 public:
  // The channel k of at() and range() that is the depth, where depth() says it is deferred.
  static constexpr int kDepth = -1;
  virtual ~DeferredAllowance() = default;
  // Whether the depth's allowance is deferred too (channel kDepth): then Expectation::allowed
  // has no primitive and no depth either. Only where the depth test needs no allowance while
  // drawing (DepthFunc::always: no fragment may win it instead of another).
  virtual bool depth() const { return false; }
  // The window row of row 0 of the frame drawn with this: a slice's first row
  // (ref::render_rows_deferred), 0 for a whole frame.
  virtual int first_row() const { return 0; }
  // Component k's allowances (or the depth's, k = kDepth) at pixels [first, first + n) of one
  // row of `frame` (the frame drawn with this, or a copy of it): out[j] is bit for bit what
  // Expectation::allowed holds at pixel first + j when it is computed at every pixel (0 where
  // nothing is drawn).
  virtual void at(const Frame& frame, int k, size_t first, int n, float* out) const = 0;
  // at() of the pixels first + j of one row for each bit j set in `lanes` (j < 64), into
  // out[j]; the other out[j] are left as they are. The same bits as at(). This one computes
  // them pixel by pixel; the reference's computes as many pixels at once as its blocks hold,
  // wherever they are in the row (lanes of a run of 64 that a comparison needs are seldom
  // next to each other).
  virtual void at_lanes(const Frame& frame, int k, size_t first, uint64_t lanes, float* out) const {
    for (; lanes != 0; lanes &= lanes - 1) {
      const int j = std::countr_zero(lanes);
      at(frame, k, first + size_t(j), 1, out + j);
    }
  }
  // at() of the one pixel i.
  float at(const Frame& frame, int k, size_t i) const {
    float out;
    at(frame, k, i, 1, &out);
    return out;
  }
  // Bounds {lo, hi} of at()'s values at pixels x0..x1 of row y (x0 <= x1), every one drawn by
  // primitive p with component k's value (or the depth, k = kDepth) in [value_lo, value_hi]:
  // lo <= each <= hi. {0, +inf} when nothing better is known.
  virtual std::array<double, 2> range(int k, int32_t p, int x0, int x1, int y, float value_lo,
                                      float value_hi) const = 0;
};

// What a correct implementation may produce: the exact reference frame, and around it the
// freedom the specification leaves.
struct Expectation {
  Frame frame;                 // the exact reference
  std::vector<uint8_t> edges;  // edge:: bits per pixel
  // Per pixel and channel (depth, components), the largest |gl - reference| a conforming
  // implementation can produce there; no components when not computed, or when `deferred`
  // (nor primitive and depth, when it defers the depth's too).
  Frame allowed;
  // With an allowance whose components are computed where asked for: allowed has the depth's
  // only, or nothing (DeferredAllowance::depth); complete_allowance fills in the rest.
  std::shared_ptr<const DeferredAllowance> deferred;
  // Where the depth test's winner is not decided (edge::depth_order), the other fragments that
  // may win, sorted by pixel; only with an allowance.
  std::vector<Candidate> candidates;

  // The candidate of primitive p at pixel i, or nullptr.
  const Candidate* candidate(size_t i, int32_t p) const {
    auto it = std::lower_bound(candidates.begin(), candidates.end(), i,
                               [](const Candidate& a, size_t pixel) { return a.pixel < pixel; });
    for (; it != candidates.end() && it->pixel == i; ++it)
      if (it->primitive == p) return &*it;
    return nullptr;
  }
};

// Computes a deferred allowance at every pixel (a heatmap shows them all): e is then as if it
// had been computed while drawing. Nothing to do without `deferred`.
inline void complete_allowance(Expectation& e, int threads = 1) {
  if (!e.deferred) return;
  const Frame& f = e.frame;
  Frame& a = e.allowed;
  const bool depth = e.deferred->depth();
  a.components.assign(f.components.size(), {});
  // Channel kDepth (when deferred) first, then the components.
  const int first = depth ? DeferredAllowance::kDepth : 0;
  if (depth) {
    a.width = f.width, a.height = f.height;
    a.primitive = f.primitive;  // each drawn fragment's primitive, as render() keeps it
  }
  parallel_for(int(a.components.size()) - first, threads, [&](int item) {
    const int k = item + first;
    std::vector<float>& values = k == DeferredAllowance::kDepth ? a.depth : a.components[size_t(k)];
    resize_large(values, f.pixel_count());
    for (int y = 0; y < f.height; ++y)
      e.deferred->at(f, k, f.index(0, y), f.width, values.data() + f.index(0, y));
  });
  e.deferred.reset();
}

}  // namespace glrc
