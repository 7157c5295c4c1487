#include "ref/setup.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace glrc::ref {

namespace {

// (x, y, w) columns of the homogeneous window-space vertex matrix.
struct H3 {
  mpq_class x, y, w;
};

// A vertex's column, by reference: the vertex's own rationals, not copies of them.
struct Column {
  const mpq_class &x, &y, &w;
};

H3 cross(const Column& u, const Column& v) {
  return {u.y * v.w - u.w * v.y, u.w * v.x - u.x * v.w, u.x * v.y - u.y * v.x};
}

// out = num / den rounded to an integer, ties to even, for den > 0 (out may be neither). The
// remainder in an integer kept per thread: no allocation once its limbs are there.
void round_half_even(mpz_class& out, const mpz_class& num, const mpz_class& den) {
  thread_local mpz_class r;
  mpz_fdiv_qr(out.get_mpz_t(), r.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
  r <<= 1;
  const int c = cmp(r, den);
  if (c > 0 || (c == 0 && mpz_odd_p(out.get_mpz_t()))) out += 1;
}

constexpr long kGuardBand = 1L << 40;  // in subpixel steps

// The snapped window position of a vertex with w_c > 0, or nothing outside the guard band.
// `xyw`: its x_h, y_h and w_c as Dyadic, when set_up had them so (else null).
std::optional<std::array<long, 2>> snap(const WindowVertex& v, const Dyadic* xyw, int bits) {
  std::array<long, 2> s{};
  const mpq_class* h[2] = {&v.x_h, &v.y_h};
  // Kept per thread, as set_up's: a fan's thousands of snaps allocate nothing once warm.
  thread_local mpz_class r, shifted;
  for (int k = 0; k < 2; ++k) {
    if (xyw) {
      // h·2^bits / w = (h.m / w.m)·2^shift: the power of two moved onto one side of the
      // integer quotient, whose rounding does not depend on a common factor (w.m > 0).
      const Dyadic &hd = xyw[k], &w = xyw[2];
      const long shift = hd.e - w.e + bits;
      if (shift >= 0) {
        mpz_mul_2exp(shifted.get_mpz_t(), hd.m.get_mpz_t(), mp_bitcnt_t(shift));
        round_half_even(r, shifted, w.m);
      } else {
        mpz_mul_2exp(shifted.get_mpz_t(), w.m.get_mpz_t(), mp_bitcnt_t(-shift));
        round_half_even(r, hd.m, shifted);
      }
    } else {
      const mpq_class q = *h[k] * mpq_class(mpz_class(1) << bits) / v.w_c;
      round_half_even(r, q.get_num(), q.get_den());
    }
    // |r| >= 2^40 compared in place: abs(r) would be a temporary integer.
    if (mpz_cmpabs_ui(r.get_mpz_t(), static_cast<unsigned long>(kGuardBand)) >= 0)
      return std::nullopt;
    s[k] = r.get_si();
  }
  return s;
}

bool culled(const Case& c, bool front_facing) {
  switch (c.cull) {
    case CullFace::none:
      return false;
    case CullFace::front:
      return front_facing;
    case CullFace::back:
      return !front_facing;
    case CullFace::front_and_back:
      return true;
  }
  return false;
}

}  // namespace

PixelBox viewport_box(const Case& c) {
  const PixelRect r = scissor_region(c);
  const Viewport& vp = c.viewport;
  // The pixels whose centres px + 1/2 lie in [x, x + width], either side included (a centre on
  // a side is the clipped polygon's edge's, which the coverage decides); whole numbers: x to
  // x + width - 1. In doubles: exact for floats within ±2^24.
  const auto first = [](double lo) { return int(std::ceil(lo - 0.5)); };
  const auto last = [](double hi) { return int(std::floor(hi - 0.5)); };
  PixelBox b;
  b.x0 = std::max(first(vp.x), r.x0);
  b.y0 = std::max(first(vp.y), r.y0);
  b.x1 = std::min(last(double(vp.x) + vp.width), r.x1);
  b.y1 = std::min(last(double(vp.y) + vp.height), r.y1);
  return b;
}

PixelBox viewport_reach(const Case& c) {
  const Viewport& vp = c.viewport;
  const double step = viewport_step(vp);
  if (step == 0) return viewport_box(c);
  // A side moves by less than two steps (x + Δx + w + Δw): centres within that of the viewport.
  const PixelRect r = scissor_region(c);
  PixelBox b;
  b.x0 = std::max(int(std::ceil(vp.x - 2 * step - 0.5)), r.x0);
  b.y0 = std::max(int(std::ceil(vp.y - 2 * step - 0.5)), r.y0);
  b.x1 = std::min(int(std::floor(double(vp.x) + vp.width + 2 * step - 0.5)), r.x1);
  b.y1 = std::min(int(std::floor(double(vp.y) + vp.height + 2 * step - 0.5)), r.y1);
  return b;
}

namespace {

// Everything setup_triangle does once the window vertices t.v are known.
void set_up(const Case& c, const Model& m, TriangleSetup& t) {
  // Homogeneous edge functions: E_i(p) = (col_j × col_k) · p with p = (x_w, y_w, 1) and
  // x_w = px + 1/2; det = col_0 · (col_1 × col_2) is 2·area·w_0·w_1·w_2 when all w_c > 0, and
  // its sign is the facing in every case (the Jacobian of the projective map has the sign of
  // det wherever w > 0).
  //
  // In dyadic arithmetic (exact.hpp) when every coordinate is dyadic, which those of float32
  // clip coordinates and an integer viewport always are: the same rationals as mpq_class
  // arithmetic gives, without its gcd after every product and sum.
  // The dyadic numbers below are kept per thread, their limbs reused from triangle to
  // triangle: made and freed here, their allocations were a third of setting up a fan.
  struct Scratch {
    Dyadic xyw[3][3], gd[3][3], centre[3], det;
  };
  thread_local Scratch scratch;
  Dyadic(&xyw)[3][3] = scratch.xyw;  // x_h, y_h, w_c of each vertex
  bool dyadic = true;
  for (int i = 0; i < 3 && dyadic; ++i)
    dyadic = Dyadic::of(t.v[i].x_h, xyw[i][0]) && Dyadic::of(t.v[i].y_h, xyw[i][1]) &&
             Dyadic::of(t.v[i].w_c, xyw[i][2]);
  // The edges' coefficients: gd (x, y) and centre (E_i's value at pixel (0, 0), whose centre
  // is (1/2, 1/2)) when dyadic, else rationals' g and centre_term (made only then: a rational
  // is an allocation even at 0).
  Dyadic(&gd)[3][3] = scratch.gd;
  Dyadic(&centre)[3] = scratch.centre;
  struct Rationals {
    H3 g[3];
    mpq_class centre_term[3];
  };
  std::optional<Rationals> rationals;
  int det_sign = 0;
  if (dyadic) {
    for (int i = 0; i < 3; ++i) {
      const Dyadic(&u)[3] = xyw[(i + 1) % 3];
      const Dyadic(&v)[3] = xyw[(i + 2) % 3];
      cross_term(gd[i][0], u[1], v[2], u[2], v[1]);
      cross_term(gd[i][1], u[2], v[0], u[0], v[2]);
      cross_term(gd[i][2], u[0], v[1], u[1], v[0]);
    }
    Dyadic& det = scratch.det;
    const Dyadic* gs[3] = {&gd[0][0], &gd[0][1], &gd[0][2]};
    const Dyadic* cs[3] = {&xyw[0][0], &xyw[0][1], &xyw[0][2]};
    sum_of_products(det, gs, cs, 3);
    det_sign = det.sign();
    const Dyadic half{1, -1}, one{1, 0};
    const Dyadic* weights[3] = {&half, &half, &one};
    for (int i = 0; i < 3; ++i) {
      const Dyadic* terms[3] = {&gd[i][0], &gd[i][1], &gd[i][2]};  // w only in the centre's
      sum_of_products(centre[i], terms, weights, 3);
    }
  } else {
    const Column col[3] = {{t.v[0].x_h, t.v[0].y_h, t.v[0].w_c},
                           {t.v[1].x_h, t.v[1].y_h, t.v[1].w_c},
                           {t.v[2].x_h, t.v[2].y_h, t.v[2].w_c}};
    auto& [g, centre_term] = rationals.emplace();
    for (int i = 0; i < 3; ++i)
      g[i] = cross(col[(i + 1) % 3], col[(i + 2) % 3]);
    det_sign = sgn(mpq_class(g[0].x * col[0].x + g[0].y * col[0].y + g[0].w * col[0].w));
    for (int i = 0; i < 3; ++i)
      centre_term[i] = (g[i].x + g[i].y) / 2 + g[i].w;
  }

  const bool all_w_positive =
      std::all_of(t.v.begin(), t.v.end(), [](const WindowVertex& v) { return sgn(v.w_c) > 0; });
  std::optional<std::array<long, 2>> s[3];
  if (m.subpixel_bits > 0 && all_w_positive) {
    for (int i = 0; i < 3; ++i)
      s[i] = snap(t.v[i], dyadic ? xyw[i] : nullptr, m.subpixel_bits);
    if (s[0] && s[1] && s[2]) t.path = CoveragePath::snapped;
  }

  int facing_sign = det_sign;
  if (t.path == CoveragePath::snapped) {
    const auto& s0 = *s[0];
    const auto& s1 = *s[1];
    const auto& s2 = *s[2];
    const int128 area2 =
        int128(s1[0] - s0[0]) * (s2[1] - s0[1]) - int128(s2[0] - s0[0]) * (s1[1] - s0[1]);
    facing_sign = area2 > 0 ? 1 : area2 < 0 ? -1 : 0;
    const int bits = m.subpixel_bits;
    t.snapped = {s0, s1, s2};
    for (int i = 0; i < 3; ++i) {
      const auto& sj = *s[(i + 1) % 3];
      const auto& sk = *s[(i + 2) % 3];
      const int128 dy = int128(sj[1]) - sk[1], dx = int128(sk[0]) - sj[0];
      TriangleSetup::IntEdge e;
      e.a = dy << bits;
      e.b = dx << bits;
      e.c = int128(sj[0]) * sk[1] - int128(sj[1]) * sk[0] + ((dy + dx) << (bits - 1));
      if (facing_sign < 0) e.a = -e.a, e.b = -e.b, e.c = -e.c;
      t.snapped_edges[i] = e;
    }
  }
  if (det_sign == 0) return;  // zero area: nothing is drawn, by any implementation
  t.has_edges = true;
  for (int i = 0; i < 3; ++i) {
    LinearForm& e = t.homogeneous_edges[i];
    if (dyadic) {  // into the form's own rationals: no temporaries
      gd[i][0].to(e.a), gd[i][1].to(e.b), centre[i].to(e.c);
    } else {
      e.c = std::move(rationals->centre_term[i]);
      e.a = std::move(rationals->g[i].x), e.b = std::move(rationals->g[i].y);
    }
    if (det_sign < 0)
      for (mpq_class* q : {&e.a, &e.b, &e.c})
        mpq_neg(q->get_mpq_t(), q->get_mpq_t());
  }

  // Pixels that can be covered: pixel centres inside the (snapped or exact) window-space
  // bounding box; with a vertex at w_c <= 0 the visible part is unbounded: the whole viewport.
  t.box = viewport_box(c);
  // Window coordinates may pass the int range (clip x of 1e8 is 3.2e9 pixels): clamp before
  // converting, the viewport clips the box anyway.
  auto clamp_int = [](double d) { return int(std::clamp(d, -1e9, 1e9)); };
  if (t.path == CoveragePath::snapped) {
    const double step = std::ldexp(1.0, -m.subpixel_bits);
    long lo[2] = {s[0]->at(0), s[0]->at(1)}, hi[2] = {lo[0], lo[1]};
    for (int i = 1; i < 3; ++i)
      for (int k = 0; k < 2; ++k)
        lo[k] = std::min(lo[k], s[i]->at(k)), hi[k] = std::max(hi[k], s[i]->at(k));
    // Exact in double: |s| < 2^40, and the scaling is a power of two.
    t.box.x0 = std::max(t.box.x0, clamp_int(std::ceil(double(lo[0]) * step - 0.5)));
    t.box.x1 = std::min(t.box.x1, clamp_int(std::floor(double(hi[0]) * step - 0.5)));
    t.box.y0 = std::max(t.box.y0, clamp_int(std::ceil(double(lo[1]) * step - 0.5)));
    t.box.y1 = std::min(t.box.y1, clamp_int(std::floor(double(hi[1]) * step - 0.5)));
  } else if (all_w_positive) {
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (const auto& v : t.v) {
      const double w[2] = {mpq_class(v.x_h / v.w_c).get_d(), mpq_class(v.y_h / v.w_c).get_d()};
      for (int k = 0; k < 2; ++k)
        lo[k] = std::min(lo[k], w[k]), hi[k] = std::max(hi[k], w[k]);
    }
    // Only bounds the loop, coverage itself is exact: a one-pixel margin absorbs the rounding.
    t.box.x0 = std::max(t.box.x0, clamp_int(std::floor(lo[0] - 0.5) - 1));
    t.box.x1 = std::min(t.box.x1, clamp_int(std::ceil(hi[0] - 0.5) + 1));
    t.box.y0 = std::max(t.box.y0, clamp_int(std::floor(lo[1] - 0.5) - 1));
    t.box.y1 = std::min(t.box.y1, clamp_int(std::ceil(hi[1] - 0.5) + 1));
  }

  if (facing_sign == 0) return;  // zero snapped area: this model draws nothing
  t.front_facing = ((facing_sign > 0) != facing_reversed(c)) == (c.front_face == FrontFace::ccw);
  if (t.discarded || culled(c, t.front_facing)) return;
  t.drawn = true;
}

}  // namespace

TriangleSetup setup_triangle(const Case& c, const Model& m, int primitive) {
  return setup_triangle(c, m, primitive, {});
}

TriangleSetup setup_triangle(const Case& c, const Model& m, int primitive,
                             const std::vector<WindowCorners::Pointer>& window) {
  TriangleSetup t;
  t.primitive = primitive;
  t.index = c.triangles[size_t(primitive)];
  t.clip_depth = c.clip_depth;
  t.depth_clamp = c.depth_clamp;
  t.discarded = c.distances.cull > 0 && culled_by_distance(c, t.index);
  std::array<WindowCorners::Pointer, 3> corners;
  for (size_t i = 0; i < 3; ++i) {
    const uint32_t k = t.index[i];
    corners[i] = k < window.size() && window[k]
                     ? window[k]
                     : std::make_shared<const WindowVertex>(to_window(c.vertices[k], c));
  }
  t.v = WindowCorners(std::move(corners));
  set_up(c, m, t);
  return t;
}

namespace {

// Triangles primitive(0 .. count-1) of c set up, in that order: each vertex they use transformed
// to the window once, shared by its triangles (WindowCorners), then each triangle set up in its
// place: a TriangleSetup default-constructed first costs its rationals' allocations.
template <class Primitive>
std::vector<std::optional<TriangleSetup>> set_up_each(const Case& c, const Model& m, int count,
                                                      Primitive primitive, ThreadPool& pool) {
  std::vector<uint8_t> used(c.vertices.size(), 0);
  for (int k = 0; k < count; ++k)
    for (uint32_t i : c.triangles[size_t(primitive(k))])
      used[i] = 1;
  std::vector<WindowCorners::Pointer> window(c.vertices.size());
  pool.parallel_for(int(c.vertices.size()), [&](int i) {
    if (used[size_t(i)])
      window[size_t(i)] = std::make_shared<const WindowVertex>(to_window(c.vertices[size_t(i)], c));
  });
  std::vector<std::optional<TriangleSetup>> setups(static_cast<size_t>(count));
  pool.parallel_for(count, [&](int k) {
    // Constructed from the returned value directly (no default construction, no move).
    struct SetUp {
      const Case& c;
      const Model& m;
      int p;
      const std::vector<WindowCorners::Pointer>& window;
      operator TriangleSetup() const { return setup_triangle(c, m, p, window); }
    };
    setups[size_t(k)].emplace(SetUp{c, m, primitive(k), window});
  });
  return setups;
}

}  // namespace

std::vector<std::optional<TriangleSetup>> setup_triangles(const Case& c, const Model& m,
                                                          ThreadPool& pool) {
  return set_up_each(
      c, m, int(c.triangles.size()), [](int p) { return p; }, pool);
}

std::vector<std::optional<TriangleSetup>> setup_triangles(const Case& c, const Model& m,
                                                          const std::vector<int>& primitives,
                                                          ThreadPool& pool) {
  return set_up_each(
      c, m, int(primitives.size()), [&](int k) { return primitives[size_t(k)]; }, pool);
}

}  // namespace glrc::ref
