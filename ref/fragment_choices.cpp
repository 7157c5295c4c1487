// Fragment choices (reference.hpp, core/fragment_trace.hpp): per pixel, which triangles a
// conforming implementation surely rasterizes there, which it may, and which shared edges give
// the pixel to one side or the other. Each triangle is judged as render.cpp judges it for its
// edge bits, with the same freedom, bands and reach, one triangle at a time instead of their
// bits OR-ed together:
//   - outside the triangle grown by its bands (CoverageTest::bands), no implementation covers
//     the centre;
//   - inside it and in no band, every implementation covers it, as the reference does;
//   - in the band of an outer edge or of a near or far plane, or near a triangle the freedom may
//     turn over, it may or may not (free);
//   - in the band of an edge it shares (ref/mesh.hpp: every user's ends from the same clip
//     coordinates, as many users on each side), it covers exactly when the centre goes to its
//     side: every user rasterizes that one edge alike (the same vertices snapped the same way,
//     the same tie rule from opposite normals), so the side is one choice for all of them.
// Where that cannot say how often one primitive covers the centre, nothing is decided
// (FragmentChoices::anything): a vertex through the eye, or a clipped polygon that may turn
// over. A clipped polygon in its own bands may cover a centre twice (its fan folding).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "ref/coverage.hpp"
#include "ref/freedom.hpp"
#include "ref/mesh.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"
#include "ref/sliver.hpp"
#include "ref/viewport.hpp"

namespace glrc::ref {

namespace {

// One triangle's part at one pixel, before the shared edges are numbered for the pixel.
struct Part {
  size_t pixel = 0;  // index into the pixels asked for
  int32_t primitive = -1;
  enum class Kind { sure, member, anything } kind = Kind::sure;
  bool free = false;
  std::vector<std::pair<int32_t, bool>> sides;  // (shared edge's group, first side)
  bool folds = false;                           // FragmentChoices::Member::folds
};

// The pixels asked for (window indices x + y·width) in window order, to find those of a run of
// rows without a pass over all of them: each triangle looks only at the rows it may reach.
class PixelIndex {
 public:
  PixelIndex(const std::vector<size_t>& pixels, int width) : pixels_(pixels), width_(width) {
    order_.resize(pixels.size());
    for (size_t k = 0; k < order_.size(); ++k)
      order_[k] = k;
    std::sort(order_.begin(), order_.end(),
              [&](size_t a, size_t b) { return pixels[a] < pixels[b]; });
  }
  // f(k, px, py) for every pixel k asked for in rows [y0, y1] (y0 <= y1), in window order.
  template <class F>
  void for_each_in_rows(int y0, int y1, F&& f) const {
    if (y0 > y1) return;
    const size_t w = size_t(width_);
    auto it = std::lower_bound(order_.begin(), order_.end(), size_t(std::max(y0, 0)) * w,
                               [&](size_t k, size_t at) { return pixels_[k] < at; });
    for (; it != order_.end() && pixels_[*it] < (size_t(y1) + 1) * w; ++it)
      f(*it, int(pixels_[*it] % w), int(pixels_[*it] / w));
  }

