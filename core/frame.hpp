// Frame: what a renderer produced, per pixel. The reference and every GL backend fill the very
// same layout, so the comparator needs to know nothing of either. Row 0 is the bottom row
// (GL window coordinates, y up).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/channel.hpp"
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
  // The values of channel ch: depth, or components[k].
  const std::vector<float>& values(Channel ch) const {
    return ch.is_depth() ? depth : components[size_t(ch.component())];
  }
  std::vector<float>& values(Channel ch) {
    return ch.is_depth() ? depth : components[size_t(ch.component())];
  }
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

}  // namespace glrc
