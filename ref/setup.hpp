// Triangle setup and snapping: edge functions, facing and culling, the pixel bounding box, and
// the barycentric forms the attribute planes are built from.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <optional>
#include <vector>

#include "core/case.hpp"
#include "core/model.hpp"
#include "core/parallel.hpp"
#include "ref/exact.hpp"
#include "ref/viewport.hpp"

namespace glrc::ref {

// How coverage is decided. `snapped`: window positions rounded to the subpixel grid and integer
// edge functions, for triangles with every w_c > 0 and positions inside a 2^40-step guard band.
// `homogeneous`: exact edge functions of the unsnapped triangle straight from clip space
// (Olano and Greer), for no snapping or for triangles reaching behind the eye, where there is
// no window position to snap.
enum class CoveragePath { snapped, homogeneous };

struct PixelBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive
  bool empty() const { return x1 < x0 || y1 < y0; }
};

// A triangle's three window vertices, read only, shared with the other triangles that use
// them: a mesh's vertex is transformed once and its rationals held once. (Copied into each
// triangle, its ten GMP numbers' copies and frees were a tenth of drawing piglit's fan.) None
// until setup_triangle sets them.
class WindowCorners {
 public:
  using Pointer = std::shared_ptr<const WindowVertex>;
  WindowCorners() = default;
  explicit WindowCorners(std::array<Pointer, 3> v) : v_(std::move(v)) {}

  const WindowVertex& operator[](size_t i) const { return *v_[i]; }

  // The three vertices in order (for range-for and the standard algorithms).
  class Iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = WindowVertex;
    using difference_type = std::ptrdiff_t;
    using pointer = const WindowVertex*;
    using reference = const WindowVertex&;
    Iterator() = default;
    explicit Iterator(const Pointer* p) : p_(p) {}
    reference operator*() const { return **p_; }
    pointer operator->() const { return p_->get(); }
    Iterator& operator++() {
      ++p_;
      return *this;
    }
    Iterator operator++(int) { return Iterator(p_++); }
    bool operator==(const Iterator&) const = default;

   private:
    const Pointer* p_ = nullptr;
  };
  Iterator begin() const { return Iterator(v_.data()); }
  Iterator end() const { return Iterator(v_.data() + 3); }

 private:
  std::array<Pointer, 3> v_;
};

struct TriangleSetup {
  int primitive = 0;  // gl_PrimitiveID
  WindowCorners v;
  std::array<uint32_t, 3> index{};                        // into Case::vertices
  ClipDepth clip_depth = ClipDepth::negative_one_to_one;  // the case's: where the near plane is
  bool depth_clamp = false;  // the case's GL_DEPTH_CLAMP: no near and far planes
  bool drawn = false;        // false: zero area, or culled
  // Discarded by a cull distance (culled_by_distance): drawn by no implementation, whatever
  // its area or facing.
  bool discarded = false;
  // The exact triangle has area: edges and box are set, even when it is not drawn (a
  // triangle culled or of zero snapped area may still be drawn by another implementation).
  bool has_edges = false;
  bool front_facing = true;
  CoveragePath path = CoveragePath::homogeneous;

  // Homogeneous edge functions at pixel (px, py), i = 0..2 opposite vertex i, sign-normalized
  // so that the visible part of the triangle is where all three are >= 0. Each is proportional
  // to the clip-space barycentric weight of vertex i over w_c at the pixel centre.
  std::array<LinearForm, 3> homogeneous_edges;
  // Snapped edge functions (A·px + B·py + C, integers), sign-normalized likewise; proportional
  // to the screen-space barycentrics of the snapped triangle.
  struct IntEdge {
    int128 a = 0, b = 0, c = 0;
    int128 at(long px, long py) const { return a * px + b * py + c; }
  };
  std::array<IntEdge, 3> snapped_edges{};
  // The snapped window positions (x_w, y_w)·2^subpixel_bits of the model set up with,
  // integers (on the snapped path).
  std::array<std::array<long, 2>, 3> snapped{};

  PixelBox box;  // pixels that may be covered, inside the viewport and framebuffer
};

TriangleSetup setup_triangle(const Case& c, const Model& m, int primitive);
// The same with the window positions given (window[i], when not null, is
// to_window(c.vertices[i], c); a null one is transformed here): a mesh's vertex is used by
// several triangles and transformed once, not once per corner, and shared by them.
TriangleSetup setup_triangle(const Case& c, const Model& m, int primitive,
                             const std::vector<WindowCorners::Pointer>& window);

// Every triangle of c set up (setup_triangle), in primitive order, on `pool`'s threads: each
// vertex a triangle uses transformed to the window once, shared by its triangles. Every element
// holds a setup.
std::vector<std::optional<TriangleSetup>> setup_triangles(const Case& c, const Model& m,
                                                          ThreadPool& pool);
// The triangles `primitives` of c (indices into c.triangles) set up likewise, in that order.
std::vector<std::optional<TriangleSetup>> setup_triangles(const Case& c, const Model& m,
                                                          const std::vector<int>& primitives,
                                                          ThreadPool& pool);

// The pixels the case may draw: the viewport within scissor_region (the framebuffer, and the
// scissor box where the case has one). Empty (x0 > x1 or y0 > y1) when they do not meet.
PixelBox viewport_box(const Case& c);
// The pixels an implementation may draw given its precision for the viewport's bounds
// (viewport_shift, ref/freedom.hpp): viewport_box for a viewport on that precision's grid
// (glViewport's whole numbers); for another, the viewport grown by the most its sides may move,
// two steps, within scissor_region.
PixelBox viewport_reach(const Case& c);

}  // namespace glrc::ref
