// Port of Mesa 22.3.6 src/gallium/auxiliary/draw/draw_pipe_clip.c (do_clip_tri, interp,
// emit_poly) and draw_pipe_cull.c (cull_tri) for triangles.
#include "driver_models/mesa_clipper.hpp"

#include "driver_models/float_ops.hpp"

namespace glrc::driver_models {
namespace {

// draw_context.c: the view-volume planes as dot4 coefficients ("mesa's a bit wonky": plane 4
// is z >= -w, plane 5 is z <= w).
constexpr float kPlanes[6][4] = {{-1, 0, 0, 1}, {1, 0, 0, 1}, {0, -1, 0, 1},
                                 {0, 1, 0, 1},  {0, 0, 1, 1}, {0, 0, -1, 1}};
// Under clip_halfz (GL_ZERO_TO_ONE) the near plane is z >= 0. The draw_context.c read here
// keeps (0, 0, 1, 1) in its table, yet llvmpipe and softpipe cut at z_c = 0: matched bit for bit
// by this plane (cases/clip_control_zero_to_one_near.json under --model and --tolerance exact).
constexpr float kHalfZNearPlane[4] = {0, 0, 1, 0};

float dot4(const std::array<float, 4>& a, const float* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

// LINTERP(T, OUT, IN) = OUT + T * (IN - OUT)
float linterp(float t, float out, float in) {
  return out + t * (in - out);
}

// interp(): a vertex between `out` and `in` at clip-space parameter t.
DrawVertex interp(const ClipContext& ctx, float t, const DrawVertex& out, const DrawVertex& in) {
  DrawVertex dst;
  for (int i = 0; i < 4; ++i)
    dst.clip[i] = linterp(t, out.clip[i], in.clip[i]);
  dst.window = window_position_c(dst.clip, ctx.viewport);
  dst.values.assign(out.values.size(), 0.0f);
  // The clip and cull distance outputs: perspective attributes to the clipper (find_interp's
  // default for an output no fragment shader input names).
  dst.distances.resize(out.distances.size());
  for (size_t k = 0; k < dst.distances.size(); ++k)
    dst.distances[k] = linterp(t, out.distances[k], in.distances[k]);

  // noperspective: t recomputed from NDC x (or y when x is equal). When both endpoints lie on
  // an x = ±w plane with different w, in_coord == out_coord == ±1 and this is 0/0: NaN. Mesa's
  // bug, modelled as is.
  float t_nopersp = t;
  for (int k = 0; k < 2; ++k) {
    if (in.clip[k] != out.clip[k]) {
      const float in_coord = in.clip[k] / in.clip[3];
      const float out_coord = out.clip[k] / out.clip[3];
      const float dst_coord = dst.clip[k] / dst.clip[3];
      t_nopersp = (dst_coord - out_coord) / (in_coord - out_coord);
      break;
    }
  }
  for (size_t k = 0; k < dst.values.size(); ++k) {
    switch (ctx.interpolation[k]) {
      case Interpolation::smooth:
        dst.values[k] = linterp(t, out.values[k], in.values[k]);
        break;
      case Interpolation::noperspective:
        dst.values[k] = linterp(t_nopersp, out.values[k], in.values[k]);
        break;
      case Interpolation::flat:
        // Not interpolated: only the provoking vertex's copy is ever read (copy_flat).
        dst.values[k] = out.values[k];
        break;
    }
  }
  return dst;
}

}  // namespace

void clip_triangle(const ClipContext& ctx, const TriangleRefs& tri, uint32_t clipmask,
                   std::deque<DrawVertex>& storage, std::vector<TriangleRefs>& out) {
  std::vector<const DrawVertex*> inlist(tri.begin(), tri.end()), outlist;
  size_t n = 3;
  while (clipmask && n >= 3) {
    const int plane = __builtin_ctz(clipmask);
    clipmask &= ~(1u << plane);
    // getclipdist: a view-volume plane's dot4, or a user plane's gl_ClipDistance output.
    const float* coefficients = plane >= 6 ? nullptr
                                : plane == 4 && ctx.clip_depth == ClipDepth::zero_to_one
                                    ? kHalfZNearPlane
                                    : kPlanes[plane];
    auto clip_distance = [&](const DrawVertex* v) {
      return coefficients ? dot4(v->clip, coefficients) : v->distances[size_t(plane - 6)];
    };
    const DrawVertex* vert_prev = inlist[0];
    float dp_prev = clip_distance(vert_prev);
    if (is_inf_or_nan(dp_prev)) return;  // discard NaN
    inlist.resize(n);
    inlist.push_back(inlist[0]);  // prevent rotation of vertices
    outlist.clear();
    for (size_t i = 1; i <= n; ++i) {
      const DrawVertex* vert = inlist[i];
      const float dp = clip_distance(vert);
      if (is_inf_or_nan(dp)) return;
      bool different_sign;
      if (dp_prev >= 0.0f) {
        outlist.push_back(vert_prev);
        different_sign = dp < 0.0f;
      } else {
        different_sign = !(dp < 0.0f);
      }
      if (different_sign) {
        // Interpolate from the endpoint outside towards the one inside, so that the same
        // edge clipped from either side gives the same vertex.
        const float denom = dp - dp_prev;
        if (dp < 0.0f) {
          if (-dp < dp_prev)
            storage.push_back(interp(ctx, dp / denom, *vert, *vert_prev));
          else
            storage.push_back(interp(ctx, -dp_prev / denom, *vert_prev, *vert));
        } else {
          if (-dp_prev < dp)
            storage.push_back(interp(ctx, -dp_prev / denom, *vert_prev, *vert));
          else
            storage.push_back(interp(ctx, dp / denom, *vert, *vert_prev));
        }
        outlist.push_back(&storage.back());
      }
      vert_prev = vert;
      dp_prev = dp;
    }
    std::swap(inlist, outlist);
    n = inlist.size();
  }
  if (n < 3) return;
  inlist.resize(n);

  // copy_flat: the polygon's vertex 0 becomes the provoking vertex of every fan triangle, so
  // it takes the original provoking vertex's flat values.
  const DrawVertex* provoking = ctx.flatshade_first ? tri[0] : tri[2];
  if (inlist[0] != provoking) {
    storage.push_back(*inlist[0]);
    for (size_t k = 0; k < ctx.interpolation.size(); ++k)
      if (ctx.interpolation[k] == Interpolation::flat)
        storage.back().values[k] = provoking->values[k];
    inlist[0] = &storage.back();
  }
  // emit_poly: the provoking vertex (inlist[0]) goes first or last.
  for (size_t i = 2; i < n; ++i) {
    if (ctx.flatshade_first)
      out.push_back({inlist[0], inlist[i - 1], inlist[i]});
    else
      out.push_back({inlist[i - 1], inlist[i], inlist[0]});
  }
}

bool cull_distances_pass(const Case& c, const TriangleRefs& tri) {
  for (int k = c.distances.clip; k < c.distances.clip + c.distances.cull; ++k) {
    auto out = [&](const DrawVertex* v) {
      const float d = v->distances[size_t(k)];
      return d < 0.0f || is_inf_or_nan(d);
    };
    if (out(tri[0]) && out(tri[1]) && out(tri[2])) return false;
  }
  return true;
}

bool cull_stage_passes(const Case& c, const TriangleRefs& tri) {
  const auto& v0 = tri[0]->window;
  const auto& v1 = tri[1]->window;
  const auto& v2 = tri[2]->window;
  const float ex = v0[0] - v2[0], ey = v0[1] - v2[1];
  const float fx = v1[0] - v2[0], fy = v1[1] - v2[1];
  const float det = ex * fy - ey * fx;
  const bool cull_front = c.cull == CullFace::front || c.cull == CullFace::front_and_back;
  const bool cull_back = c.cull == CullFace::back || c.cull == CullFace::front_and_back;
  if (det != 0) {
    // Window y is up in a user FBO, so det > 0 is counter-clockwise as GL sees it (Mesa's
    // "det < 0 is ccw" and the state tracker's flipped front_ccw cancel out).
    // NaN takes the det > 0 branch, as Mesa's (det < 0) test does.
    const bool ccw = !(det < 0);
    // GL_UPPER_LEFT flips front_ccw once more (st_atom_rasterizer.c).
    const bool front = (ccw != facing_reversed(c)) == (c.front_face == FrontFace::ccw);
    return !(front ? cull_front : cull_back);
  }
  return !cull_back;
}

}  // namespace glrc::driver_models