 private:
  const std::vector<size_t>& pixels_;
  int width_;
  std::vector<size_t> order_;  // indices into pixels_, by window index
};

// Where triangle p may reach a centre, in double: a triangle inside the clip volume (nothing
// clipped: no new vertex, no guard-band variant) lies in the viewport, and each vertex's freedom
// is 2^-bits plus the rounding of a window position below 2^14 plus the viewport's magnitude
// (freedom.cpp's snap_and_round), under 0.1 pixel for bits >= 4. Every triangle its vertices so
// moved make (turned over or not) lies within that distance of the triangle itself (each of its
// points is a convex combination of the moved vertices, so within it of the same combination of
// the vertices), and it covers or classifies no centre farther than 1 + ceil(1.5·0.1) = 2
// pixels beyond it: one more than kReach pixels outside an edge's line, or beyond the box of its
// window vertices, is reached by none (here in double, off by far less than a pixel). Any other
// triangle may reach anything. Its users share a shared edge's ends, so a shared edge near a
// pixel keeps all its users: their sides stay as the whole case's.
class Reach {
 public:
  Reach(const Case& c, int p) {
    std::array<std::array<double, 2>, 3> v{};
    for (size_t i = 0; i < 3; ++i) {
      const auto& clip = c.vertices[c.triangles[size_t(p)][i]].clip;
      if (!inside_view_volume(c, clip)) return;
      v[i] = approximate_window(c, clip);
      lo_[0] = std::min(lo_[0], v[i][0]), hi_[0] = std::max(hi_[0], v[i][0]);
      lo_[1] = std::min(lo_[1], v[i][1]), hi_[1] = std::max(hi_[1], v[i][1]);
    }
    bounded_ = true;
    // Each edge's line as a·x + b·y + c, (a, b) of unit length, >= 0 on the triangle's side. A
    // triangle whose doubled area is within double's rounding has no side to trust: its box
    // alone.
    const double area =
        (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[2][0] - v[0][0]) * (v[1][1] - v[0][1]);
    const double size = std::max(hi_[0] - lo_[0], hi_[1] - lo_[1]);
    if (!(std::fabs(area) > 1e-6 * size * size)) return;
    for (size_t i = 0; i < 3; ++i) {
      const auto& from = v[(i + 1) % 3];
      const auto& to = v[(i + 2) % 3];
      const double a = from[1] - to[1], b = to[0] - from[0];
      const double length = std::hypot(a, b) * (area > 0 ? 1 : -1);
      edges_[i] = {a / length, b / length, -(a * from[0] + b * from[1]) / length};
    }
    sided_ = true;
  }
  // Whether no implementation's version of the triangle covers or classifies the centre of
  // pixel (px, py).
  bool beyond(int px, int py) const {
    if (!bounded_) return false;
    const double x = px + 0.5, y = py + 0.5;
    if (x < lo_[0] - kReach || x > hi_[0] + kReach || y < lo_[1] - kReach || y > hi_[1] + kReach)
      return true;
    if (!sided_) return false;
    for (const auto& [a, b, c] : edges_)
      if (a * x + b * y + c < -kReach) return true;
    return false;
  }
  // Rows [y0, y1] that may hold a centre it reaches (y0 > y1: none), within `viewport`.
  std::pair<int, int> rows(const PixelBox& viewport) const {
    if (!bounded_) return {viewport.y0, viewport.y1};
    return {std::max(viewport.y0, int(std::floor(lo_[1] - kReach))),
            std::min(viewport.y1, int(std::ceil(hi_[1] + kReach)))};
  }

