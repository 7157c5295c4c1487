// Port of the edge setup of Mesa 22.3.6 lp_setup_tri.c (do_triangle_ccw: bounding box, plane
// c/dcdx/dcdy/eo with the fill-convention bias; lp_setup_bin_triangle: which tiles and planes
// are rasterized), lp_setup.c (lp_setup_add_scissor_planes) and the tests of lp_rast_tri.c and
// lp_rast_tri_tmp.h.
#include "driver_models/llvmpipe_raster.hpp"

#include <algorithm>
#include <bit>
#include <functional>

namespace glrc::driver_models {
namespace {

constexpr int kTileOrder = 6;  // TILE_ORDER: 64x64 tiles
constexpr int kTileSize = 1 << kTileOrder;
// MAX_FIXED_LENGTH32: boxes up to this many pixels take the 32-bit rasterizers.
constexpr int kMaxFixedLength32 = 1 << (15 - kLlvmpipeFixedOrder);

// llvmpipe's integer code relies on two's complement wrapping (SSE lanes, and C that the
// compiler turns into the same instructions); these spell it out without undefined behaviour.
int32_t wrap32(int64_t v) {
  return int32_t(uint32_t(uint64_t(v)));
}
int32_t add32(int32_t a, int32_t b) {
  return int32_t(uint32_t(a) + uint32_t(b));
}
int32_t sub32(int32_t a, int32_t b) {
  return int32_t(uint32_t(a) - uint32_t(b));
}
int32_t mul32(int32_t a, int32_t b) {
  return int32_t(uint32_t(a) * uint32_t(b));
}
int32_t shl32(int32_t a, int n) {
  return int32_t(uint32_t(a) << n);
}
int64_t add64(int64_t a, int64_t b) {
  return int64_t(uint64_t(a) + uint64_t(b));
}
int64_t sub64(int64_t a, int64_t b) {
  return int64_t(uint64_t(a) - uint64_t(b));
}

// struct lp_rast_plane: c at the framebuffer origin, steps scaled by FIXED_ONE, and the
// one-pixel trivial-reject offset.
struct RastPlane {
  int64_t c = 0;
  int32_t dcdx = 0, dcdy = 0;
  uint32_t eo = 0;
};

// u_rect, inclusive.
struct Rect {
  int32_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};

// floor_pot: the highest set bit (bsr), as the int the caller stores it in.
int32_t floor_pot(uint32_t n) {
  return n == 0 ? 0 : int32_t(uint32_t(1) << (31 - std::countl_zero(n)));
}

// build_mask_linear_sse / build_masks_sse: bit 4 * row + col is the sign of
// c + col * dcdx + row * dcdy in int32 (the saturating packs keep the sign).
unsigned sign_mask(int32_t c, int32_t dcdx, int32_t dcdy) {
  unsigned mask = 0;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col)
      if (add32(add32(c, mul32(dcdx, col)), mul32(dcdy, row)) < 0) mask |= 1u << (4 * row + col);
  return mask;
}

// lp_rast_tri_tmp.h built with RASTER_64 (lp_rast_triangle_N, do_block_16, do_block_4): per
// tile, 16x16 and then 4x4 blocks trivially rejected, shaded whole, or tested further.
class Raster64 {
 public:
  Raster64(int fb_width, int fb_height, const std::vector<RastPlane>& planes,
           const std::function<void(int, int)>& covered)
      : width_(fb_width), height_(fb_height), planes_(planes), covered_(covered) {}

  // lp_rast_triangle_N (RASTER_64) on the tile whose top-left pixel is (x, y), with the
  // planes in plane_mask.
  void tile(int x, int y, unsigned plane_mask) {
    std::vector<const RastPlane*> planes;
    std::vector<int64_t> c;
    for (size_t i = 0; i < planes_.size(); ++i)
      if (plane_mask >> i & 1) {
        const RastPlane& p = planes_[i];
        planes.push_back(&p);
        c.push_back(sub64(add64(p.c, int64_t(p.dcdy) * y), int64_t(p.dcdx) * x));
      }
    blocks(planes, c, x, y, 16);
  }

  // lp_rast_shade_tile: every 4x4 block inside the framebuffer.
  void whole(int x, int y) {
    for (int py = y; py < y + kTileSize; ++py)
      for (int px = x; px < x + kTileSize; ++px)
        emit(px, py);
  }

