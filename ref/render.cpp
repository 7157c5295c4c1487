// The frame: every triangle, in primitive order, classified and drawn pixel by pixel. The work
// about a triangle that does not depend on the pixel (setup, freedom, planes, allowances) is
// prepared once, on several threads, for a chunk of triangles at a time; then tiles of rows
// (tiles.hpp) draw the chunk on several threads, each tile every triangle of the chunk in
// order, so a pixel sees the same triangles in the same order on any number of threads.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/vector_clones.hpp"
#include "ref/allowance.hpp"
#include "ref/coverage.hpp"
#include "ref/deferred.hpp"
#include "ref/depth.hpp"
#include "ref/depth_offset.hpp"
#include "ref/freedom.hpp"
#include "ref/interpolation.hpp"
#include "ref/mesh.hpp"
#include "ref/reference.hpp"
#include "ref/setup.hpp"
#include "ref/sliver.hpp"
#include "ref/tiles.hpp"

namespace glrc::ref {

namespace {

// What every triangle shares: the case, the model, the allowance's freedom.
struct Settings {
  const Case& c;
  const Model& m;
  bool allowance;
  bool edges;         // the edge bits too (render_frame: only the frame)
  int bits;           // subpixel bits of the position freedom (with an allowance)
  double model_step;  // the edge band without an allowance
  PixelBox viewport;  // its rows cut to the ones drawn
  // viewport_reach, its rows cut likewise: beyond `viewport` only for a fractional viewport,
  // whose sides an implementation may move by its precision (ref/viewport.hpp).
  PixelBox reach;
  std::vector<bool> component_smooth;
  int row0 = 0;  // the window row of the frames' row 0
  // With a deferred allowance: the components' allowances are not drawn (only those of the
  // depth test's candidates), and each triangle's are kept here instead.
  TriangleAllowances* deferred = nullptr;
  // The depth's allowance deferred too: no depth test needs it while drawing.
  bool deferred_depth = false;
  // With an allowance: each triangle's first identical copy (identical_triangles), for the
  // depth test's invariance.
  std::vector<int32_t> twin;
};

// Fragments that may win the depth test instead of the reference's, by pixel.
using CandidateMap = std::map<size_t, std::vector<Candidate>>;

// One triangle, ready to draw: everything about it that does not depend on the pixel. Read
// only once built, so that every tile may draw it at once.
struct Prepared {
  Prepared(const Settings& s, const TriangleSetup& setup, const std::array<bool, 3>& shared_edges)
      : t(setup), shared(shared_edges), coverage(setup, s.m, s.edges) {
    const Case& c = s.c;
    if (s.allowance) allowance = std::make_shared<TriangleAllowance>(c, t, s.bits);
    // Reaching the eye (within rounding), the triangle may cover anything: unstable too.
    eye = s.allowance && allowance->eye();
    unstable = eye || (s.allowance && freedom().may_turn_over());
    if (s.allowance)
      for (const TurningPiece& piece : freedom().turning_pieces())
        turning.emplace_back(piece);
    // The bands reach up to delta·sqrt(2) outside the covered pixels: look that much further
    // (the viewport bounds it anyway; the clamp keeps the conversion defined).
    largest = s.allowance ? freedom().largest() : s.model_step;
    margin = 1 + int(std::min(std::ceil(largest * 1.5), 1e6));
    // How far outside the exact triangle a centre may be classified or covered, and a little
    // more (sqrt(2) < 1.5), never beyond the margin of the box: classified within the largest
    // band, largest·sqrt(2); covered only on the snapped path, where each vertex moved by at
    // most half a subpixel step along x and y, so every point of the snapped triangle is that
    // close to a point of the exact one (a convex combination of the moves), 2^-(bits+1)·sqrt(2)
    // away at most. (The homogeneous path covers only centres inside the exact triangle.)
    // row_span widens by its own arithmetic's error bounds (SignEvaluator::row_bound).
    const double snapping =
        t.path == CoveragePath::snapped ? std::ldexp(1.0, -(s.m.subpixel_bits + 1)) : 0.0;
    reach_px = std::min(double(margin), std::max(largest, snapping) * 1.5);
    reach = {std::max(s.reach.x0, t.box.x0 - margin), std::max(s.reach.y0, t.box.y0 - margin),
             std::min(s.reach.x1, t.box.x1 + margin), std::min(s.reach.y1, t.box.y1 + margin)};
    if (!t.drawn || t.box.empty()) return;
    clipped = s.allowance && allowance->clipped();
    // Kept per thread: its nine rationals and dyadic numbers, copied for every triangle, reuse
    // their limbs instead of being allocated and freed each time (unsnapped planes, the
    // default; snapped planes make their forms anew).
    thread_local Barycentrics b;
    barycentrics(t, s.m, b);
    const DepthOffset offset = depth_offset(c, t);
    const Plane depth_forms = depth_plane(t, b, c.polygon_offset ? &offset.value : nullptr);
    depth = depth_forms.evaluator();
    planes = component_planes(c, t, b, depth_forms);
    values = ComponentValues(planes);
    if (s.allowance) {
      allowance->set(c, t, planes, depth_forms, s.component_smooth);
      if (c.polygon_offset)
        allowance->add_depth_freedom(depth_offset_freedom(c, freedom(), offset));
    }
  }

