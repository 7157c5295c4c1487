#include "ref/allowance.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace glrc::ref {

namespace {

// Both forms scaled by one power of two so that their largest coefficient is near 1: the ratio
// is unchanged and the double copies can neither overflow nor underflow.
void normalized_doubles(const LinearForm& n, const LinearForm& d, double out[6]) {
  const mpq_class* q[6] = {&n.a, &n.b, &n.c, &d.a, &d.b, &d.c};
  long e = std::numeric_limits<long>::min();
  for (const mpq_class* x : q)
    if (sgn(*x) != 0)
      e = std::max(e, long(mpz_sizeinbase(x->get_num_mpz_t(), 2)) -
                          long(mpz_sizeinbase(x->get_den_mpz_t(), 2)));
  if (e == std::numeric_limits<long>::min()) e = 0;
  // Scaled in a rational kept per thread: a copy per coefficient was six allocations per
  // channel of every triangle.
  thread_local mpq_class scaled;
  for (int i = 0; i < 6; ++i) {
    if (e > 0)
      mpq_div_2exp(scaled.get_mpq_t(), q[i]->get_mpq_t(), mp_bitcnt_t(e));
    else
      mpq_mul_2exp(scaled.get_mpq_t(), q[i]->get_mpq_t(), mp_bitcnt_t(-e));
    out[i] = scaled.get_d();
  }
}

}  // namespace

double value_freedom(const Case& c, const TriangleSetup& t, double scale, int generations) {
  double w = 1, m = 1 + std::max(c.fb_width, c.fb_height);
  for (uint32_t index : t.index)
    w = std::max(w, std::fabs(double(c.vertices[index].clip[3])));
  m = std::max({m, 1 + std::fabs(double(c.viewport.x)) + c.viewport.width,
                1 + std::fabs(double(c.viewport.y)) + c.viewport.height});
  return (kValueRoundings + kClippedValueRoundings * generations) * kFloatUnitRoundoff * scale +
         kDenormalFlushes * 0x1p-126 * m * w;
}

FanTriangles::FanTriangles(const WindowPolygon& polygon, double margin, double rounding) {
  if (!(margin >= 0)) margin = 0;
  if (!(rounding >= 0)) rounding = 0;
  for (const auto& a : polygon)
    if (!std::isfinite(a[0]) || !std::isfinite(a[1])) return;
  const size_t n = polygon.size();
  // The polygon's edges (it is convex, its vertices in order), skipping a vertex given twice.
  double polygon_area2 = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto &a = polygon[i], &b = polygon[(i + 1) % n];
    polygon_area2 += a[0] * b[1] - b[0] * a[1];
  }
  const double sense = polygon_area2 > 0 ? 1 : -1;
  if (n >= 3 && std::fabs(polygon_area2) > 0)
    for (size_t i = 0; i < n; ++i) {
      const auto &a = polygon[i], &b = polygon[(i + 1) % n];
      const double ea = -(b[1] - a[1]) * sense, eb = (b[0] - a[0]) * sense;
      const double length = std::hypot(ea, eb);
      if (!(length > 0)) continue;
      hull_.push_back({ea / length, eb / length, -(ea * a[0] + eb * a[1]) / length});
    }
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        const std::array<double, 2> q[3] = {polygon[i], polygon[j], polygon[k]};
        const double area2 =
            (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[2][0] - q[0][0]) * (q[1][1] - q[0][1]);
        // Three vertices on one line (on one clip plane): nothing to draw.
        if (!(std::fabs(area2) > 0)) continue;
        Triangle t{};
        t.box[0] = std::min({q[0][0], q[1][0], q[2][0]}) - margin;
        t.box[1] = std::min({q[0][1], q[1][1], q[2][1]}) - margin;
        t.box[2] = std::max({q[0][0], q[1][0], q[2][0]}) + margin;
        t.box[3] = std::max({q[0][1], q[1][1], q[2][1]}) + margin;
        const double orientation = area2 > 0 ? 1 : -1;
        for (size_t e = 0; e < 3; ++e) {
          const auto& p0 = q[e];
          const auto& p1 = q[(e + 1) % 3];
          // Left of p0 -> p1 for a counter-clockwise triangle: inside.
          double ea = -(p1[1] - p0[1]) * orientation, eb = (p1[0] - p0[0]) * orientation;
          const double length = std::hypot(ea, eb);
          ea /= length, eb /= length;
          t.edge[e][0] = ea, t.edge[e][1] = eb, t.edge[e][2] = margin - (ea * p0[0] + eb * p0[1]);
          // G from the vertex q_e as the anchor (allowance.hpp).
          const auto& p2 = q[(e + 2) % 3];
          const double e1x = p1[0] - p0[0], e1y = p1[1] - p0[1];
          const double e2x = p2[0] - p0[0], e2y = p2[1] - p0[1];
          const double kappa = std::fabs(e1x * e2y) + std::fabs(e2x * e1y);
          const double same = 2 * std::max(std::fabs(e1x * e2x), std::fabs(e1y * e2y));
          t.condition = std::max(t.condition, (2 * kappa + same) / std::fabs(area2));
          t.q[e][0] = p0[0], t.q[e][1] = p0[1];
        }
        // Each vertex moved by up to ε in x and in y changes 2A by at most ε·Σ_j (|E_j.x| +
        // |E_j.y|) + 8ε² (E_j the edge opposite vertex j); 2^-40 more for this arithmetic.
        double edges = 0;
        for (size_t e = 0; e < 3; ++e)
          edges += std::fabs(q[(e + 1) % 3][0] - q[e][0]) + std::fabs(q[(e + 1) % 3][1] - q[e][1]);
        const double change = (rounding * edges + 8 * rounding * rounding) * (1 + 0x1p-40);
        t.area_below = std::fabs(area2) * (1 - 0x1p-40) - change;
        t.rounding = rounding;
        triangles_.push_back(t);
      }
}

