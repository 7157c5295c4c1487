// The draw module paths, from draw_pt_vsplit.c, draw_pt_fetch_shade_pipeline_llvm.c,
// draw_pt_fetch_shade_pipeline.c and draw_pipe_validate.c (Mesa 22.3.6).
#include "driver_models/draw.hpp"

#include <algorithm>
#include <deque>

#include "driver_models/draw_offset.hpp"
#include "driver_models/mesa_clipper.hpp"

namespace glrc::driver_models {
namespace {

// vsplit: an indexed draw of at most SEGMENT_SIZE (1024) indices runs as one segment; a
// longer one is cut into segments of 1023 indices (341 triangles). Each segment is shaded,
// tested and sent on its own.
constexpr size_t kSegmentIndices = 1024;
constexpr size_t kSplitTriangles = (kSegmentIndices - 1) / 3;

DrawVertex shade_vertex(const Vertex& v, const ViewportXform& vp, const DrawConfig& config,
                        const Case& c) {
  DrawVertex d;
  d.clip = v.clip;  // the vertex (and geometry) shader copies gl_Position unchanged
  d.clipmask = clip_mask(v.clip, c.clip_depth, !c.depth_clamp);
  d.distances = v.distances;
  // llvmpipe transforms every vertex; the C path only unclipped ones, but a clipped vertex's
  // window position is never read (the clipper replaces it), so computing it does no harm.
  d.window = config.path == VertexPath::llvm ? window_position_llvm(v.clip, vp, config.fma)
                                             : window_position_c(v.clip, vp);
  d.values = v.values;
  return d;
}

}  // namespace

std::vector<Interpolation> component_interpolation(const Case& c) {
  std::vector<Interpolation> out;
  for (const Varying& v : c.varyings)
    for (int i = 0; i < v.size; ++i)
      out.push_back(v.interpolation);
  return out;
}

void run_draw(const Case& c, const DrawConfig& config, TriangleSink& sink) {
  ClipContext ctx;
  ctx.viewport = viewport_xform(c);
  ctx.flatshade_first = c.provoking == ProvokingVertex::first;
  ctx.clip_depth = c.clip_depth;
  ctx.interpolation = component_interpolation(c);

  std::vector<DrawVertex> vertices;
  vertices.reserve(c.vertices.size());
  // The user planes the draw module clips by: the enabled ones, but every written one where
  // none is enabled (Direct3D's rule, which GL does not have: llvmpipe, softpipe and zink clip
  // by every written distance then, cases/clip_distance_none_enabled.json, bit for bit).
  const uint32_t written = c.distances.clip > 0 ? (1u << c.distances.clip) - 1u : 0u;
  const uint32_t ucp = c.distances.enabled & written ? c.distances.enabled & written : written;
  for (const Vertex& v : c.vertices) {
    vertices.push_back(shade_vertex(v, ctx.viewport, config, c));
    // draw_cliptest_tmp.h's (clipdist < 0 || NaN) for each of those planes.
    for (int i = 0; i < c.distances.clip; ++i)
      if ((ucp >> i & 1u) && !(v.distances[size_t(i)] >= 0.0f))
        vertices.back().clipmask |= 1u << (6 + i);
  }

  const size_t count = c.triangles.size();
  const size_t segment =
      count * 3 <= kSegmentIndices ? std::max<size_t>(count, 1) : kSplitTriangles;
  for (size_t first = 0; first < count; first += segment) {
    const size_t last = std::min(count, first + segment);
    // Any clipped vertex in the segment sends the whole segment through the pipeline
    // ("clipped" from the vertex shader / post-VS); otherwise it is emitted as is.
    // Cull distances send every triangle through the pipeline: its cull stage does them.
    // So does the offset stage where the driver uses it (DrawConfig::offset_stage).
    bool pipeline = c.distances.cull > 0 || (config.offset_stage && c.polygon_offset);
    for (size_t t = first; t < last; ++t)
      for (uint32_t i : c.triangles[t])
        pipeline = pipeline || vertices[i].clipmask != 0;

    for (size_t t = first; t < last; ++t) {
      const auto& idx = c.triangles[t];
      const TriangleRefs tri = {&vertices[idx[0]], &vertices[idx[1]], &vertices[idx[2]]};
      const int32_t primitive = int32_t(t);
      if (!pipeline) {
        sink.triangle(*tri[0], *tri[1], *tri[2], primitive);
        continue;
      }
      if (c.distances.cull > 0 && !cull_distances_pass(c, tri)) continue;
      // clip_tri: untouched when no vertex is outside, dropped when all are outside one
      // plane, clipped otherwise.
      const uint32_t any = tri[0]->clipmask | tri[1]->clipmask | tri[2]->clipmask;
      const uint32_t all = tri[0]->clipmask & tri[1]->clipmask & tri[2]->clipmask;
      std::deque<DrawVertex> storage;
      std::vector<TriangleRefs> pieces;
      if (any == 0)
        pieces.push_back(tri);
      else if (all == 0)
        clip_triangle(ctx, tri, any, storage, pieces);
      for (const TriangleRefs& piece : pieces) {
        // The cull stage runs in the pipeline whenever culling is on (validate_pipeline),
        // on top of the driver's own culling.
        if (c.cull != CullFace::none && !cull_stage_passes(c, piece)) continue;
        if (config.offset_stage && c.polygon_offset) {
          // After clip and cull, on copies of the piece's vertices (dup_vert).
          std::array<DrawVertex, 3> offset{*piece[0], *piece[1], *piece[2]};
          offset_stage(*c.polygon_offset, offset);
          sink.triangle(offset[0], offset[1], offset[2], primitive);
          continue;
        }
        sink.triangle(*piece[0], *piece[1], *piece[2], primitive);
      }
    }
  }
}

}  // namespace glrc::driver_models