 private:
  // The 4x4 grid of blocks of `size` pixels from (x, y) (lp_rast_triangle: 16, do_block_16:
  // 4): trivially rejected, trivially accepted (shaded whole), or descended into.
  void blocks(const std::vector<const RastPlane*>& planes, const std::vector<int64_t>& c, int x,
              int y, int size) {
    const int shift = size == 16 ? 4 : 2;
    unsigned outmask = 0, partmask = 0;
    for (size_t j = 0; j < planes.size(); ++j) {
      const RastPlane& p = *planes[j];
      // The low FIXED_ORDER bits of c never change the sign, so the tests run on c >> 8 in
      // 32 bits; with wrapped steps (a vertex at INT32_MIN) they wrap too.
      int32_t dcdx = sub32(0, p.dcdx) >> kLlvmpipeFixedOrder;
      int32_t dcdy = p.dcdy >> kLlvmpipeFixedOrder;
      const int32_t cox = int32_t(p.eo >> kLlvmpipeFixedOrder);
      const int32_t ei = shl32(sub32(add32(dcdy, dcdx), cox), shift);
      const int32_t cox_s = shl32(cox, shift);
      const int32_t co = add32(wrap32(c[j] >> kLlvmpipeFixedOrder), cox_s);
      const int32_t cdiff =
          add32(sub32(ei, cox_s), sub32(wrap32(sub64(c[j], 1) >> kLlvmpipeFixedOrder),
                                        wrap32(c[j] >> kLlvmpipeFixedOrder)));
      dcdx = shl32(dcdx, shift);
      dcdy = shl32(dcdy, shift);
      outmask |= sign_mask(co, dcdx, dcdy);
      partmask |= sign_mask(add32(co, cdiff), dcdx, dcdy);
    }
    if (outmask == 0xffff) return;
    const unsigned inmask = ~partmask & 0xffff;
    const unsigned partial = partmask & ~outmask;
    for (int i = 0; i < 16; ++i) {
      const int ix = (i & 3) * size, iy = (i >> 2) * size;
      if (partial >> i & 1) {
        std::vector<int64_t> cx(c.size());
        for (size_t j = 0; j < c.size(); ++j)
          cx[j] = add64(sub64(c[j], int64_t(planes[j]->dcdx) * ix), int64_t(planes[j]->dcdy) * iy);
        if (size == 16)
          blocks(planes, cx, x + ix, y + iy, 4);
        else
          block4(planes, cx, x + ix, y + iy);
      } else if (inmask >> i & 1) {
        for (int py = y + iy; py < y + iy + size; ++py)
          for (int px = x + ix; px < x + ix + size; ++px)
            emit(px, py);
      }
    }
  }

  // do_block_4 (RASTER_64).
  void block4(const std::vector<const RastPlane*>& planes, const std::vector<int64_t>& c, int x,
              int y) {
    unsigned mask = 0xffff;
    for (size_t j = 0; j < planes.size(); ++j)
      mask &= ~sign_mask(wrap32(sub64(c[j], 1) >> kLlvmpipeFixedOrder),
                         sub32(0, planes[j]->dcdx) >> kLlvmpipeFixedOrder,
                         planes[j]->dcdy >> kLlvmpipeFixedOrder);
    for (int i = 0; i < 16; ++i)
      if (mask >> i & 1) emit(x + (i & 3), y + (i >> 2));
  }

  // Fragments outside the framebuffer land in the tile's padding (or are filtered out by
  // lp_rast_shade_quads_mask_sample): never seen.
  void emit(int px, int py) {
    if (px < width_ && py < height_) covered_(px, py);
  }

  int width_, height_;
  const std::vector<RastPlane>& planes_;
  const std::function<void(int, int)>& covered_;
};

}  // namespace

LlvmpipeEdges llvmpipe_edges(const LlvmpipeTriangle& t, const PixelRect& region) {
  LlvmpipeEdges e;
  // Edge i runs from vertex i to vertex i+1: dcdx = y_i - y_j, dcdy = x_i - x_j,
  // c = dcdx * x_i - dcdy * y_i.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const int64_t dcdx = int64_t(t.y[i]) - t.y[j];
    const int64_t dcdy = int64_t(t.x[i]) - t.x[j];
    int64_t c = dcdx * t.x[i] - dcdy * t.y[i];
    // Fill convention for a y-up FBO (bottom_edge_rule 0): left edges (dcdx < 0) and
    // horizontal edges with dcdy >= 0 include their pixel centres (the SSE path's c_dec).
    if (dcdx < 0 || (dcdx == 0 && dcdy >= 0)) ++c;
    e.c[i] = c;
    e.dcdx[i] = dcdx * (1 << kLlvmpipeFixedOrder);
    e.dcdy[i] = dcdy * (1 << kLlvmpipeFixedOrder);
  }
  // For the 32-bit rasterizers' triangles (boxes up to 128 px) nothing wraps, and a box one
  // pixel wider than the snapped vertices holds every pixel the edges can accept.
  const int32_t min_x = std::min({t.x[0], t.x[1], t.x[2]});
  const int32_t max_x = std::max({t.x[0], t.x[1], t.x[2]});
  const int32_t min_y = std::min({t.y[0], t.y[1], t.y[2]});
  const int32_t max_y = std::max({t.y[0], t.y[1], t.y[2]});
  e.x0 = std::max((min_x >> kLlvmpipeFixedOrder) - 1, region.x0);
  e.x1 = std::min((max_x >> kLlvmpipeFixedOrder) + 1, region.x1);
  e.y0 = std::max((min_y >> kLlvmpipeFixedOrder) - 1, region.y0);
  e.y1 = std::min((max_y >> kLlvmpipeFixedOrder) + 1, region.y1);
  return e;
}