double FanTriangles::condition(double x, double y) const {
  double g = 0;
  for (const Triangle& t : triangles_) {
    if (t.condition <= g) continue;
    if (x < t.box[0] || x > t.box[2] || y < t.box[1] || y > t.box[3]) continue;
    bool inside = true;
    for (const auto& e : t.edge)
      inside = inside && e[0] * x + e[1] * y + e[2] >= 0;
    if (inside) g = t.condition;
  }
  return g;
}

GLRC_BLOCK_FORM void FanTriangles::condition(const double* x, const double* y, double* out) const {
  // condition()'s steps lane by lane, its skips and tests turned into one choice per triangle.
  constexpr int n = kRowBlock;
  double g[n] = {};
  for (const Triangle& t : triangles_)
    for (int j = 0; j < n; ++j) {
      const bool skipped = t.condition <= g[j];
      const bool outside_box =
          (x[j] < t.box[0]) | (x[j] > t.box[2]) | (y[j] < t.box[1]) | (y[j] > t.box[3]);
      bool inside = true;
      for (const auto& e : t.edge)
        inside = inside & (e[0] * x[j] + e[1] * y[j] + e[2] >= 0);
      g[j] = (!skipped & !outside_box & inside) ? t.condition : g[j];
    }
  std::copy(g, g + n, out);
}

std::array<double, 2> FanTriangles::condition_range(double x0, double x1, double y) const {
  double lo = 0, hi = 0;
  for (const Triangle& t : triangles_) {
    if (x1 < t.box[0] || x0 > t.box[2] || y < t.box[1] || y > t.box[3]) continue;
    hi = std::max(hi, t.condition);
    if (t.condition <= lo || x0 < t.box[0] || x1 > t.box[2]) continue;
    // Inside at both ends by more than the edge tests' rounding (two roundings of terms of
    // the magnitudes below; 2^-48 of them taken): inside as computed at every point between.
    bool inside = true;
    for (const auto& e : t.edge) {
      const double s = 0x1p-48 * (std::fabs(e[0]) * std::max(std::fabs(x0), std::fabs(x1)) +
                                  std::fabs(e[1] * y) + std::fabs(e[2]));
      inside = inside && e[0] * x0 + e[1] * y + e[2] >= s && e[0] * x1 + e[1] * y + e[2] >= s;
    }
    if (inside) lo = t.condition;
  }
  return {lo, hi};
}