  // Only with an allowance.
  const PositionFreedom& freedom() const { return allowance->freedom(); }

  const TriangleSetup& t;
  std::array<bool, 3> shared;
  CoverageTest coverage;
  // With an allowance: the position freedom, and the allowances once the triangle draws (set).
  // Shared: a deferred allowance keeps it after the triangle is drawn.
  std::shared_ptr<TriangleAllowance> allowance;
  bool unstable = false, clipped = false;
  // With an allowance: the centres each piece of the clipped polygon that may turn over may
  // cover (PositionFreedom::turning_pieces), edge::unstable.
  std::vector<Sliver> turning;
  // PositionFreedom::reaches_eye: every centre of the viewport is unstable, and the smooth and
  // noperspective values and the depth it draws have no bound (an infinite allowance).
  bool eye = false;
  int margin = 1;
  double largest = 0;   // the freedom at no pixel is larger (PositionFreedom::largest)
  double reach_px = 1;  // how far from the triangle a pixel may be classified or covered
  // The pixels it may classify: its box grown by the margin, within the viewport's reach.
  PixelBox reach;
  RatioEvaluator depth;
  std::vector<ComponentPlane> planes;
  ComponentValues values;  // of `planes`
};

// Marks the centres of rows [y0, y1], columns [x0, x1] (window coordinates) edge::unstable.
void mark_unstable(int x0, int y0, int x1, int y1, int row0, const Frame& f,
                   std::vector<uint8_t>& edges) {
  for (int py = y0; py <= y1; ++py)
    for (int px = x0; px <= x1; ++px)
      edges[f.index(px, py - row0)] |= edge::unstable;
}

// Marks the centres of rows [y0, y1] a zero-area triangle's slivers may cover (Sliver), in
// columns [x0, x1], edge::unstable: any primitive and any fragment count there is what some
// conforming implementation draws.
void mark_sliver(const Sliver& sliver, int x0, int y0, int x1, int y1, int row0, const Frame& f,
                 std::vector<uint8_t>& edges) {
  for (int py = y0; py <= y1; ++py) {
    const auto [first, last] = sliver.row_span(py, x0, x1);
    for (int px = first; px <= last; ++px)
      edges[f.index(px, py - row0)] |= edge::unstable;
  }
}

// A block's window depths as the depth test takes them (fragment_depth: GL_DEPTH_CLAMP's
// range, or [0, 1] after a polygon offset); nothing to do for most cases.
inline void clamp_depths(const Case& c, float* z) {
  if (!c.depth_clamp && !c.polygon_offset) return;
  for (int j = 0; j < kRowBlock; ++j)
    z[j] = fragment_depth(c, z[j]);
}

// kRowBlock floats from `from` to `to` (apart), a block's lanes to a frame: a copy of a size
// the compiler sees, which becomes one or two vector moves (std::copy_n, not seeing its count
// as fixed, calls memmove: a call per block and channel; a loop, the source possibly
// overlapping, copies float by float).
inline void copy_block(const float* from, float* to) {
  std::memcpy(to, from, kRowBlock * sizeof(float));
}

// One triangle's fragments with their allowances, kRowBlock covered pixels at a time: each
// per-pixel quantity for the whole block first (the allowances' arithmetic in blocks,
// allowance.hpp), then the depth test pixel by pixel, then the values and allowances of the
// fragments that are drawn or stay candidates. The same bits as one pixel at a time: the
// pixels one triangle covers are different pixels of the frame, so their order among each
// other is free.
class FragmentBlocks {
 public:
  FragmentBlocks(const Settings& s, const Prepared& w, int p, Expectation& r,
                 CandidateMap& candidates)
      : s_(s),
        w_(w),
        p_(p),
        r_(r),
        candidates_(candidates),
        value_(w.planes.size()),
        allowed_(w.planes.size()),
        scratch_(w.planes.size()),
        block_values_(w.planes.size() * kRowBlock) {}
  FragmentBlocks(const FragmentBlocks&) = delete;
  FragmentBlocks& operator=(const FragmentBlocks&) = delete;

  // The fragment of covered pixel (px, py), drawn by the next flush() at the latest (which
  // must come before anything else reads or draws the frame).
  void add(int px, int py) {
    px_[count_] = px, py_[count_] = py;
    if (++count_ == kRowBlock) flush();
  }

  void flush() {
    if (count_ > 0) draw(count_);
    count_ = 0;
  }