void llvmpipe_coverage(const LlvmpipeTriangle& t, int fb_width, int fb_height,
                       const PixelRect& draw_region, const std::function<void(int, int)>& covered) {
  const auto [min_x, max_x] = std::minmax({t.x[0], t.x[1], t.x[2]});
  const auto [min_y, max_y] = std::minmax({t.y[0], t.y[1], t.y[2]});
  // do_triangle_ccw: x0, y0 inclusive, x1, y1 exclusive of the last subpixel (adj = 0 for
  // bottom_edge_rule 0).
  Rect bbox{min_x >> kLlvmpipeFixedOrder, min_y >> kLlvmpipeFixedOrder,
            sub32(max_x, 1) >> kLlvmpipeFixedOrder, sub32(max_y, 1) >> kLlvmpipeFixedOrder};
  // draw_regions: the framebuffer, within the scissor box when the scissor test is on.
  const Rect region{draw_region.x0, draw_region.y0, draw_region.x1, draw_region.y1};
  if (region.x0 > region.x1 || region.y0 > region.y1) return;
  if (bbox.x1 < region.x0 || region.x1 < bbox.x0 || bbox.y1 < region.y0 || region.y1 < bbox.y0)
    return;
  const int32_t max_szorig = sub32(bbox.x1, bbox.x0 & ~3) | sub32(bbox.y1, bbox.y0 & ~3);
  if (max_szorig <= kMaxFixedLength32) {
    // The 32-bit rasterizers: a box this small wraps nothing, so their block tests give the
    // plain edge test.
    const LlvmpipeEdges e = llvmpipe_edges(t, draw_region);
    for (int py = e.y0; py <= e.y1; ++py)
      for (int px = e.x0; px <= e.x1; ++px)
        if (llvmpipe_covers(e, px, py)) covered(px, py);
    return;
  }
  bbox.x0 = std::max(bbox.x0, 0);
  bbox.y0 = std::max(bbox.y0, 0);

  // The SSE plane setup: 32-bit differences (they wrap for a vertex far away, e.g. one whose
  // NaN window position became INT32_MIN), 64-bit c, steps scaled in 32 bits.
  std::vector<RastPlane> planes;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const int32_t dcdx = sub32(t.y[i], t.y[j]);
    const int32_t dcdy = sub32(t.x[i], t.x[j]);
    RastPlane p;
    p.c = sub64(int64_t(dcdx) * t.x[i], int64_t(dcdy) * t.y[i]);
    // Fill convention for a y-up FBO (bottom_edge_rule 0): left edges (dcdx < 0) and
    // horizontal edges with dcdy >= 0 include their pixel centres (c_dec).
    if (dcdx < 0 || (dcdx == 0 && dcdy >= 0)) p.c = add64(p.c, 1);
    p.dcdx = shl32(dcdx, kLlvmpipeFixedOrder);
    p.dcdy = shl32(dcdy, kLlvmpipeFixedOrder);
    // The signs are the unscaled steps', the values the scaled ones.
    p.eo = uint32_t(sub32(dcdy < 0 ? 0 : p.dcdy, dcdx < 0 ? p.dcdx : 0));
    planes.push_back(p);
  }
  // lp_setup_add_scissor_planes for the sides of the draw region the box crosses, in its order
  // (left, right, bottom, top); without a scissor box only the right and top framebuffer
  // edges, as the box is clamped at 0.
  if (bbox.x0 < region.x0)
    planes.push_back({-(int64_t(region.x0 - 1) << kLlvmpipeFixedOrder),
                      shl32(-1, kLlvmpipeFixedOrder), 0, uint32_t(1 << kLlvmpipeFixedOrder)});
  if (bbox.x1 > region.x1)
    planes.push_back(
        {int64_t(region.x1 << kLlvmpipeFixedOrder) + 127, 1 << kLlvmpipeFixedOrder, 0, 0});
  if (bbox.y0 < region.y0)
    planes.push_back({-(int64_t(region.y0 - 1) << kLlvmpipeFixedOrder), 0, 1 << kLlvmpipeFixedOrder,
                      uint32_t(1 << kLlvmpipeFixedOrder)});
  if (bbox.y1 > region.y1)
    planes.push_back(
        {int64_t(region.y1 << kLlvmpipeFixedOrder) + 127, 0, shl32(-1, kLlvmpipeFixedOrder), 0});
  const unsigned all_planes = (1u << planes.size()) - 1;

  Raster64 raster(fb_width, fb_height, planes, covered);
  // lp_setup_bin_triangle: a box within one tile goes to that tile with every plane (whatever
  // the box's size: the 64-bit 3_4 and 3_16 commands run the whole-tile rasterizer), even
  // where the edges reach beyond the box.
  if (floor_pot(uint32_t((bbox.x0 ^ bbox.x1) | (bbox.y0 ^ bbox.y1))) < kTileSize) {
    raster.tile(bbox.x0 / kTileSize * kTileSize, bbox.y0 / kTileSize * kTileSize, all_planes);
    return;
  }
  // Otherwise every tile of the box within the framebuffer is tested in 64 bits: rejected,
  // shaded whole, or rasterized with the planes it is not inside of; a row stops at the
  // first rejected tile after one that was not.
  const Rect trimmed{std::max(bbox.x0, region.x0), std::max(bbox.y0, region.y0),
                     std::min(bbox.x1, region.x1), std::min(bbox.y1, region.y1)};
  const int ix0 = trimmed.x0 / kTileSize, iy0 = trimmed.y0 / kTileSize;
  const int ix1 = trimmed.x1 / kTileSize, iy1 = trimmed.y1 / kTileSize;
  const size_t n = planes.size();
  std::vector<int64_t> c(n), ei(n), eo(n), xstep(n), ystep(n);
  for (size_t i = 0; i < n; ++i) {
    const RastPlane& p = planes[i];
    c[i] = sub64(add64(p.c, int64_t(p.dcdy) * iy0 * kTileSize), int64_t(p.dcdx) * ix0 * kTileSize);
    ei[i] = int64_t(uint64_t(int64_t(sub32(p.dcdy, p.dcdx)) - int64_t(p.eo)) << kTileOrder);
    eo[i] = int64_t(p.eo) << kTileOrder;
    xstep[i] = -(int64_t(p.dcdx) << kTileOrder);
    ystep[i] = int64_t(p.dcdy) << kTileOrder;
  }
  for (int y = iy0; y <= iy1; ++y) {
    bool in = false;
    std::vector<int64_t> cx = c;
    for (int x = ix0; x <= ix1; ++x) {
      bool out = false;
      unsigned partial = 0;
      for (size_t i = 0; i < n; ++i) {
        out = out || add64(cx[i], eo[i]) < 0;
        if (sub64(add64(cx[i], ei[i]), 1) < 0) partial |= 1u << i;
      }
      if (out) {
        if (in) break;
      } else {
        in = true;
        if (partial)
          raster.tile(x * kTileSize, y * kTileSize, partial);
        else
          raster.whole(x * kTileSize, y * kTileSize);
      }
      for (size_t i = 0; i < n; ++i)
        cx[i] = add64(cx[i], xstep[i]);
    }
    for (size_t i = 0; i < n; ++i)
      c[i] = add64(c[i], ystep[i]);
  }
}