// Outside the polygon: the derivation is allowance.hpp's. An implementation whose planes come
// from its unsnapped vertices f_j (each within ε of the exact q_j) and whose coverage from its
// snapped ones draws at the centre p its plane's value there: the exact value at
// q = Σ λ'_j q_j, λ' the barycentrics of p in (f_j), and p = Σ λ'_j f_j, so
// |q - p| <= Σ |λ'_j|·ε in x and in y. λ'_j = 2A'_j(p)/2A' (2A'_j(p) the doubled area with p
// in place of f_j): moving the vertices changes Σ_j |2A_j(p)| by at most
// 2ε·Σ_i |q_i - p|_1 + 6ε² (each vertex is in two of the three, ε·|edge|_1 each, and ε² terms)
// and |2A| by at most its `change` above, whence the reach below, a bound, not a first order;
// unbounded where 2A' may be 0.
double FanTriangles::reach(const Triangle& t, double x, double y) {
  if (!(t.area_below > 0)) return INFINITY;
  double areas = 0, distances = 0;
  for (int j = 0; j < 3; ++j) {
    const double* a = t.q[(j + 1) % 3];
    const double* b = t.q[(j + 2) % 3];
    areas += std::fabs((a[0] - x) * (b[1] - y) - (b[0] - x) * (a[1] - y));
    distances += std::fabs(t.q[j][0] - x) + std::fabs(t.q[j][1] - y);
  }
  const double e = t.rounding;
  return (1 + 0x1p-40) * e * (areas + 2 * e * distances + 6 * e * e) / t.area_below;
}

bool FanTriangles::inside(double x, double y) const {
  // On an edge within the test's rounding (2^-48 of its terms) counts as inside: a centre
  // exactly on an edge is the polygon's own.
  for (const auto& e : hull_) {
    const double s = 0x1p-48 * (std::fabs(e[0] * x) + std::fabs(e[1] * y) + std::fabs(e[2]));
    if (e[0] * x + e[1] * y + e[2] < -s) return false;
  }
  return true;
}

double FanTriangles::outside_reach(double x, double y) const {
  if (hull_.empty() || inside(x, y)) return -1;
  double held = -1, any = 0;
  for (const Triangle& t : triangles_) {
    const double r = reach(t, x, y);
    any = std::max(any, r);
    if (x < t.box[0] || x > t.box[2] || y < t.box[1] || y > t.box[3]) continue;
    bool holds = true;
    for (const auto& e : t.edge)
      holds = holds && e[0] * x + e[1] * y + e[2] >= 0;
    if (holds) held = std::max(held, r);
  }
  return held >= 0 ? held : any;
}

GLRC_BLOCK_FORM void FanTriangles::outside_reach(const double* x, const double* y,
                                                 double* out) const {
  // inside()'s tests lane by lane, without branches (vectorized): the common case, every lane
  // inside, ends there; a lane outside is then taken one at a time (the same function, the
  // same bits).
  constexpr int n = kRowBlock;
  int beyond[n] = {};
  for (const auto& e : hull_)
    for (int j = 0; j < n; ++j) {
      const double s =
          0x1p-48 * (std::fabs(e[0] * x[j]) + std::fabs(e[1] * y[j]) + std::fabs(e[2]));
      beyond[j] |= e[0] * x[j] + e[1] * y[j] + e[2] < -s;
    }
  int any = 0;
  for (int j = 0; j < n; ++j)
    out[j] = -1, any |= beyond[j];
  if (!any) return;
  for (int j = 0; j < n; ++j)
    if (beyond[j]) out[j] = outside_reach(x[j], y[j]);
}

bool FanTriangles::holds_run(double x0, double x1, double y) const {
  if (hull_.empty()) return true;
  for (const auto& e : hull_) {
    // Inside at both ends by more than inside()'s slack at any point between.
    const double s = 0x1p-47 * (std::fabs(e[0]) * std::max(std::fabs(x0), std::fabs(x1)) +
                                std::fabs(e[1] * y) + std::fabs(e[2]));
    if (e[0] * x0 + e[1] * y + e[2] < s || e[0] * x1 + e[1] * y + e[2] < s) return false;
  }
  return true;
}