 private:
  GLRC_BLOCK_FORM void draw(int count) {
    constexpr int n = kRowBlock;
    const Settings& s = s_;
    const Prepared& w = w_;
    const int p = p_;
    Expectation& r = r_;
    CandidateMap& candidates = candidates_;
    const Case& c = s.c;
    Frame& f = r.frame;
    const TriangleAllowance& a = *w.allowance;
    const auto& planes = w.planes;
    const bool deferred = s.deferred != nullptr;
    // Lanes past `count` repeat the last pixel: computed, never used.
    double x[n], y[n];
    for (int j = 0; j < n; ++j) {
      const int k = std::min(j, count - 1);
      x[j] = double(px_[k]), y[j] = double(py_[k]);
    }
    w.depth.at(x, y, z_);
    clamp_depths(c, z_);
    if (!s.deferred_depth) {
      a.prepare(x, y, block_);
      a.depth_at(block_, z_, z_allowed_);
    } else if (w.clipped) {
      a.freedom().at(x, y, block_.delta);  // for the viewport's sides below
    }
    // The depth test, pixel by pixel: which fragments need their values and allowances.
    int needed = 0, losers = 0;
    for (int j = 0; j < count; ++j) {
      const int px = px_[j], py = py_[j];
      const size_t i = f.index(px, py - s.row0);
      role_[j] = Role::none;
      // The clipped polygon's edges on the x and y planes lie on the viewport's sides (where a
      // whole-number viewport has no pixel centre; a fractional one may); they move with its
      // vertices, inwards too.
      if (w.clipped && viewport_side_distance(c.viewport, px, py) <= block_.delta[j])
        r.edges[i] |= edge::snapping;
      // Every fragment rasterization produces is counted, whether or not it passes the depth
      // test: the count checks coverage, which must not depend on the depth order GL leaves
      // free between fragments within rounding of each other (core/frame.hpp).
      ++f.fragments[i];
      const float z = z_[j], z_allowed = z_allowed_[j];
      const bool passes = depth_test(c.depth_func, z, f.depth[i]);
      if (c.depth_func == DepthFunc::always) {
        take(j, i);
        ++needed;
        continue;
      }
      // The fragments GL may hold at the pixel when this one arrives are the reference's
      // winner and its candidates; at a pixel nothing has been drawn to yet, the clear value
      // (primitive none, depth glClearDepth's, exact: allowance 0). Against one of them (depth
      // `other`), this fragment may pass the test, and may fail it: where their depths are
      // within each other's allowances, either; else as the exact depths say. So a fragment
      // within its allowance of the clear value (depths clamped to the range's far end, a
      // triangle on the far plane) may be kept or not. Against an earlier copy of its own
      // triangle (bitwise-identical clip positions, in the same order: Settings::twin) GL's
      // invariance rules give both the same depth, so the test is decided as for equal depths.
      const bool equal_passes = depth_test(c.depth_func, z, z);
      auto may = [&](bool pass, int32_t other_primitive, float other, float other_allowed) {
        if (other_primitive != Frame::kNoPrimitive &&
            s.twin[size_t(other_primitive)] == s.twin[size_t(p)])
          return pass == equal_passes;
        if (std::fabs(double(z) - double(other)) <= double(z_allowed) + double(other_allowed))
          return true;
        return depth_test(c.depth_func, z, other) == pass;
      };
      // Looked up, not inserted: most pixels have no candidates.
      const auto it = candidates.find(i);
      std::vector<Candidate>* others = it != candidates.end() ? &it->second : nullptr;
      // A candidate this fragment surely passes against is replaced wherever GL holds it.
      if (others)
        std::erase_if(*others, [&](const Candidate& o) {
          return !may(false, o.primitive, o.depth, o.allowed_depth);
        });
      if (!passes) {
        // A candidate itself where it may pass against any fragment GL may hold.
        bool kept = may(true, f.primitive[i], f.depth[i],
                        f.primitive[i] == Frame::kNoPrimitive ? 0.0f : r.allowed.depth[i]);
        for (size_t k = 0; !kept && others && k < others->size(); ++k) {
          const Candidate& o = (*others)[k];
          kept = may(true, o.primitive, o.depth, o.allowed_depth);
        }
        if (!kept) continue;
        role_[j] = Role::loser;
        ++needed, ++losers;
        continue;
      }
      // The old winner is a candidate where this one may fail against it: its allowances as
      // they were drawn, or as the deferred allowance of its triangle gives them.
      const bool cleared = f.primitive[i] == Frame::kNoPrimitive;
      const float held_allowed = cleared ? 0.0f : r.allowed.depth[i];
      if (may(false, f.primitive[i], f.depth[i], held_allowed)) {
        // The clear value as a candidate: no primitive, whose values nothing compares.
        Candidate old{i, f.primitive[i], f.depth[i], held_allowed, {}, {}};
        for (size_t k = 0; k < planes.size(); ++k) {
          old.values.push_back(cleared ? 0.0f : f.components[k][i]);
          old.allowed.push_back(cleared    ? 0.0f
                                : deferred ? s.deferred->at(f, Channel::component(int(k)), i)
                                           : r.allowed.components[k][i]);
        }
        candidates[i].push_back(std::move(old));
      }
      take(j, i);
      ++needed;
    }
    if (needed == 0) return;
    // The values: of the whole block at once when every pixel needs them (padding lanes
    // repeat a pixel), else of those that do; then their allowances, unless deferred and
    // needed by no candidate.
    if (needed == count) {
      w.values.values(x, y, block_values_.data());
      for (size_t k = 0; k < planes.size(); ++k)
        copy_block(block_values_.data() + k * n, value_[k].data());
    } else {
      for (int j = 0; j < count; ++j) {
        if (role_[j] == Role::none) continue;
        w.values.values(px_[j], py_[j], scratch_.data());
        for (size_t k = 0; k < planes.size(); ++k)
          value_[k][size_t(j)] = scratch_[k];
      }
    }
    if (!deferred || losers > 0)
      for (size_t k = 0; k < planes.size(); ++k)
        a.component_at(block_, k, value_[k].data(), allowed_[k].data());
    // The winners' values and allowances, channel by channel: each channel's two frames get the
    // block's pixels (mostly neighbours in a row) together. These stores are most of this
    // function's time on a frame of many channels: every one is a write to memory that nothing
    // here reads again. A block's pixels are distinct, so the order changes no value.
    size_t index[n];
    for (int j = 0; j < count; ++j)
      index[j] = f.index(px_[j], py_[j] - s.row0);
    // Nearly always: a whole block of winners, neighbours in a row. Then each frame gets the
    // block's values as one contiguous copy.
    bool run = count == n;
    for (int j = 0; j < count; ++j)
      run = run && role_[j] == Role::winner && index[j] == index[0] + size_t(j);
    for (size_t k = 0; k < planes.size(); ++k) {
      float* values = f.components[k].data();
      float* allowances = deferred ? nullptr : r.allowed.components[k].data();
      if (run) {
        copy_block(value_[k].data(), values + index[0]);
        if (allowances) copy_block(allowed_[k].data(), allowances + index[0]);
        continue;
      }
      for (int j = 0; j < count; ++j)
        if (role_[j] == Role::winner) {
          values[index[j]] = value_[k][size_t(j)];
          if (allowances) allowances[index[j]] = allowed_[k][size_t(j)];
        }
    }
    for (int j = 0; j < count; ++j) {
      if (role_[j] != Role::loser) continue;
      const size_t i = index[j];
      Candidate loser{i, p, z_[j], z_allowed_[j], {}, {}};
      for (size_t k = 0; k < planes.size(); ++k) {
        loser.values.push_back(value_[k][size_t(j)]);
        loser.allowed.push_back(allowed_[k][size_t(j)]);
      }
      candidates[i].push_back(std::move(loser));
    }
  }

