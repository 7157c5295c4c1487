#include "ref/interpolation.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace glrc::ref {

void barycentrics(const TriangleSetup& t, const Model& m, Barycentrics& b) {
  b.screen_space = m.planes == Planes::snapped && t.path == CoveragePath::snapped;
  if (b.screen_space) {
    for (int i = 0; i < 3; ++i) {
      const auto& e = t.snapped_edges[i];
      b.l[i] = {mpq_class(to_mpz(e.a)), mpq_class(to_mpz(e.b)), mpq_class(to_mpz(e.c))};
    }
  } else {
    b.l = t.homogeneous_edges;  // into b's rationals: their limbs reused
  }
  b.is_dyadic = true;
  for (int i = 0; i < 3 && b.is_dyadic; ++i)
    b.is_dyadic = Dyadic::of(b.l[i].a, b.dyadic[i][0]) && Dyadic::of(b.l[i].b, b.dyadic[i][1]) &&
                  Dyadic::of(b.l[i].c, b.dyadic[i][2]);
}

LinearForm sum(const Barycentrics& b, const std::array<mpq_class, 3>& alpha) {
  LinearForm f;
  // Dyadic forms and weights (every weight of an unsnapped plane: a float32 value, w_c, w_c·z_w
  // or 1): each coefficient as one sum of products of integers, then made a rational once.
  if (Dyadic weight[3]; b.is_dyadic && Dyadic::of(alpha[0], weight[0]) &&
                        Dyadic::of(alpha[1], weight[1]) && Dyadic::of(alpha[2], weight[2])) {
    const Dyadic* weights[3] = {&weight[0], &weight[1], &weight[2]};
    mpq_class* coefficient[3] = {&f.a, &f.b, &f.c};
    Dyadic total;
    for (int k = 0; k < 3; ++k) {
      const Dyadic* terms[3] = {&b.dyadic[0][k], &b.dyadic[1][k], &b.dyadic[2][k]};
      sum_of_products(total, terms, weights, 3);
      total.to(*coefficient[k]);
    }
    return f;
  }
  mpq_class scratch;
  for (int i = 0; i < 3; ++i)
    // Most weights are 1 (beta of smooth or noperspective planes): a sum, no product.
    if (alpha[i] == 1)
      f += b.l[i];
    else
      f.add_product(b.l[i], alpha[i], scratch);
  return f;
}

Plane plane(const Barycentrics& b, const std::array<mpq_class, 3>& alpha,
            const std::array<mpq_class, 3>& beta) {
  return {sum(b, alpha), sum(b, beta)};
}

namespace {

// Built-in component `i` of varying v on triangle t (component_planes).
ComponentPlane builtin_plane(const Case& c, const Varying& v, int i, const TriangleSetup& t,
                             const Barycentrics& b, const Plane& depth) {
  ComponentPlane p;
  p.builtin = v.builtin;
  p.component = i;
  if (v.builtin == Builtin::front_facing) {
    p.flat = true;
    p.flat_value = t.front_facing ? 1.0f : 0.0f;
    return p;
  }
  const mpq_class half = v.layout.pixel_center_integer ? mpq_class(0) : mpq_class(1, 2);
  const LinearForm one{0, 0, 1};
  if (i == 0) {
    p.plane = {{1, 0, half}, one};
  } else if (i == 1) {
    p.plane = v.layout.origin_upper_left ? Plane{{0, -1, mpq_class(c.fb_height) - (1 - half)}, one}
                                         : Plane{{0, 1, half}, one};
  } else if (i == 2) {
    p.plane = depth;
  } else {
    std::array<mpq_class, 3> alpha, beta;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t j = 0; j < 3; ++j) {
      const mpq_class& w = t.v[j].w_c;
      if (b.screen_space) {
        mpq_inv(alpha[j].get_mpq_t(), w.get_mpq_t());
        beta[j] = 1;
      } else {
        alpha[j] = 1;
        beta[j] = w;
      }
      const double inverse = 1 / double(c.vertices[t.index[j]].clip[3]);
      lo = std::min(lo, inverse), hi = std::max(hi, inverse);
      p.scale = std::max(p.scale, std::fabs(inverse));
    }
    // Every value is Σ λ_i/w_i over the drawn polygon, within [lo, hi] where every w_i > 0 (its
    // clip-made vertices' w_c are convex combinations of the w_i); 1/w_i in double is within
    // 2^-53 of its own, so 2^-50 of the magnitudes more holds the exact spread. Behind the eye
    // no bound.
    p.spread = lo > 0 ? (hi - lo) + 0x1p-50 * hi : INFINITY;
    p.plane = plane(b, alpha, beta);
  }
  p.ratio = p.plane.evaluator();
  return p;
}

}  // namespace