 private:
  static constexpr double kReach = 4;
  double lo_[2] = {INFINITY, INFINITY}, hi_[2] = {-INFINITY, -INFINITY};
  bool bounded_ = false;  // inside the clip volume: the box and, where sided_, the edges hold
  bool sided_ = false;
  std::array<std::array<double, 3>, 3> edges_{};
};

// Whether triangle p may reach a pixel asked for.
bool may_reach(const Reach& reach, const PixelIndex& pixels, const PixelBox& viewport) {
  const auto [y0, y1] = reach.rows(viewport);
  bool near = false;
  pixels.for_each_in_rows(y0, y1,
                          [&](size_t, int px, int py) { near = near || !reach.beyond(px, py); });
  return near;
}

// Triangle p's parts at the pixels it may reach.
void parts_of(const Case& c, const Model& m, int bits, const TriangleSetup& t, int32_t p,
              const std::array<SharedEdge, 3>& shared, const Reach& near, const PixelIndex& pixels,
              const PixelBox& viewport, std::vector<Part>& out) {
  if (t.discarded) return;  // by a cull distance: by every implementation
  const bool either_face = c.cull != CullFace::front_and_back;
  if (!t.has_edges) {
    // Zero area: drawn by no model, but a sliver of some implementation's (Sliver).
    if (!either_face) return;
    const PositionFreedom freedom(c, t, bits);
    if (!freedom.reaches_eye() && freedom.sliver_sources().empty()) return;
    const Sliver sliver(freedom);
    // A sliver from a clipped polygon may fold onto itself: any count.
    const bool folds = freedom.reaches_eye() || freedom.generations() > 0;
    pixels.for_each_in_rows(viewport.y0, viewport.y1, [&](size_t k, int px, int py) {
      if (px < viewport.x0 || px > viewport.x1) return;
      const auto [first, last] = sliver.row_span(py, px, px);
      if (first > last) return;
      out.push_back({k, p, folds ? Part::Kind::anything : Part::Kind::member, true, {}});
    });
    return;
  }
  // A triangle this model does not draw may still be drawn by another implementation when its
  // orientation is not decided by the freedom (render.cpp's test).
  if (!t.drawn && !either_face) return;
  const PositionFreedom freedom(c, t, bits);
  const bool eye = freedom.reaches_eye();
  const bool unstable = eye || freedom.may_turn_over();
  // The centres a piece of the clipped polygon that may turn over may cover (render.cpp's
  // mark_sliver of Prepared::turning): any count there.
  for (const TurningPiece& piece : freedom.turning_pieces()) {
    const Sliver sliver(piece);
    pixels.for_each_in_rows(viewport.y0, viewport.y1, [&](size_t k, int px, int py) {
      if (px < viewport.x0 || px > viewport.x1) return;
      const auto [first, last] = sliver.row_span(py, px, px);
      if (first <= last) out.push_back({k, p, Part::Kind::anything, true, {}});
    });
  }
  if (!t.drawn && !unstable) return;
  // render.cpp's Prepared::reach: the box grown by the margin, in the viewport.
  const int margin = 1 + int(std::min(std::ceil(freedom.largest() * 1.5), 1e6));
  const PixelBox reach{
      std::max(viewport.x0, t.box.x0 - margin), std::max(viewport.y0, t.box.y0 - margin),
      std::min(viewport.x1, t.box.x1 + margin), std::min(viewport.y1, t.box.y1 + margin)};
  if (eye) {
    // Every centre of the viewport (render.cpp's mark_unstable), and any count.
    pixels.for_each_in_rows(viewport.y0, viewport.y1, [&](size_t k, int px, int) {
      if (px >= viewport.x0 && px <= viewport.x1)
        out.push_back({k, p, Part::Kind::anything, true, {}});
    });
    return;
  }
  const CoverageTest coverage(t, m);
  const double largest = freedom.largest(), z_largest = freedom.z_clip_largest();
  pixels.for_each_in_rows(reach.y0, reach.y1, [&](size_t k, int px, int py) {
    if (px < reach.x0 || px > reach.x1 || near.beyond(px, py)) return;
    // At the freedom's largest first: every band grows with the freedom, so a centre that one
    // does not reach, none does, and the freedom's envelopes need not be evaluated there.
    if (!coverage.bands(px, py, largest, z_largest).reached) return;
    const CoverageTest::Bands b =
        coverage.bands(px, py, freedom.at(px, py), freedom.z_clip_at(px, py));
    if (!b.reached) return;
    if (unstable) {
      // A clipped polygon that may turn over may fold onto itself: any count.
      const bool folds = freedom.generations() > 0;
      out.push_back({k, p, folds ? Part::Kind::anything : Part::Kind::member, true, {}});
      return;
    }
    // The clipped polygon's edges on the x and y planes lie on the viewport's sides, where no
    // centre is, but move with its vertices, inwards too (render.cpp's FragmentBlocks).
    const bool side = freedom.generations() > 0 &&
                      viewport_side_distance(c.viewport, px, py) <= freedom.at(px, py);
    if (b.edges == 0 && !b.plane) {
      // Every implementation covers it, but for the sides; the reference's own coverage
      // counts it.
      if (!coverage.covers(px, py)) return;
      out.push_back({k, p, side ? Part::Kind::member : Part::Kind::sure, side, {}});
      return;
    }
    // A clipped polygon is drawn as a fan of triangles from vertices the clipper rounds: a thin
    // one may turn non-convex within that rounding, and its fan then fold, covering a centre
    // in its bands twice, though the triangle itself keeps its orientation (a fuzz campaign's
    // sliver cut by y = -w: llvmpipe gives 2 fragments of it beside two of its edges).
    Part part{k, p, Part::Kind::member, b.plane || side, {}, freedom.generations() > 0};
    for (size_t i = 0; i < 3; ++i) {
      if (!(b.edges & (1u << i))) continue;
      if (shared[i].shared())
        part.sides.emplace_back(shared[i].group, shared[i].first_side);
      else
        part.free = true;
    }
    if (part.sides.empty()) part.free = true;
    out.push_back(std::move(part));
  });
}

// fragment_choices() from `given`, render()'s set-up of the whole case, or where null from the
// triangles that may reach a pixel asked, set up here.
std::vector<FragmentChoices> choose(const Case& c, const Model& m, int freedom_bits,
                                    const std::vector<size_t>& pixels, int threads,
                                    const CaseSetup* given) {
  std::vector<FragmentChoices> out(pixels.size());
  if (pixels.empty()) return out;
  if (given && given->triangles.size() != c.triangles.size())
    throw std::invalid_argument("fragment_choices: a set-up of " +
                                std::to_string(given->triangles.size()) +
                                " triangles for a case of " + std::to_string(c.triangles.size()));
  const int bits = std::max(freedom_bits, 4);  // render.cpp's Settings::bits
  ThreadPool pool(thread_count(threads));
  const PixelIndex index(pixels, c.fb_width);
  // Only the triangles that may reach a pixel asked (most of a large case's are far from the
  // few pixels traced), judged in primitive order; set up here only without render()'s.
  const PixelBox viewport = viewport_box(c);
  std::vector<std::optional<Reach>> reach(c.triangles.size());
  pool.parallel_for(int(c.triangles.size()), [&](int p) {
    if (Reach r(c, p); may_reach(r, index, viewport)) reach[size_t(p)] = r;
  });
  std::vector<int> kept;
  for (int p = 0; p < int(c.triangles.size()); ++p)
    if (reach[size_t(p)]) kept.push_back(p);
  std::optional<CaseSetup> own;
  if (!given) {
    own.emplace();
    own->triangles = setup_triangles(c, m, kept, pool);
    own->shared = shared_edge_groups(own->triangles, thread_count(threads));
    own->threads = threads;
  }
  const auto setup_of = [&](size_t k) -> const TriangleSetup& {
    return given ? *given->triangles[size_t(kept[k])] : *own->triangles[k];
  };
  const auto shared_of = [&](size_t k) -> const std::array<SharedEdge, 3>& {
    return given ? given->shared[size_t(kept[k])] : own->shared[k];
  };
  // Each triangle's parts on some thread, then put together in primitive order.
  std::vector<std::vector<Part>> parts(kept.size());
  pool.parallel_for(int(kept.size()), [&](int k) {
    parts_of(c, m, bits, setup_of(size_t(k)), kept[size_t(k)], shared_of(size_t(k)),
             *reach[size_t(kept[size_t(k)])], index, viewport, parts[size_t(k)]);
  });
  // Per pixel, its shared edges numbered from 0 in the order they come.
  std::vector<std::map<int32_t, uint32_t>> edge_names(pixels.size());
  for (const std::vector<Part>& list : parts)
    for (const Part& part : list) {
      FragmentChoices& f = out[part.pixel];
      switch (part.kind) {
        case Part::Kind::anything:
          f.anything = true;
          break;
        case Part::Kind::sure:
          f.sure += fragment_trace(part.primitive);
          break;
        case Part::Kind::member: {
          FragmentChoices::Member member{part.primitive, part.free, {}, part.folds};
          for (const auto& [group, first_side] : part.sides) {
            auto [it, added] = edge_names[part.pixel].emplace(group, f.edges);
            if (added) ++f.edges;
            member.sides.emplace_back(it->second, first_side);
          }
          f.members.push_back(std::move(member));
          break;
        }
      }
    }
  return out;
}

}  // namespace

std::vector<FragmentChoices> fragment_choices(const Case& c, const Model& m, int freedom_bits,
                                              const std::vector<size_t>& pixels, int threads) {
  return choose(c, m, freedom_bits, pixels, threads, nullptr);
}

std::vector<FragmentChoices> fragment_choices(const Case& c, const Model& m, int freedom_bits,
                                              const std::vector<size_t>& pixels, int threads,
                                              const CaseSetup& setup) {
  return choose(c, m, freedom_bits, pixels, threads, &setup);
}

}  // namespace glrc::ref