  // Lane j's fragment is the reference's at pixel i (the depth test passed).
  void take(int j, size_t i) {
    Frame& f = r_.frame;
    f.primitive[i] = p_;
    f.depth[i] = z_[j];
    if (!s_.deferred_depth) {
      r_.allowed.primitive[i] = p_;
      r_.allowed.depth[i] = z_allowed_[j];
    }
    role_[j] = Role::winner;
  }

  enum class Role : uint8_t { none, winner, loser };
  const Settings& s_;
  const Prepared& w_;
  const int p_;
  Expectation& r_;
  CandidateMap& candidates_;
  int count_ = 0;
  int px_[kRowBlock]{}, py_[kRowBlock]{};
  float z_[kRowBlock]{}, z_allowed_[kRowBlock]{};
  Role role_[kRowBlock]{};
  TriangleAllowance::Block block_{};
  std::vector<std::array<float, kRowBlock>> value_, allowed_;  // by component, then lane
  std::vector<float> scratch_, block_values_;
};

// One triangle's fragments without an allowance (`digest`, the driver models' edge bits),
// kRowBlock covered pixels at a time: the block's depths at once, the depth test pixel by
// pixel, then the values of the whole block at once when every fragment is drawn (padding
// lanes repeat a pixel), else of those drawn. The same bits as one pixel at a time: the block
// forms give the float nearest each exact ratio as the single-pixel ones do, and the pixels
// one triangle covers are different pixels of the frame, so their order is free.
class FrameBlocks {
 public:
  FrameBlocks(const Settings& s, const Prepared& w, int p, Frame& f)
      : s_(s), w_(w), p_(p), f_(f), block_values_(w.planes.size() * kRowBlock) {}
  FrameBlocks(const FrameBlocks&) = delete;
  FrameBlocks& operator=(const FrameBlocks&) = delete;

  // As FragmentBlocks::add.
  void add(int px, int py) {
    px_[count_] = px, py_[count_] = py;
    if (++count_ == kRowBlock) flush();
  }

  void flush() {
    if (count_ > 0) draw(count_);
    count_ = 0;
  }

 private:
  GLRC_BLOCK_FORM void draw(int count) {
    constexpr int n = kRowBlock;
    const Prepared& w = w_;
    Frame& f = f_;
    const size_t components = w.planes.size();
    for (int j = 0; j < n; ++j) {
      const int k = std::min(j, count - 1);
      x_[j] = double(px_[k]), y_[j] = double(py_[k]);
    }
    w.depth.at(x_, y_, z_);
    clamp_depths(s_.c, z_);
    int drawn = 0;
    for (int j = 0; j < count; ++j) {
      const size_t i = f.index(px_[j], py_[j] - s_.row0);
      index_[j] = i;
      ++f.fragments[i];  // every fragment, passing the depth test or not (FragmentBlocks)
      drawn_[j] = depth_test(s_.c.depth_func, z_[j], f.depth[i]);
      if (!drawn_[j]) continue;
      ++drawn;
      f.primitive[i] = p_;
      f.depth[i] = z_[j];
    }
    if (drawn == 0) return;
    if (drawn == count) {
      w.values.values(x_, y_, block_values_.data());
    } else {
      float* scratch = block_values_.data();  // lane j's components at j·components
      for (int j = 0; j < count; ++j)
        if (drawn_[j]) w.values.values(px_[j], py_[j], scratch + size_t(j) * components);
      for (size_t k = 0; k < components; ++k) {
        float* values = f.components[k].data();
        for (int j = 0; j < count; ++j)
          if (drawn_[j]) values[index_[j]] = scratch[size_t(j) * components + k];
      }
      return;
    }
    // Nearly always a whole block of neighbours in a row: one contiguous copy per channel.
    bool run = count == n;
    for (int j = 0; j < count; ++j)
      run = run && index_[j] == index_[0] + size_t(j);
    for (size_t k = 0; k < components; ++k) {
      float* values = f.components[k].data();
      const float* column = block_values_.data() + k * n;
      if (run) {
        copy_block(column, values + index_[0]);
        continue;
      }
      for (int j = 0; j < count; ++j)
        values[index_[j]] = column[j];
    }
  }