std::vector<ComponentPlane> component_planes(const Case& c, const TriangleSetup& t,
                                             const Barycentrics& b, const Plane& depth) {
  std::vector<ComponentPlane> planes;
  std::optional<LinearForm> denominators[2];  // noperspective, smooth
  const int provoking = c.provoking == ProvokingVertex::last ? 2 : 0;
  const auto owner = component_varying(c);
  for (size_t k = 0; k < owner.size(); ++k) {
    const Varying& v = c.varyings[size_t(owner[k])];
    if (v.is_builtin()) {
      planes.push_back(builtin_plane(c, v, varying_component(c, int(k)).component, t, b, depth));
      continue;
    }
    ComponentPlane p;
    const Interpolation q = v.interpolation;
    if (q == Interpolation::flat) {
      p.flat = true;
      p.flat_value = c.vertices[t.index[provoking]].values[k];
      planes.push_back(std::move(p));
      continue;
    }
    const bool perspective = q == Interpolation::smooth;
    // The weights in rationals kept per thread, each product or quotient made in its place: as
    // temporaries they were a dozen allocations per component of every triangle.
    thread_local std::array<mpq_class, 3> alpha, beta;
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < 3; ++i) {
      const double value = double(c.vertices[t.index[i]].values[k]);
      lo = std::min(lo, value), hi = std::max(hi, value);
      p.scale = std::max(p.scale, std::fabs(value));
      const mpq_class& w = t.v[i].w_c;
      alpha[i] = value;
      if (b.screen_space && perspective)
        mpq_div(alpha[i].get_mpq_t(), alpha[i].get_mpq_t(), w.get_mpq_t());
      else if (!b.screen_space && !perspective)
        mpq_mul(alpha[i].get_mpq_t(), w.get_mpq_t(), alpha[i].get_mpq_t());
    }
    // Every component of one qualifier has the same denominator: its exact form is built once
    // per triangle, not once per component.
    std::optional<LinearForm>& denominator = denominators[perspective ? 1 : 0];
    if (!denominator) {
      for (int i = 0; i < 3; ++i) {
        const mpq_class& w = t.v[i].w_c;
        if (b.screen_space && perspective)
          mpq_inv(beta[i].get_mpq_t(), w.get_mpq_t());
        else if (b.screen_space || perspective)
          beta[i] = 1;
        else
          beta[i] = w;
      }
      denominator = sum(b, beta);
    }
    p.spread = hi - lo;
    p.plane = {sum(b, alpha), *denominator};
    p.ratio = p.plane.evaluator();
    planes.push_back(std::move(p));
  }
  return planes;
}

ComponentValues::ComponentValues(const std::vector<ComponentPlane>& planes) : planes_(&planes) {
  for (size_t k = 0; k < planes.size(); ++k) {
    if (planes[k].flat) continue;
    double f[6];
    if (!planes[k].ratio.fast_coefficients(f)) {
      slow_.push_back(k);
      continue;
    }
    auto same = std::find_if(shared_.begin(), shared_.end(), [&](const Denominator& d) {
      return d.a == f[3] && d.b == f[4] && d.c == f[5];
    });
    if (same == shared_.end()) same = shared_.insert(shared_.end(), {f[3], f[4], f[5], {}});
    same->numerators.push_back({k, f[0], f[1], f[2]});
  }
}

