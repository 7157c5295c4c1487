// Port of Mesa 22.3.6 src/gallium/drivers/softpipe/sp_setup.c: calc_det,
// setup_sort_vertices, tri_linear_coeff, tri_persp_coeff, const_coeff, setup_tri_edges,
// subtriangle (with the cliprect of a framebuffer without scissor).
#include "driver_models/softpipe_setup.hpp"

#include <cmath>

#include "driver_models/float_ops.hpp"

namespace glrc::driver_models {
namespace {

constexpr float kPixelOffset = 0.5f;  // half_pixel_center

struct Edge {
  float dx = 0, dy = 0, dxdy = 0, sx = 0, sy = 0;
  int lines = 0;
};

struct Setup {
  const DrawVertex *vmin = nullptr, *vmid = nullptr, *vmax = nullptr;
  Edge ebot, etop, emaj;
  float oneoverarea = 0;
};

// setup_sort_vertices' bottom-to-top order, ties exactly as Mesa breaks them.
void sort_vertices(Setup& s, const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2) {
  const float y0 = v0.window[1], y1 = v1.window[1], y2 = v2.window[1];
  if (y0 <= y1) {
    if (y1 <= y2) {
      s.vmin = &v0, s.vmid = &v1, s.vmax = &v2;
    } else if (y2 <= y0) {
      s.vmin = &v2, s.vmid = &v0, s.vmax = &v1;
    } else {
      s.vmin = &v0, s.vmid = &v2, s.vmax = &v1;
    }
  } else {
    if (y0 <= y2) {
      s.vmin = &v1, s.vmid = &v0, s.vmax = &v2;
    } else if (y2 <= y1) {
      s.vmin = &v2, s.vmid = &v1, s.vmax = &v0;
    } else {
      s.vmin = &v1, s.vmid = &v2, s.vmax = &v0;
    }
  }
}

Plane tri_linear_coeff(const Setup& s, float a0, float a1, float a2) {
  const float botda = a1 - a0;
  const float majda = a2 - a0;
  const float a = s.ebot.dy * majda - botda * s.emaj.dy;
  const float b = s.emaj.dx * botda - majda * s.ebot.dx;
  Plane p;
  p.dadx = a * s.oneoverarea;
  p.dady = b * s.oneoverarea;
  p.a0 = a0 - (p.dadx * (s.vmin->window[0] - kPixelOffset) +
               p.dady * (s.vmin->window[1] - kPixelOffset));
  return p;
}

// subtriangle: rows sy .. sy + lines - 1 between two edges, left-inclusive, right-exclusive,
// each end truncated by (int), cut to the cliprect (the framebuffer, or the scissor box within
// it: `clip`, bounds inclusive, which Mesa holds as exclusive maxima).
void subtriangle(Edge& eleft, Edge& eright, int lines, const PixelRect& clip,
                 std::vector<Span>& spans) {
  const int minx = clip.x0, miny = clip.y0, maxx = clip.x1 + 1, maxy = clip.y1 + 1;
  const int sy = cvt_trunc_i32(eleft.sy);
  int start_y = sy < miny ? miny : sy;
  int finish_y = sy + lines;
  if (finish_y > maxy) finish_y = maxy;
  start_y -= sy;
  finish_y -= sy;
  for (int y = start_y; y < finish_y; ++y) {
    int left = cvt_trunc_i32(eleft.sx + float(y) * eleft.dxdy);
    int right = cvt_trunc_i32(eright.sx + float(y) * eright.dxdy);
    if (left < minx) left = minx;
    if (right > maxx) right = maxx;
    if (left < right) spans.push_back(Span{sy + y, left, right});
  }
  // Saved so that emaj can be restarted for the upper half: a float accumulation.
  eleft.sx += float(lines) * eleft.dxdy;
  eright.sx += float(lines) * eright.dxdy;
  eleft.sy += float(lines);
  eright.sy += float(lines);
}

}  // namespace

bool softpipe_setup_triangle(const Case& c, const std::vector<Interpolation>& interpolation,
                             const DrawVertex& v0, const DrawVertex& v1, const DrawVertex& v2,
                             SoftpipeTriangle& out) {
  // calc_det: e = v0 - v2, f = v1 - v2.
  const float ex = v0.window[0] - v2.window[0], ey = v0.window[1] - v2.window[1];
  const float fx = v1.window[0] - v2.window[0], fy = v1.window[1] - v2.window[1];
  const float det = ex * fy - ey * fx;

  Setup s;
  sort_vertices(s, v0, v1, v2);
  const auto& pmin = s.vmin->window;
  const auto& pmid = s.vmid->window;
  const auto& pmax = s.vmax->window;
  s.ebot.dx = pmid[0] - pmin[0];
  s.ebot.dy = pmid[1] - pmin[1];
  s.emaj.dx = pmax[0] - pmin[0];
  s.emaj.dy = pmax[1] - pmin[1];
  s.etop.dx = pmax[0] - pmid[0];
  s.etop.dy = pmax[1] - pmid[1];
  const float area = s.emaj.dx * s.ebot.dy - s.ebot.dx * s.emaj.dy;
  s.oneoverarea = 1.0f / area;
  if (is_inf_or_nan(s.oneoverarea)) return false;

  // facing = (det < 0) ^ front_ccw, with front_ccw flipped for a y-up FBO: back facing when
  // the triangle is counter-clockwise in GL's sense and the front face is CW, or vice versa;
  // flipped once more under GL_UPPER_LEFT (st_atom_rasterizer.c).
  const bool front_ccw = (c.front_face == FrontFace::cw) != facing_reversed(c);
  const bool back = (det < 0) != front_ccw;
  const bool cull_front = c.cull == CullFace::front || c.cull == CullFace::front_and_back;
  const bool cull_back = c.cull == CullFace::back || c.cull == CullFace::front_and_back;
  if (back ? cull_back : cull_front) return false;
  out.front_facing = !back;

  // setup_tri_coefficients
  out.z = tri_linear_coeff(s, pmin[2], pmid[2], pmax[2]);
  out.w = tri_linear_coeff(s, pmin[3], pmid[3], pmax[3]);
  const DrawVertex& provoking = c.provoking == ProvokingVertex::first ? v0 : v2;
  out.values.resize(interpolation.size());
  for (size_t k = 0; k < interpolation.size(); ++k) {
    const float a0 = s.vmin->values[k], a1 = s.vmid->values[k], a2 = s.vmax->values[k];
    switch (interpolation[k]) {
      case Interpolation::flat:
        out.values[k] = Plane{provoking.values[k], 0, 0};
        break;
      case Interpolation::noperspective:
        out.values[k] = tri_linear_coeff(s, a0, a1, a2);
        break;
      case Interpolation::smooth:  // tri_persp_coeff: premultiplied by 1/w
        out.values[k] = tri_linear_coeff(s, a0 * pmin[3], a1 * pmid[3], a2 * pmax[3]);
        break;
    }
  }

  // setup_tri_edges
  const float vmin_x = pmin[0] + kPixelOffset;
  const float vmid_x = pmid[0] + kPixelOffset;
  const float vmin_y = pmin[1] - kPixelOffset;
  const float vmid_y = pmid[1] - kPixelOffset;
  const float vmax_y = pmax[1] - kPixelOffset;
  auto edge = [](Edge& e, float start_x, float start_y, float end_y) {
    e.sy = std::ceil(start_y);
    e.lines = cvt_trunc_i32(std::ceil(end_y - e.sy));
    e.dxdy = e.dy != 0.0f ? e.dx / e.dy : 0.0f;
    e.sx = start_x + (e.sy - start_y) * e.dxdy;
  };
  edge(s.emaj, vmin_x, vmin_y, vmax_y);
  edge(s.etop, vmid_x, vmid_y, vmax_y);
  edge(s.ebot, vmin_x, vmin_y, vmid_y);

  const PixelRect clip = scissor_region(c);
  if (clip.empty()) return true;
  if (s.oneoverarea < 0.0f) {  // emaj on the left
    subtriangle(s.emaj, s.ebot, s.ebot.lines, clip, out.spans);
    subtriangle(s.emaj, s.etop, s.etop.lines, clip, out.spans);
  } else {
    subtriangle(s.ebot, s.emaj, s.ebot.lines, clip, out.spans);
    subtriangle(s.etop, s.emaj, s.etop.lines, clip, out.spans);
  }
  return true;
}

}  // namespace glrc::driver_models