LlvmpipeRasterizer::LlvmpipeRasterizer(const Case& c, bool fma, FrameWriter& writer)
    : case_(c),
      fma_(fma),
      writer_(writer),
      interpolation_(component_interpolation(c)),
      values_(interpolation_.size()),
      builtins_(writes_builtins(c)) {}

void LlvmpipeRasterizer::triangle(const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2,
                                  int32_t primitive) {
  LlvmpipeTriangle t;
  if (!llvmpipe_setup_triangle(case_, v0, v1, v2, t)) return;
  const LlvmpipeCoefficients k =
      llvmpipe_coefficients(t, interpolation_, case_.provoking == ProvokingVertex::first,
                            case_.polygon_offset ? &*case_.polygon_offset : nullptr);
  const std::array<float, 2> bounds = llvmpipe_depth_bounds(case_);
  llvmpipe_coverage(t, case_.fb_width, case_.fb_height, scissor_region(case_), [&](int px, int py) {
    float position[2];
    float depth = llvmpipe_fragment(k, interpolation_, px, py, fma_, values_.data(),
                                    builtins_ ? position : nullptr);
    if (case_.depth_clamp) depth = llvmpipe_depth_clamp(depth, bounds);
    if (builtins_)
      write_builtins(case_, px, py, position[0], position[1], t.front_facing, values_.data());
    writer_.fragment(px, py, primitive, depth, values_.data());
  });
}

}  // namespace glrc::driver_models