Anchors::Anchors(const WindowPolygon& polygon, const WindowPolygon& guard_band) {
  // A point given twice (an unclipped triangle is its own guard-band triangle) counts once,
  // a fan anchor if either is: the largest terms over the anchors are the same.
  auto add = [&](double x, double y, bool fan) {
    for (size_t i = 0; i < count_; ++i)
      if (points_[i][0] == x && points_[i][1] == y) {
        fan_[i] = fan_[i] || fan;
        return;
      }
    if (count_ == kMost) throw std::logic_error("Anchors: more than 13 anchors");
    points_[count_] = {x, y}, fan_[count_] = fan, ++count_;
  };
  add(0, 0, false);
  for (const WindowPolygon* p : {&polygon, &guard_band})
    for (const auto& a : *p)
      if (std::isfinite(a[0]) && std::isfinite(a[1])) add(a[0], a[1], p == &polygon);
}

void Anchors::distances(int px, int py, Distances& out) const {
  const double x = px + 0.5, y = py + 0.5;  // window coordinates of the centre
  for (size_t i = 0; i < count_; ++i) {
    out.dx[i] = std::fabs(x - points_[i][0]), out.dy[i] = std::fabs(y - points_[i][1]);
    out.most[i] = std::max(out.dx[i], out.dy[i]);
  }
}

GLRC_BLOCK_FORM void Anchors::distances(const double* px, const double* py,
                                        RowDistances& out) const {
  for (size_t i = 0; i < count_; ++i) {
    const double ax = points_[i][0], ay = points_[i][1];
    for (int j = 0; j < kRowBlock; ++j) {
      const double dx = std::fabs((px[j] + 0.5) - ax), dy = std::fabs((py[j] + 0.5) - ay);
      out.dx[i][size_t(j)] = dx, out.dy[i][size_t(j)] = dy;
      out.most[i][size_t(j)] = std::max(dx, dy);
    }
  }
}

void Anchors::distances(int px0, int px1, int py, RunDistances& out) const {
  const double x0 = px0 + 0.5, x1 = px1 + 0.5, y = py + 0.5;
  for (size_t i = 0; i < count_; ++i) {
    const double ax = points_[i][0];
    const double d0 = std::fabs(x0 - ax), d1 = std::fabs(x1 - ax);
    // Zero where the anchor's column is within the run (x - x_a changes sign there).
    out.dx_lo[i] = x0 <= ax && ax <= x1 ? 0.0 : std::min(d0, d1);
    out.dx_hi[i] = std::max(d0, d1);
    out.dy[i] = std::fabs(y - points_[i][1]);
    out.most_lo[i] = std::max(out.dx_lo[i], out.dy[i]);
    out.most_hi[i] = std::max(out.dx_hi[i], out.dy[i]);
  }
}

void Allowance::set_planes(const LinearForm& numerator, const LinearForm& denominator) {
  double c[6];
  normalized_doubles(numerator, denominator, c);
  an_ = c[0], bn_ = c[1], cn_ = c[2], ad_ = c[3], bd_ = c[4], cd_ = c[5];
  abs_an_ = std::fabs(an_), abs_bn_ = std::fabs(bn_), abs_ad_ = std::fabs(ad_),
  abs_bd_ = std::fabs(bd_);
  // The planes' values at the anchors; the forms take pixel coordinates px = x - 1/2.
  const Anchors& a = anchors();
  for (size_t i = 0; i < a.size(); ++i) {
    n_[i] = std::fabs(an_ * (a.x(i) - 0.5) + bn_ * (a.y(i) - 0.5) + cn_);
    d_[i] = std::fabs(ad_ * (a.x(i) - 0.5) + bd_ * (a.y(i) - 0.5) + cd_);
  }
}

Allowance::Allowance(const LinearForm& numerator, const LinearForm& denominator, double spread,
                     double values, const WindowPolygon& polygon, const WindowPolygon& guard_band)
    : spread_(spread), values_(values), own_(polygon, guard_band) {
  set_planes(numerator, denominator);
}

Allowance::Allowance(const LinearForm& numerator, const LinearForm& denominator, double spread,
                     double values, const Anchors& anchors, const PositionReach& reach)
    : spread_(spread), values_(values), reach_(reach), shared_(&anchors) {
  set_planes(numerator, denominator);
}