void ComponentValues::values(long px, long py, float* out) const {
  const std::vector<ComponentPlane>& planes = *planes_;
  for (size_t k = 0; k < planes.size(); ++k)
    if (planes[k].flat) out[k] = planes[k].flat_value;
  for (size_t k : slow_)
    out[k] = planes[k].ratio.exact_at(px, py);
  // The fast path of RatioEvaluator::at, with the division by d shared. n and d are the forms
  // in double, each coefficient within a relative 2u of the exact one (u = 2^-53): whatever
  // the order of the products and sums, fused or not, |n - N| <= 5u·S (S the sum of the terms'
  // magnitudes), which en = 8u·S̃ bounds with S̃ computed in double; likewise ed for d. Where
  // |d| > 4·ed, |n/d - N/D| <= (en + |n/d|·ed)/(|d| - ed) =: E. q = n·(1/d) is within 2u|q| of
  // n/d, and the endpoints q ± err are rounded once more (u(|q| + err)), so
  //     err = ((en + |q|·ed)·(1/(|d| - ed)) + 6u|q|)·1.01 + 2^-1000
  // keeps N/D within [q - err, q + err] as computed: the 1% covers the few roundings of err's
  // own arithmetic and of |q| for |n/d| in E; 2^-1000 a q in double's subnormal range. Where
  // both ends round to the same float, monotone rounding makes it the float nearest N/D, which
  // is what the exact path gives; anywhere else the exact path decides.
  constexpr double u = 0x1p-53;
  const double x = double(px), y = double(py), ax = std::fabs(x), ay = std::fabs(y);
  for (const Denominator& den : shared_) {
    const double d = den.a * x + den.b * y + den.c;
    const double ed = 8 * u * (std::fabs(den.a) * ax + std::fabs(den.b) * ay + std::fabs(den.c));
    const double ad = std::fabs(d);
    const bool fast = ad > 4 * ed;
    const double inverse_d = 1 / d, inverse_margin = 1 / (ad - ed);
    for (const Numerator& num : den.numerators) {
      if (fast) {
        const double n = num.a * x + num.b * y + num.c;
        const double en =
            8 * u * (std::fabs(num.a) * ax + std::fabs(num.b) * ay + std::fabs(num.c));
        const double q = n * inverse_d;
        const double err =
            ((en + std::fabs(q) * ed) * inverse_margin + 6 * u * std::fabs(q)) * 1.01 + 0x1p-1000;
        const float lo = float(q - err), hi = float(q + err);
        if (std::bit_cast<uint32_t>(lo) == std::bit_cast<uint32_t>(hi) && std::isfinite(lo)) {
          out[num.component] = lo;
          continue;
        }
      }
      out[num.component] = planes[num.component].ratio.exact_at(px, py);
    }
  }
}

