// Expectation: what a correct implementation may produce for a case. The exact reference frame,
// what is known about its edges at each pixel, the allowance around each channel's value and
// the other fragments the depth test may keep. Made by the reference (ref/), judged against by
// the comparator (compare/) and carried as data by the reproducers (export/).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/frame.hpp"
#include "core/large_buffer.hpp"
#include "core/parallel.hpp"

namespace glrc {

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
// A fragment GL may hold at a pixel instead of the reference's, the depth test's order being
// free there (edge::depth_order). Primitive none is the clear value: where a fragment within its
// allowance of glClearDepth's value may fail the test against it, or pass, GL may keep nothing
// (its values 0, its allowances 0) or keep the fragment.
struct Candidate {
  size_t pixel = 0;
  int32_t primitive = Frame::kNoPrimitive;
  float depth = 0, allowed_depth = 0;
  std::vector<float> values, allowed;  // per component, as in Frame::components

  float value(Channel ch) const { return ch.is_depth() ? depth : values[size_t(ch.component())]; }
  float allowance(Channel ch) const {
    return ch.is_depth() ? allowed_depth : allowed[size_t(ch.component())];
  }
};

// The allowances of a frame's components (and of its depth, where no depth test needs them
// while drawing) computed where they are asked for, not at every pixel: most of a comparison
// needs only bounds of them over a run of pixels (a pixel's error below the run's least
// allowance is within it). Made by the reference (ref::render_deferred) for the frame it draws;
// asked by the comparator (compare/).
class DeferredAllowance {
 public:
  virtual ~DeferredAllowance() = default;
  // Whether the depth's allowance is deferred too: then Expectation::allowed has no primitive
  // and no depth either (AllowanceState::all_deferred). Only where the depth test needs no
  // allowance while drawing (DepthFunc::always: no fragment may win it instead of another).
  virtual bool defers_depth() const { return false; }
  // The channels it gives for a frame of `component_count` components, by slot: the depth's
  // where it defers it, then every component's.
  std::vector<Channel> channels(int component_count) const {
    std::vector<Channel> out = channels_of(component_count);
    if (!defers_depth()) out.erase(out.begin());
    return out;
  }
  // The window row of row 0 of the frame drawn with this: a slice's first row
  // (ref::render_rows_deferred), 0 for a whole frame.
  virtual int first_row() const { return 0; }
  // Channel ch's allowances (a component's, or the depth's where defers_depth()) at pixels
  // [first, first + n) of one row of `frame` (the frame drawn with this, or a copy of it):
  // out[j] is bit for bit what Expectation::allowed holds at pixel first + j when it is
  // computed at every pixel (0 where nothing is drawn).
  virtual void at(const Frame& frame, Channel ch, size_t first, int n, float* out) const = 0;
  // at() of the pixels first + j of one row for each bit j set in `lanes` (j < 64), into
  // out[j]; the other out[j] are left as they are. The same bits as at(). This one computes
  // them pixel by pixel; the reference's computes as many pixels at once as its blocks hold,
  // wherever they are in the row (lanes of a run of 64 that a comparison needs are seldom
  // next to each other).
  virtual void at_lanes(const Frame& frame, Channel ch, size_t first, uint64_t lanes,
                        float* out) const {
    for (; lanes != 0; lanes &= lanes - 1) {
      const int j = std::countr_zero(lanes);
      at(frame, ch, first + size_t(j), 1, out + j);
    }
  }
  // at() of the one pixel i.
  float at(const Frame& frame, Channel ch, size_t i) const {
    float out;
    at(frame, ch, i, 1, &out);
    return out;
  }
  // Bounds {lo, hi} of at()'s values at pixels x0..x1 of row y (x0 <= x1), every one drawn by
  // primitive p with channel ch's value in [value_lo, value_hi]: lo <= each <= hi. {0, +inf}
  // when nothing better is known.
  virtual std::array<double, 2> range(Channel ch, int32_t p, int x0, int x1, int y, float value_lo,
                                      float value_hi) const = 0;
};

// How an Expectation holds its allowance: the one place its fields are decoded.
enum class AllowanceState {
  none,                 // no allowance (exact or ULP tolerances; the reference without freedom)
  per_pixel,            // `allowed` holds the depth's and every component's at every pixel
  deferred_components,  // `allowed` holds the depth's (and primitive); `deferred` the components'
  all_deferred,         // `allowed` is empty; `deferred` gives every channel's, the depth's too
};

// What a correct implementation may produce: the exact reference frame, and around it the
// freedom the specification leaves.
struct Expectation {
  Frame frame;                 // the exact reference
  std::vector<uint8_t> edges;  // edge:: bits per pixel
  // Per pixel and channel (depth, components), the largest |gl - reference| a conforming
  // implementation can produce there, as allowance_state() says it is held.
  Frame allowed;
  // With an allowance whose components are computed where asked for (and the depth's, where it
  // says so); complete_allowance makes them per pixel.
  std::shared_ptr<const DeferredAllowance> deferred;
  // Where the depth test's winner is not decided (edge::depth_order), the other fragments that
  // may win, sorted by pixel; only with an allowance.
  std::vector<Candidate> candidates;