// The derivation's position term, in two parts: the first order times 1.5, the exact bound over
// the points within h of p (its denominator's test apart), and then their larger, at most the
// spread. The block form computes the parts of every lane in one loop and chooses in another:
// a choice between the exact bound and infinity in one loop would move the bound's division
// into a branch, which is not vectorized (it might trap).
[[gnu::always_inline]] inline Allowance::PositionParts Allowance::position_parts(
    double px, double py, double v, double d, double delta, double h) const {
  // The value's gradient per pixel: ∇(N/D) = (∇N - v∇D) / D.
  const double a = an_ - v * ad_, b = bn_ - v * bd_;
  const double vx = a / d, vy = b / d;
  const double first = 1.5 * delta * (std::fabs(vx) + std::fabs(vy));
  const double gd = abs_ad_ + abs_bd_;
  const double numerator =
      h * ((std::fabs(a) + std::fabs(b)) + (0x1p-23 * std::fabs(v) + 0x1p-149) * gd);
  const double terms_d = abs_ad_ * std::fabs(px) + std::fabs(bd_ * py) + std::fabs(cd_);
  const double below = (std::fabs(d) - 0x1p-50 * terms_d) - h * gd;
  return {first, (1 + 0x1p-30) * (numerator / below), double(below > 0x1p-20 * std::fabs(d))};
}

[[gnu::always_inline]] inline double Allowance::position(const PositionParts& p) const {
  const double bound = p.defined != 0 ? p.exact : INFINITY;
  const double moved = p.first < bound ? bound : p.first;  // std::max(first, bound)
  return spread_ < moved ? spread_ : moved;                // std::min(moved, spread_)
}

double Allowance::outside_position(double px, double py, double v, double d, double delta,
                                   double outside) const {
  // A sliver that may turn over: its 1/2A may be infinite, and even a constant plane's gradient
  // 0·∞.
  if (!(outside < INFINITY)) return INFINITY;
  // Equal values at every vertex make a constant plane: any implementation's value is a sum of
  // them weighted by barycentrics that sum to 1, in or out of its triangle, so still that one.
  if (spread_ == 0) return 0;
  // The snapped implementation's (its value that of a point within h of p, as inside, but no
  // longer within the vertices' spread: p lies beyond them) and the unsnapped one's (the point
  // within `outside`).
  const PositionParts snapped = position_parts(px, py, v, d, delta, reach_.at(delta));
  const PositionParts unsnapped = position_parts(px, py, v, d, outside, outside);
  double most = 0;
  for (const PositionParts& p : {snapped, unsnapped})
    most = std::max({most, p.first, p.defined != 0 ? p.exact : INFINITY});
  return most;
}

double Allowance::at(int px, int py, float value, double delta, double extra, double condition,
                     double outside) const {
  Anchors::Distances distances;
  anchors().distances(px, py, distances);
  return at(px, py, value, delta, extra, condition, outside, distances);
}

double Allowance::at(int px, int py, float value, double delta, double extra, double condition,
                     double outside, const Anchors::Distances& distances) const {
  const double v = double(value);
  const double d = ad_ * px + bd_ * py + cd_;
  if (!(std::fabs(d) > 0) || !std::isfinite(v)) return std::numeric_limits<double>::infinity();
  const double moved = outside >= 0
                           ? outside_position(px, py, v, d, delta, outside)
                           : position(position_parts(px, py, v, d, delta, reach_.at(delta)));
  // Each plane evaluated in float from an anchor: its terms' magnitudes, at the worst anchor;
  // and set up from a fan triangle anchored at a polygon vertex.
  const double abs_v = std::fabs(v);
  const double gn = abs_an_ + abs_bn_, gd = abs_ad_ + abs_bd_;
  const double g = gn + abs_v * gd;
  const Anchors& a = anchors();
  double terms = 0, setup = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double dx = distances.dx[i], dy = distances.dy[i];
    const double en = n_[i] + abs_an_ * dx + abs_bn_ * dy;
    const double ed = d_[i] + abs_ad_ * dx + abs_bd_ * dy;
    terms = std::max(terms, en + abs_v * ed);
    if (a.fan(i)) setup = std::max(setup, g * distances.most[i]);
  }
  const double evaluation = kEvaluationRoundings * kFloatUnitRoundoff * terms / std::fabs(d);
  const double set_up = kSetupRoundings * kFloatUnitRoundoff * condition * setup / std::fabs(d);
  return moved + evaluation + set_up + values_ + extra;
}