  const Settings& s_;
  const Prepared& w_;
  const int p_;
  Frame& f_;
  int count_ = 0;
  int px_[kRowBlock]{}, py_[kRowBlock]{};
  double x_[kRowBlock]{}, y_[kRowBlock]{};
  float z_[kRowBlock]{};
  size_t index_[kRowBlock]{};
  bool drawn_[kRowBlock]{};
  std::vector<float> block_values_;
};

// Draws triangle p's rows [tile.y0, tile.y1] into r: the edge bits of the pixels it may reach,
// then the fragments it covers, depth-tested, with their allowances and the candidates. With an
// AVX2 copy (core/vector_clones.hpp): the spans' ceil and floor are an instruction each there.
GLRC_VECTOR_CLONES void draw_rows(const Settings& s, const Prepared& w, int p, Tile tile,
                                  Expectation& r, CandidateMap& candidates) {
  const TriangleSetup& t = w.t;
  Frame& f = r.frame;
  auto delta_at = [&](int px, int py) {
    return s.allowance ? w.freedom().at(px, py) : s.model_step;
  };

  // The covered pixels a block at a time: with their allowances (FragmentBlocks) or without.
  std::optional<FragmentBlocks> blocks;
  std::optional<FrameBlocks> frame_blocks;
  if (s.allowance)
    blocks.emplace(s, w, p, r, candidates);
  else
    frame_blocks.emplace(s, w, p, f);

  if (w.eye)
    mark_unstable(s.viewport.x0, std::max(tile.y0, s.viewport.y0), s.viewport.x1,
                  std::min(tile.y1, s.viewport.y1), s.row0, f, r.edges);
  for (const Sliver& piece : w.turning)
    mark_sliver(piece, s.viewport.x0, std::max(tile.y0, s.viewport.y0), s.viewport.x1,
                std::min(tile.y1, s.viewport.y1), s.row0, f, r.edges);
  // Beyond a fractional viewport's sides, within how far they may move: the centres the
  // triangle may reach there (its box grown by its margin) are an implementation's to draw or
  // not, with this triangle or another.
  const bool beyond = s.reach.x0 < s.viewport.x0 || s.reach.x1 > s.viewport.x1 ||
                      s.reach.y0 < s.viewport.y0 || s.reach.y1 > s.viewport.y1;
  if (beyond && t.drawn && !t.box.empty() && s.edges)
    for (int py = std::max({tile.y0, s.reach.y0, t.box.y0 - w.margin});
         py <= std::min({tile.y1, s.reach.y1, t.box.y1 + w.margin}); ++py)
      for (int px = std::max(s.reach.x0, t.box.x0 - w.margin);
           px <= std::min(s.reach.x1, t.box.x1 + w.margin); ++px)
        if (px < s.viewport.x0 || px > s.viewport.x1 || py < s.viewport.y0 || py > s.viewport.y1)
          r.edges[f.index(px, py - s.row0)] |= edge::unstable;
  // Rows [cy0, cy1]: those of the tile the triangle may cover.
  const bool draws = t.drawn && !t.box.empty();
  const int cy0 = std::max(tile.y0, t.box.y0), cy1 = std::min(tile.y1, t.box.y1);
  auto add = [&](int px, int py) {
    if (blocks)
      blocks->add(px, py);
    else
      frame_blocks->add(px, py);
  };
  auto flush = [&] {
    if (blocks) blocks->flush();
    if (frame_blocks) frame_blocks->flush();
  };
  // Without edge bits, a walked triangle needs no spans: its runs are exact. Walked down its
  // columns where they are fewer than its rows in the tile (a thin triangle nearer vertical: a
  // pixel or none a row, where a column has several), else along its rows, each line's run at
  // once; over the columns that can hold its pixels of these rows, not the whole box.
  if (!s.edges && draws && cy0 <= cy1) {
    // The lines from `first` in turn, each one's run at once; draw(line, k) for k in the run.
    auto walk_lines = [&](CoverageTest::CoveredRows& lines, int first, int count, auto draw) {
      int line = first;
      lines.for_each_row(count, [&](int lo, int hi) {
        for (int k = lo; k <= hi; ++k)
          draw(line, k);
        ++line;
      });
      flush();
    };
    const auto [cx0, cx1] = w.coverage.columns_of_rows(cy0, cy1);
    if (cx0 > cx1) return;  // nothing of it in these rows
    if (cx1 - cx0 < cy1 - cy0) {
      if (auto columns = w.coverage.covered_columns(cx0, cx1, cy0, cy1))
        return walk_lines(*columns, cx0, cx1 - cx0 + 1, [&](int px, int py) { add(px, py); });
    }
    if (auto rows = w.coverage.covered_rows(cy0, cy1, cx0, cx1))
      return walk_lines(*rows, cy0, cy1 - cy0 + 1, [&](int py, int px) { add(px, py); });
  }
  // With edge bits: the covered pixels of row py within [x0, x1] (its span), a block at a time.
  // Walked row after row (CoverageTest::CoveredRows) where the coverage test allows, else tested
  // pixel by pixel (for_each_covered); every row of [cy0, cy1] passed here in order when it
  // draws.
  std::optional<CoverageTest::CoveredRows> walk;
  if (draws && cy0 <= cy1) walk = w.coverage.covered_rows(cy0, cy1, t.box.x0, t.box.x1);
  auto draw_row = [&](int py, int x0, int x1) {
    if (!walk) {
      w.coverage.for_each_covered(py, std::max(x0, t.box.x0), std::min(x1, t.box.x1),
                                  [&](int px) { add(px, py); });
      return;
    }
    const auto [lo, hi] = walk->next();
    for (int px = std::max(lo, x0), last = std::min(hi, x1); px <= last; ++px)
      add(px, py);
  };
  // Only the pixels within `margin` of the triangle, row by row (CoverageTest::row_span): a
  // thin triangle's bounding box holds a thousand times the pixels it reaches. Classifying only
  // ORs edge bits and drawing never reads them, so one span per row serves both, in one pass.
  // The span holds every pixel the triangle covers, so a walked row's run is cut to it for
  // nothing: the same pixels either way.
  const int y0 = std::max(tile.y0, w.reach.y0), y1 = std::min(tile.y1, w.reach.y1);
  const CoverageTest::RowSpans spans =
      w.coverage.row_spans(w.reach_px, w.reach.x0, w.reach.x1, y0, y1);
  for (int py = y0; py <= y1; ++py) {
    const auto [x0, x1] = spans.at(py);
    for (int px = x0; s.edges && px <= x1; ++px)
      // Most pixels are beyond or deep within every band: no freedom to compute for them.
      if (!w.coverage.classifies_nothing(px, py, w.largest, w.unstable,
                                         s.allowance ? w.freedom().z_clip_largest() : 0.0))
        r.edges[f.index(px, py - s.row0)] |=
            w.coverage.classify(px, py, delta_at(px, py), w.shared, w.unstable,
                                s.allowance ? w.freedom().z_clip_at(px, py) : 0.0);
    if (!draws || py < t.box.y0 || py > t.box.y1) continue;
    draw_row(py, x0, x1);
  }
  flush();
}

}  // namespace

Expectation render(const Case& c, const Model& m, std::optional<int> freedom_bits, int threads) {
  return render_rows(c, m, freedom_bits, threads, 0, c.fb_height);
}

namespace {

// Empties every element of v on the pool's threads: a case's setups and prepared triangles
// hold many GMP numbers each, and freeing them on one thread was a serial tenth of drawing a
// fan.
template <class T>
void release(std::vector<T>& v, ThreadPool& pool) {
  pool.parallel_for(int(v.size()), [&](int k) { v[size_t(k)] = {}; });
}

// Sets the components of the frame and of the allowance to 0 (Frame's clear value) at every
// pixel no fragment was drawn at (no primitive): the frames were made with their components
// uncleared (Frame::reset_uncleared_components), and a drawn fragment writes every component of
// both. In chunks of pixels on the pool's threads, each finding its runs of undrawn pixels once.
void clear_uncovered(Expectation& r, ThreadPool& pool) {
  const Frame& f = r.frame;
  const size_t n = f.pixel_count();
  constexpr size_t kChunk = size_t(1) << 16;
  pool.parallel_for(int((n + kChunk - 1) / kChunk), [&](int k) {
    // The primitive, not the fragment count: a count of 65,536 fragments wraps to 0.
    const int32_t* primitive = f.primitive.data();
    const size_t end = std::min(n, (size_t(k) + 1) * kChunk);
    for (size_t i = size_t(k) * kChunk; i < end;) {
      if (primitive[i] != Frame::kNoPrimitive) {
        ++i;
        continue;
      }
      size_t j = i + 1;
      while (j < end && primitive[j] == Frame::kNoPrimitive)
        ++j;
      for (Frame* frame : {&r.frame, &r.allowed})
        for (std::vector<float>& component : frame->components)
          std::fill(component.begin() + ptrdiff_t(i), component.begin() + ptrdiff_t(j), 0.0f);
      i = j;
    }
  });
}

// render_rows(), and without `edges` its frame alone (render_frame): no edge bits, so neither
// the shared edges nor the bands are looked for. In `storage`'s buffers, where given.
// `deferred`: with an allowance, its components computed where asked for (render_deferred).
// `keep`: where given, the triangles' set-up is handed back there instead of freed.
// What one draw() of the reference makes: every public render function is one request.
struct DrawRequest {
  // With the allowance of an implementation of these GL_SUBPIXEL_BITS (at least 4 taken); none:
  // no allowance, and edge bands one model subpixel step wide.
  std::optional<int> freedom_bits;
  // The components' allowances (and the depth's, without a depth test) deferred to a
  // TriangleAllowances: only with freedom_bits.
  bool deferred = false;
  int threads = 1;  // thread_count's
  int y0 = 0;       // rows [y0, y0 + rows) of the framebuffer
  int rows = 0;
  bool edges = true;  // the edge bits too (render_frame: only the frame)
};

// `storage`: an Expectation whose buffers are reused; `keep`: where the triangles' set-up is
// handed back (render()'s overloads with a CaseSetup).
Expectation draw(const Case& c, const Model& m, const DrawRequest& request,
                 Expectation* storage = nullptr, std::shared_ptr<const CaseSetup>* keep = nullptr) {
  const int y0 = request.y0, row_count = request.rows;
  const bool edges = request.edges;
  if (y0 < 0 || row_count < 0 || row_count > c.fb_height - y0)
    throw std::invalid_argument("render_rows: rows [" + std::to_string(y0) + ", " +
                                std::to_string(int64_t(y0) + row_count) +
                                ") outside a framebuffer " + std::to_string(c.fb_height) + " high");
  const int threads = thread_count(request.threads);
  // One set of threads for every step below (core/parallel.hpp).
  ThreadPool pool(threads);
  // The frames cleared on every thread, a buffer each: on a large frame of many channels,
  // filling them is otherwise a serial part of drawing it.
  Expectation r;
  if (storage) r = std::exchange(*storage, Expectation{});
  const bool allowance = request.freedom_bits.has_value();
  const bool deferred = request.deferred && allowance;
  // The components are cleared where nothing is drawn once everything is (clear_uncovered):
  // every fragment drawn writes all of them, in the frame and in the allowance alike.
  r.frame.reset_uncleared_components(c.fb_width, row_count, c.component_count(), threads);
  // Frame's clear depth is 1.0, GL's default; the case's glClearDepth where it differs.
  if (c.depth_clear != 1.0f) std::fill(r.frame.depth.begin(), r.frame.depth.end(), c.depth_clear);
  // Without a depth test, no fragment may win it instead of another (no candidates), and the
  // depth's allowance is only compared: deferred with the components'.
  const bool deferred_depth = deferred && c.depth_func == DepthFunc::always;
  if (allowance && !deferred_depth) {
    r.allowed.reset_uncleared_components(c.fb_width, row_count, deferred ? 0 : c.component_count(),
                                         threads);
  } else {
    r.allowed = Frame();
  }
  r.deferred.reset();
  std::shared_ptr<TriangleAllowances> kept;
  if (deferred) kept = std::make_shared<TriangleAllowances>(c.triangles.size(), y0, deferred_depth);
  r.candidates.clear();
  if (!edges) r.edges = {};
  Frame& f = r.frame;
  pool.parallel_for(edges ? 2 : 1, [&](int b) {
    if (b == 1)
      assign_large(r.edges, f.pixel_count(), uint8_t(0));
    else
      assign_large(f.fragments, f.pixel_count(), uint16_t(0));
  });
  // Without an allowance, coverage may legally differ within one model subpixel step of an
  // edge (1/256 pixel when the model does not snap).
  Settings s{.c = c,
             .m = m,
             .allowance = allowance,
             .edges = edges,
             .bits = allowance ? std::max(*request.freedom_bits, 4) : 0,
             .model_step = std::ldexp(1.0, -(m.subpixel_bits > 0 ? m.subpixel_bits : 8)),
             .viewport = viewport_box(c),
             .reach = viewport_reach(c),
             .component_smooth = {},
             .row0 = y0,
             .deferred = kept.get(),
             .deferred_depth = deferred_depth,
             .twin = {}};
  // Only the rows asked for: what a triangle does elsewhere changes nothing in them.
  s.viewport.y0 = std::max(s.viewport.y0, y0);
  s.viewport.y1 = std::min(s.viewport.y1, y0 + row_count - 1);
  s.reach.y0 = std::max(s.reach.y0, y0);
  s.reach.y1 = std::min(s.reach.y1, y0 + row_count - 1);
  for (int v : component_varying(c))
    s.component_smooth.push_back(c.varyings[size_t(v)].interpolation == Interpolation::smooth);
  if (allowance && c.depth_func != DepthFunc::always) s.twin = identical_triangles(c);

  const int count = int(c.triangles.size());
  std::vector<std::optional<TriangleSetup>> setups = setup_triangles(c, m, pool);
  // Which edges are shared marks edge bits only.
  SharedEdges groups = edges ? shared_edge_groups(setups, threads) : SharedEdges(setups.size());
  const std::vector<std::array<bool, 3>> shared = shared_flags(groups);

  const std::vector<Tile> rows = tiles(s.reach.y0, s.reach.y1, threads);
  std::vector<CandidateMap> candidates(rows.size());
  // A chunk of triangles prepared at a time: their work held at once, not the whole case's.
  constexpr int kChunk = 512;
  std::vector<std::unique_ptr<const Prepared>> prepared;
  std::vector<std::optional<Sliver>> slivers;
  for (int first = 0; first < count; first += kChunk) {
    const int n = std::min(kChunk, count - first);
    prepared.clear();
    prepared.resize(size_t(n));
    slivers.assign(size_t(n), std::nullopt);
    pool.parallel_for(n, [&](int k) {
      const int p = first + k;
      const TriangleSetup& t = *setups[size_t(p)];
      if (t.discarded) return;  // by a cull distance: by every implementation
      // Zero area: drawn by no model, but a sliver of some implementation's (Sliver). Its
      // facing is either, so only culling both faces rules it out.
      if (allowance && !t.has_edges && c.cull != CullFace::front_and_back) {
        const PositionFreedom freedom(c, t, s.bits);
        if (freedom.reaches_eye() || !freedom.sliver_sources().empty())
          slivers[size_t(k)].emplace(freedom);
        return;
      }
      // A triangle this model does not draw (zero snapped area, culled) may still be drawn by
      // another implementation when its orientation is not decided by the freedom.
      if (!t.drawn && !(allowance && t.has_edges && c.cull != CullFace::front_and_back)) return;
      auto w = std::make_unique<const Prepared>(s, t, shared[size_t(p)]);
      if (!t.drawn && !w->unstable && w->turning.empty()) return;
      prepared[size_t(k)] = std::move(w);
    });
    if (kept)
      for (int k = 0; k < n; ++k)
        if (const Prepared* w = prepared[size_t(k)].get(); w && w->t.drawn)
          kept->add(size_t(first + k), w->allowance);
    pool.parallel_for(int(rows.size()), [&](int b) {
      for (int k = 0; k < n; ++k)
        if (const Prepared* w = prepared[size_t(k)].get();
            w && w->reach.y0 <= rows[size_t(b)].y1 && w->reach.y1 >= rows[size_t(b)].y0)
          draw_rows(s, *w, first + k, rows[size_t(b)], r, candidates[size_t(b)]);
        else if (const auto& sliver = slivers[size_t(k)])
          mark_sliver(*sliver, s.viewport.x0, std::max(s.viewport.y0, rows[size_t(b)].y0),
                      s.viewport.x1, std::min(s.viewport.y1, rows[size_t(b)].y1), s.row0, f,
                      r.edges);
    });
    release(prepared, pool);
  }
  if (keep) {
    auto setup = std::make_shared<CaseSetup>();
    setup->triangles = std::move(setups);
    setup->shared = std::move(groups);
    setup->threads = threads;
    *keep = std::move(setup);
  } else {
    release(setups, pool);
  }
  clear_uncovered(r, pool);
  // Tiles in order, each in pixel order: the candidates sorted by pixel, as with one tile.
  // (Only with an allowance are there any.)
  for (CandidateMap& tile : candidates)
    for (auto& [i, list] : tile) {
      if (list.empty()) continue;
      r.edges[i] |= edge::depth_order;
      for (Candidate& k : list)
        r.candidates.push_back(std::move(k));
    }
  r.deferred = std::move(kept);
  return r;
}

}  // namespace

Expectation render_rows(const Case& c, const Model& m, std::optional<int> freedom_bits, int threads,
                        int y0, int row_count) {
  return draw(c, m,
              {.freedom_bits = freedom_bits, .threads = threads, .y0 = y0, .rows = row_count});
}

Expectation render_rows_deferred(const Case& c, const Model& m, int freedom_bits, int threads,
                                 int y0, int row_count, Expectation&& storage) {
  return draw(c, m,
              {.freedom_bits = freedom_bits,
               .deferred = true,
               .threads = threads,
               .y0 = y0,
               .rows = row_count},
              &storage);
}

Expectation render(const Case& c, const Model& m, std::optional<int> freedom_bits, int threads,
                   Expectation&& storage) {
  return draw(c, m, {.freedom_bits = freedom_bits, .threads = threads, .rows = c.fb_height},
              &storage);
}

Expectation render_deferred(const Case& c, const Model& m, int freedom_bits, int threads,
                            Expectation&& storage) {
  return draw(
      c, m,
      {.freedom_bits = freedom_bits, .deferred = true, .threads = threads, .rows = c.fb_height},
      &storage);
}

Expectation render(const Case& c, const Model& m, std::optional<int> freedom_bits, int threads,
                   Expectation&& storage, std::shared_ptr<const CaseSetup>& setup) {
  return draw(c, m, {.freedom_bits = freedom_bits, .threads = threads, .rows = c.fb_height},
              &storage, &setup);
}

Expectation render_deferred(const Case& c, const Model& m, int freedom_bits, int threads,
                            Expectation&& storage, std::shared_ptr<const CaseSetup>& setup) {
  return draw(
      c, m,
      {.freedom_bits = freedom_bits, .deferred = true, .threads = threads, .rows = c.fb_height},
      &storage, &setup);
}

Frame render_frame(const Case& c, const Model& m, int threads) {
  return std::move(draw(c, m, {.threads = threads, .rows = c.fb_height, .edges = false}).frame);
}

}  // namespace glrc::ref