GLRC_BLOCK_FORM void ComponentValues::values(const double* px, const double* py, float* out) const {
  constexpr int n = kRowBlock;
  const std::vector<ComponentPlane>& planes = *planes_;
  for (size_t k = 0; k < planes.size(); ++k)
    if (planes[k].flat) std::fill(out + k * n, out + (k + 1) * n, planes[k].flat_value);
  for (size_t k : slow_)
    for (int j = 0; j < n; ++j)
      out[k * n + size_t(j)] = planes[k].ratio.exact_at(long(px[j]), long(py[j]));
  // values()'s fast path and its proof, lane by lane, every lane's quantities 64 bits wide so
  // that the loops are vectorized; a lane it does not decide takes the exact path afterwards.
  // The bounds en and ed are taken once for the block, at its largest |x| and |y|: each is a sum
  // of products of non-negative numbers, and rounding is monotone, so it is at least every
  // lane's own. A larger en or ed only widens a lane's interval (err grows with both, and the
  // fast path needs |d| > 4·ed), so the proof holds as it stands; a lane it decides gets the
  // one float both ends round to, the same bits. The block's pixels are neighbours in a row:
  // it widens the bound by a few pixels' worth of 8u, and decides as many lanes.
  constexpr double u = 0x1p-53;
  double x[n], y[n], d[n], inverse_d[n], value[n];
  double largest_x = 0, largest_y = 0;
  for (int j = 0; j < n; ++j) {
    x[j] = px[j], y[j] = py[j];
    largest_x = std::max(largest_x, std::fabs(px[j]));
    largest_y = std::max(largest_y, std::fabs(py[j]));
  }
  // The bound en or ed of a form a·x + b·y + c over the block.
  auto block_bound = [&](double a, double b, double c) {
    return 8 * u * (std::fabs(a) * largest_x + std::fabs(b) * largest_y + std::fabs(c));
  };
  for (const Denominator& den : shared_) {
    const double ed = block_bound(den.a, den.b, den.c);
    double smallest_d = INFINITY;
    for (int j = 0; j < n; ++j) {
      d[j] = den.a * x[j] + den.b * y[j] + den.c;
      smallest_d = std::min(smallest_d, std::fabs(d[j]));
      inverse_d[j] = 1 / d[j];
    }
    // Every lane on the fast path (nearly always): err of the whole block at once, from the
    // block's smallest |d| and largest |q|. Each is a sum and products of non-negative
    // quantities, and rounding is monotone: 1/(smallest |d| - ed) is at least every lane's
    // 1/(|d| - ed), and the block's err at least every lane's own, so each lane's interval
    // [q - err, q + err] only widens (its ends are rounded monotonically too) and still holds
    // N/D. Where both ends round to one float it is the float nearest N/D, as before: the same
    // bits, for about half the arithmetic per lane. (A NaN q may or may not be the largest |q|: its
    // own ends are NaN, not finite, and it takes the exact path either way.)
    if (smallest_d > 4 * ed) {
      const double block_inverse_margin = 1 / (smallest_d - ed);
      // Lanes some component leaves undecided, ORed over the components as integers (one
      // horizontal test per block, not one per component): nearly always none.
      int32_t undecided[n] = {};
      // A group of components at a time, in three passes (the quotients and their largest
      // magnitudes; every err; the ends), so that the components' chains of dependent scalar
      // operations overlap instead of each waiting for the last.
      constexpr size_t kGroup = 8;
      const std::vector<Numerator>& numerators = den.numerators;
      for (size_t first = 0; first < numerators.size(); first += kGroup) {
        const size_t count = std::min(kGroup, numerators.size() - first);
        double quotient[kGroup][n], largest_q[kGroup], err[kGroup];
        for (size_t k = 0; k < count; ++k) {
          const Numerator& num = numerators[first + k];
          double magnitude[n];
          for (int j = 0; j < n; ++j) {
            quotient[k][j] = (num.a * x[j] + num.b * y[j] + num.c) * inverse_d[j];
            magnitude[j] = std::fabs(quotient[k][j]);
          }
          // The largest |q| by halving the lanes (a tree the vectorizer takes, where a
          // running std::max over doubles is not reassociated).
#pragma GCC unroll 4
          for (int width = n / 2; width >= 1; width /= 2)
            for (int j = 0; j < width; ++j)
              magnitude[j] =
                  magnitude[j] < magnitude[j + width] ? magnitude[j + width] : magnitude[j];
          largest_q[k] = magnitude[0];
        }
        for (size_t k = 0; k < count; ++k) {
          const Numerator& num = numerators[first + k];
          const double en = block_bound(num.a, num.b, num.c);
          err[k] = ((en + largest_q[k] * ed) * block_inverse_margin + 6 * u * largest_q[k]) * 1.01 +
                   0x1p-1000;
        }
        for (size_t k = 0; k < count; ++k) {
          float* column = out + numerators[first + k].component * n;
          // Decided: the same float at both ends (bit for bit: -0 and +0 differ, as they
          // should), and finite (NaN is not).
          for (int j = 0; j < n; ++j) {
            const float lo = float(quotient[k][j] - err[k]), hi = float(quotient[k][j] + err[k]);
            column[j] = lo;
            undecided[j] |= int32_t(std::bit_cast<int32_t>(lo) != std::bit_cast<int32_t>(hi)) |
                            int32_t(!(std::fabs(lo) <= std::numeric_limits<float>::max()));
          }
        }
      }
      int32_t any = 0;
      for (int j = 0; j < n; ++j)
        any |= undecided[j];
      // A lane some component left undecided: every shared component of it by the exact path
      // (which gives a decided one the same float).
      if (any != 0)
        for (int j = 0; j < n; ++j)
          if (undecided[j] != 0)
            for (const Numerator& num : den.numerators)
              out[num.component * n + size_t(j)] =
                  planes[num.component].ratio.exact_at(long(px[j]), long(py[j]));
      continue;
    }
    // Some lane's denominator too near 0 for the block's bound: each lane its own margin, and
    // the lanes off the fast path exact.
    double fast[n], decided[n], inverse_margin[n];  // fast, decided: 1 or 0, as wide as doubles
    for (int j = 0; j < n; ++j) {
      const double ad = std::fabs(d[j]);
      fast[j] = ad > 4 * ed ? 1.0 : 0.0;
      inverse_margin[j] = 1 / (ad - ed);
    }
    for (const Numerator& num : den.numerators) {
      const double en = block_bound(num.a, num.b, num.c);
      for (int j = 0; j < n; ++j) {
        const double nv = num.a * x[j] + num.b * y[j] + num.c;
        const double q = nv * inverse_d[j];
        const double err =
            ((en + std::fabs(q) * ed) * inverse_margin[j] + 6 * u * std::fabs(q)) * 1.01 +
            0x1p-1000;
        // The two ends rounded to float and back (exact, one to one): the same float when they
        // compare equal with the same sign (-0 and +0 compare equal; NaN never does).
        const double lo = double(float(q - err)), hi = double(float(q + err));
        const bool same = (lo == hi) & (std::copysign(1.0, lo) == std::copysign(1.0, hi));
        const bool finite = std::fabs(lo) <= double(std::numeric_limits<float>::max());
        decided[j] = same ? (finite ? fast[j] : 0.0) : 0.0;
        value[j] = lo;
      }
      float* column = out + num.component * n;
      // Whether any lane is undecided, as an integer OR over the lanes (vectorized, unlike a
      // branch per lane): nearly always none.
      int64_t undecided = 0;
      for (int j = 0; j < n; ++j) {
        column[j] = float(value[j]);
        undecided |= int64_t(decided[j] != 1);
      }
      if (undecided == 0) continue;
      for (int j = 0; j < n; ++j)
        if (decided[j] != 1)
          column[j] = planes[num.component].ratio.exact_at(long(px[j]), long(py[j]));
    }
  }
}

}  // namespace glrc::ref