std::array<double, 2> Allowance::range(int px0, int px1, int py, float value_lo, float value_hi,
                                       const std::array<double, 2>& delta,
                                       const std::array<double, 2>& extra,
                                       const std::array<double, 2>& condition,
                                       const Anchors::RunDistances& distances) const {
  constexpr std::array<double, 2> kUnknown{0.0, INFINITY};
  const double v_lo = value_lo, v_hi = value_hi;
  if (!(v_lo <= v_hi) || !std::isfinite(v_lo) || !std::isfinite(v_hi)) return kUnknown;
  // A linear form's computed value is within two roundings of its exact value, 2^-52 of its
  // terms' magnitudes (s below is four times that); the exact value is linear along the run,
  // so between its ends' values.
  const auto linear = [](double e0, double e1, double s) -> std::array<double, 2> {
    return {std::min(e0, e1) - 2 * s, std::max(e0, e1) + 2 * s};
  };
  // |a| of a range {lo, hi}: {0, ...} where it may change sign.
  const auto magnitude = [](const std::array<double, 2>& r) -> std::array<double, 2> {
    if (r[0] > 0) return r;
    if (r[1] < 0) return {-r[1], -r[0]};
    return {0.0, std::max(-r[0], r[1])};
  };
  const double x0 = px0, x1 = px1, y = py;
  const double x_most = std::max(std::fabs(x0), std::fabs(x1));
  const auto d = linear(ad_ * x0 + bd_ * y + cd_, ad_ * x1 + bd_ * y + cd_,
                        0x1p-50 * (abs_ad_ * x_most + std::fabs(bd_ * y) + std::fabs(cd_)));
  const auto abs_d = magnitude(d);
  if (!(abs_d[0] > 0)) return kUnknown;
  const double v_most = std::max(std::fabs(v_lo), std::fabs(v_hi));
  const auto abs_v = magnitude({v_lo, v_hi});
  // |a - v·b| of the gradient's numerators A and B (linear in v), and (a - v·b)/d.
  const auto numerator = [&](double a, double b) {
    return magnitude(
        linear(a - v_lo * b, a - v_hi * b, 0x1p-50 * (std::fabs(a) + v_most * std::fabs(b))));
  };
  const auto num_a = numerator(an_, ad_), num_b = numerator(bn_, bd_);
  const std::array<double, 2> vx{num_a[0] / abs_d[1], num_a[1] / abs_d[0]};
  const std::array<double, 2> vy{num_b[0] / abs_d[1], num_b[1] / abs_d[0]};
  const double first_lo = 1.5 * delta[0] * (vx[0] + vy[0]);
  const double first_hi = 1.5 * delta[1] * (vx[1] + vy[1]);
  const double gn = abs_an_ + abs_bn_, gd = abs_ad_ + abs_bd_;
  // The exact bound's operands, each monotone, in position()'s order.
  const double h_lo = reach_.at(delta[0]), h_hi = reach_.at(delta[1]);
  const double n_lo = h_lo * ((num_a[0] + num_b[0]) + (0x1p-23 * abs_v[0] + 0x1p-149) * gd);
  const double n_hi = h_hi * ((num_a[1] + num_b[1]) + (0x1p-23 * abs_v[1] + 0x1p-149) * gd);
  const double x_least = x0 <= 0 && x1 >= 0 ? 0.0 : std::min(std::fabs(x0), std::fabs(x1));
  const double terms_d_lo = abs_ad_ * x_least + std::fabs(bd_ * y) + std::fabs(cd_);
  const double terms_d_hi = abs_ad_ * x_most + std::fabs(bd_ * y) + std::fabs(cd_);
  const double below_lo = (abs_d[0] - 0x1p-50 * terms_d_hi) - h_hi * gd;
  const double below_hi = (abs_d[1] - 0x1p-50 * terms_d_lo) - h_lo * gd;
  // Infinite at a pixel whose denominator is below 2^-20·|d|: above any lo, and hi only where
  // none is.
  const double bound_lo = below_hi > 0 ? (1 + 0x1p-30) * (n_lo / below_hi) : 0.0;
  const double bound_hi =
      below_lo > 0x1p-20 * abs_d[1] ? (1 + 0x1p-30) * (n_hi / below_lo) : INFINITY;
  const double moved_lo = std::max(first_lo, bound_lo), moved_hi = std::max(first_hi, bound_hi);
  const double position_lo = spread_ < moved_lo ? spread_ : moved_lo;
  const double position_hi = spread_ < moved_hi ? spread_ : moved_hi;
  const double g_lo = gn + abs_v[0] * gd, g_hi = gn + abs_v[1] * gd;
  const Anchors& a = anchors();
  double terms_lo = 0, terms_hi = 0, setup_lo = 0, setup_hi = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double en_lo = n_[i] + abs_an_ * distances.dx_lo[i] + abs_bn_ * distances.dy[i];
    const double en_hi = n_[i] + abs_an_ * distances.dx_hi[i] + abs_bn_ * distances.dy[i];
    const double ed_lo = d_[i] + abs_ad_ * distances.dx_lo[i] + abs_bd_ * distances.dy[i];
    const double ed_hi = d_[i] + abs_ad_ * distances.dx_hi[i] + abs_bd_ * distances.dy[i];
    terms_lo = std::max(terms_lo, en_lo + abs_v[0] * ed_lo);
    terms_hi = std::max(terms_hi, en_hi + abs_v[1] * ed_hi);
    if (a.fan(i)) {
      setup_lo = std::max(setup_lo, g_lo * distances.most_lo[i]);
      setup_hi = std::max(setup_hi, g_hi * distances.most_hi[i]);
    }
  }
  const double evaluation_lo = kEvaluationRoundings * kFloatUnitRoundoff * terms_lo / abs_d[1];
  const double evaluation_hi = kEvaluationRoundings * kFloatUnitRoundoff * terms_hi / abs_d[0];
  const double set_up_lo =
      kSetupRoundings * kFloatUnitRoundoff * condition[0] * setup_lo / abs_d[1];
  const double set_up_hi =
      kSetupRoundings * kFloatUnitRoundoff * condition[1] * setup_hi / abs_d[0];
  const double lo = position_lo + evaluation_lo + set_up_lo + values_ + extra[0];
  const double hi = position_hi + evaluation_hi + set_up_hi + values_ + extra[1];
  if (!(lo >= 0) || !(hi < INFINITY)) return {std::max(lo, 0.0) * (1 - 0x1p-44), INFINITY};
  // round_up is monotone: the stored float of a bound below hi is at most round_up(hi).
  return {lo * (1 - 0x1p-44), double(round_up(hi * (1 + 0x1p-44)))};
}