  AllowanceState allowance_state() const {
    if (deferred)
      return deferred->defers_depth() ? AllowanceState::all_deferred
                                      : AllowanceState::deferred_components;
    return allowed.depth.empty() ? AllowanceState::none : AllowanceState::per_pixel;
  }
  // Whether the allowance is held or given as allowance_state() says: every buffer `allowed`
  // holds covers the frame's pixels, the others are empty, and a per-pixel allowance has every
  // component. "" when it is, else what is not, in a few words ("the allowance's components are
  // not the frame's"). The comparator and the exporters check it before they read the
  // allowance.
  std::string allowance_shape_error() const {
    const size_t pixels = frame.pixel_count();
    const bool depth_held = allowed.depth.size() == pixels;
    switch (allowance_state()) {
      case AllowanceState::none:
        return allowed.components.empty() ? "" : "an allowance of components without the depth's";
      case AllowanceState::per_pixel:
        if (!depth_held) return "the allowance's depth is not the frame's size";
        if (allowed.components.size() != frame.components.size())
          return "the allowance has not the frame's components";
        for (const std::vector<float>& values : allowed.components)
          if (values.size() != pixels) return "the allowance's components are not the frame's size";
        return "";
      case AllowanceState::deferred_components:
        if (!depth_held) return "the allowance's depth is not the frame's size";
        return allowed.components.empty() ? "" : "components both deferred and held";
      case AllowanceState::all_deferred:
        return allowed.depth.empty() && allowed.components.empty()
                   ? ""
                   : "an allowance both deferred and held";
    }
    return "an allowance of no known state";
  }

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
// had been computed while drawing (AllowanceState::per_pixel). Nothing to do without `deferred`.
inline void complete_allowance(Expectation& e, int threads = 1) {
  if (!e.deferred) return;
  const Frame& f = e.frame;
  Frame& a = e.allowed;
  a.components.assign(f.components.size(), {});
  if (e.deferred->defers_depth()) {
    a.width = f.width, a.height = f.height;
    a.primitive = f.primitive;  // each drawn fragment's primitive, as render() keeps it
  }
  const std::vector<Channel> channels = e.deferred->channels(int(f.components.size()));
  parallel_for(int(channels.size()), threads, [&](int item) {
    const Channel ch = channels[size_t(item)];
    std::vector<float>& values = a.values(ch);
    resize_large(values, f.pixel_count());
    for (int y = 0; y < f.height; ++y)
      e.deferred->at(f, ch, f.index(0, y), f.width, values.data() + f.index(0, y));
  });
  e.deferred.reset();
}

}  // namespace glrc