// Inlined into each block form's own copies (GLRC_BLOCK_FORM), which are vectorized for their
// own target: one body, two outputs.
[[gnu::always_inline]] inline void Allowance::block_at(const double* px, const double* py,
                                                       const float* value, const double* delta,
                                                       const double* extra, const double* condition,
                                                       const double* outside,
                                                       const Anchors::RowDistances& distances,
                                                       double* result) const {
  // The single pixel's at() above, lane by lane, in its order of operations: each lane's
  // double is the same bits. Its early return (no finite value, or D = 0 at the pixel) is a
  // choice at the end; the anchors' loop is turned inside out, each lane's maxima taken over
  // the anchors in the same order.
  constexpr int n = kRowBlock;
  const double gn = abs_an_ + abs_bn_, gd = abs_ad_ + abs_bd_;
  // Local arrays, written back at the end: no aliasing with the inputs to rule out.
  double v[n], d[n], abs_v[n], g[n], terms[n], setup[n];
  for (int j = 0; j < n; ++j) {
    v[j] = double(value[j]);
    d[j] = ad_ * px[j] + bd_ * py[j] + cd_;
    abs_v[j] = std::fabs(v[j]);
    g[j] = gn + abs_v[j] * gd;
  }
  // The anchors' maxima in vectors of four lanes (GCC's vector extensions: the same IEEE
  // operations, lane by lane), so that they stay in registers from anchor to anchor: as arrays,
  // each anchor's maximum was stored and loaded again, a chain through memory that held a fifth
  // of this function's samples.
  using Four = double __attribute__((vector_size(4 * sizeof(double))));
  static_assert(n == 2 * 4);
  // A block's lanes as two vectors, and back (by reference: a vector returned by value would
  // change the ABI between the two clones).
  const auto load = [](const double* lanes, Four& low, Four& high) {
    std::memcpy(&low, lanes, sizeof low), std::memcpy(&high, lanes + 4, sizeof high);
  };
  const auto store = [](const Four& low, const Four& high, double* lanes) {
    std::memcpy(lanes, &low, sizeof low), std::memcpy(lanes + 4, &high, sizeof high);
  };
  Four abs_v0, abs_v1, g0, g1, terms0 = {}, terms1 = {}, setup0 = {}, setup1 = {};
  load(abs_v, abs_v0, abs_v1);
  load(g, g0, g1);
  const Anchors& a = anchors();
  for (size_t i = 0; i < a.size(); ++i) {
    Four dx0, dx1, dy0, dy1;
    load(distances.dx[i].data(), dx0, dx1);
    load(distances.dy[i].data(), dy0, dy1);
    const Four en0 = n_[i] + abs_an_ * dx0 + abs_bn_ * dy0;
    const Four en1 = n_[i] + abs_an_ * dx1 + abs_bn_ * dy1;
    const Four ed0 = d_[i] + abs_ad_ * dx0 + abs_bd_ * dy0;
    const Four ed1 = d_[i] + abs_ad_ * dx1 + abs_bd_ * dy1;
    const Four term0 = en0 + abs_v0 * ed0, term1 = en1 + abs_v1 * ed1;
    // std::max(terms, term): terms unless terms < term.
    terms0 = terms0 < term0 ? term0 : terms0;
    terms1 = terms1 < term1 ? term1 : terms1;
    if (a.fan(i)) {
      Four most0, most1;
      load(distances.most[i].data(), most0, most1);
      const Four moved0 = g0 * most0, moved1 = g1 * most1;
      setup0 = setup0 < moved0 ? moved0 : setup0;
      setup1 = setup1 < moved1 ? moved1 : setup1;
    }
  }
  store(terms0, terms1, terms);
  store(setup0, setup1, setup);
  double first[n], exact[n], defined[n];
  for (int j = 0; j < n; ++j) {
    const PositionParts p = position_parts(px[j], py[j], v[j], d[j], delta[j], reach_.at(delta[j]));
    first[j] = p.first, exact[j] = p.exact, defined[j] = p.defined;
  }
  double position[n];
  int any_outside = 0;
  for (int j = 0; j < n; ++j) {
    position[j] = this->position({first[j], exact[j], defined[j]});
    any_outside |= outside[j] >= 0;
  }
  // A pixel outside the polygon (rare: where an implementation covers beyond the exact
  // edges), one at a time, as at() does.
  if (any_outside)
    for (int j = 0; j < n; ++j)
      if (outside[j] >= 0 && std::fabs(d[j]) > 0 && abs_v[j] <= std::numeric_limits<double>::max())
        position[j] = outside_position(px[j], py[j], v[j], d[j], delta[j], outside[j]);
  for (int j = 0; j < n; ++j) {
    // The early return, as a selection below (no branch: vectorized).
    const double evaluation =
        kEvaluationRoundings * kFloatUnitRoundoff * terms[j] / std::fabs(d[j]);
    const double set_up =
        kSetupRoundings * kFloatUnitRoundoff * condition[j] * setup[j] / std::fabs(d[j]);
    result[j] = position[j] + evaluation + set_up + values_ + extra[j];
  }
  // A loop of its own: a selection between the sum and infinity in the loop above would move
  // the sum's divisions into a branch, which is not vectorized (they might trap).
  for (int j = 0; j < n; ++j) {
    // !(|d| > 0) or !isfinite(v): NaN compares false.
    const bool undefined =
        !(std::fabs(d[j]) > 0) | !(abs_v[j] <= std::numeric_limits<double>::max());
    result[j] = undefined ? std::numeric_limits<double>::infinity() : result[j];
  }
}

GLRC_BLOCK_FORM void Allowance::at(const double* px, const double* py, const float* value,
                                   const double* delta, const double* extra,
                                   const double* condition, const double* outside,
                                   const Anchors::RowDistances& distances, double* out) const {
  double result[kRowBlock];
  block_at(px, py, value, delta, extra, condition, outside, distances, result);
  std::copy(result, result + kRowBlock, out);
}

GLRC_BLOCK_FORM void Allowance::at_rounded_up(const double* px, const double* py,
                                              const float* value, const double* delta,
                                              const double* extra, const double* condition,
                                              const double* outside,
                                              const Anchors::RowDistances& distances,
                                              float* out) const {
  // The bounds go to round_up from registers or this frame, not through the caller's memory.
  double result[kRowBlock];
  block_at(px, py, value, delta, extra, condition, outside, distances, result);
  round_up(result, out);
}

}  // namespace glrc::ref
