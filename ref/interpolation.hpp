// Interpolation: each varying component, and depth, as the exact ratio of two forms linear in
// window coordinates, N/D = sum L_i·alpha_i / sum L_i·beta_i, where the L_i are barycentric
// edge functions and (alpha_i, beta_i) depend on the qualifier:
//
//   planes from unsnapped positions (L_i ~ b_i/w at the pixel, clip-space barycentrics):
//     smooth         alpha = v_i            beta = 1       v = sum b_i v_i
//     noperspective  alpha = w_i v_i        beta = w_i     v = sum lambda_i v_i
//     depth          alpha = w_i z_w,i      beta = w_i     z_w = sum lambda_i z_w,i
//   planes from snapped positions (L_i ~ lambda_i, screen-space barycentrics):
//     smooth         alpha = v_i / w_i      beta = 1/w_i   (sum lambda v/w) / (sum lambda/w)
//     noperspective  alpha = v_i            beta = 1
//     depth          alpha = z_w,i          beta = 1
//
//   flat: the provoking vertex's value, copied.
//
// Unsnapped planes come straight from clip space, so they also hold for triangles that reach
// behind the eye; snapped planes exist only where positions were snapped.
#pragma once

#include <vector>

#include "core/case.hpp"
#include "core/model.hpp"
#include "ref/blocks.hpp"
#include "ref/exact.hpp"
#include "ref/setup.hpp"

namespace glrc::ref {

struct Barycentrics {
  std::array<LinearForm, 3> l;
  bool screen_space = false;  // snapped planes
  // l's coefficients (a, b, c of each) as Dyadic, when every one is dyadic (always, for planes
  // of float32 clip coordinates): sum() then multiplies and adds without gcds.
  std::array<std::array<Dyadic, 3>, 3> dyadic;
  bool is_dyadic = false;
};

// The barycentric forms of triangle t under model m, into `out`, whose rationals' storage is
// reused: a caller that keeps one per thread (render.cpp, per triangle) allocates nothing for
// unsnapped planes once it is warm (snapped planes' forms are made from the integer edges, and
// swapped in).
void barycentrics(const TriangleSetup& t, const Model& m, Barycentrics& out);

// A channel's value as N / D, two exact linear forms in pixel coordinates.
struct Plane {
  LinearForm numerator, denominator;
  RatioEvaluator evaluator() const { return RatioEvaluator(numerator, denominator); }
};

// Per component of the case: either a flat value or the exact ratio to evaluate per pixel.
struct ComponentPlane {
  bool flat = false;
  float flat_value = 0;
  Plane plane;
  RatioEvaluator ratio;
  double spread = 0, scale = 0;  // max v_i - min v_i and max |v_i| over the three vertices
  // A built-in's component (Varying::builtin; `component` 0..3 of gl_FragCoord), whose
  // allowance is its own (deferred.hpp).
  Builtin builtin = Builtin::none;
  int component = 0;
};

// Each component's plane on triangle t. A built-in's (core/case.hpp), exactly:
//   gl_FragCoord.x  px + 1/2 (px under pixel_center_integer)
//   gl_FragCoord.y  py + 1/2, or H − (py + 1/2) under origin_upper_left (H the framebuffer's
//                   height; 1/2 less each under pixel_center_integer)
//   gl_FragCoord.z  z_w: `depth`, the depth's plane
//   gl_FragCoord.w  1/w_c, linear in window coordinates: Σ λ_i/w_i, the noperspective plane of
//                   the values 1/w_i (alpha = 1, beta = w_i unsnapped; alpha = 1/w_i, beta = 1
//                   snapped), exact though no 1/w_i is a float
//   gl_FrontFacing  1 or 0 (TriangleSetup::front_facing), flat.
std::vector<ComponentPlane> component_planes(const Case& c, const TriangleSetup& t,
                                             const Barycentrics& b, const Plane& depth);

// Every component's value at a pixel at once, as ComponentPlane gives them, each the float
// nearest its exact ratio. Components that share a denominator (every smooth one: sum L_i over
// unsnapped planes; every noperspective one) share its evaluation, and the fast path divides
// once per denominator, not once per component (the proof is at values()). Read only once
// built: safe to use from several threads.
class ComponentValues {
 public:
  ComponentValues() = default;
  explicit ComponentValues(const std::vector<ComponentPlane>& planes);
  // out[k] = component k's value at pixel (px, py), for every k of `planes` (which must
  // outlive this).
  void values(long px, long py, float* out) const;
  // The same for kRowBlock pixels (px[j], py[j]) at once (integer pixel coordinates as
  // doubles): out[k·kRowBlock + j] is component k's value at pixel j, bit for bit what values()
  // gives (every value is the float nearest its exact ratio either way); the fast path's
  // arithmetic in loops over the lanes.
  void values(const double* px, const double* py, float* out) const;

 private:
  struct Numerator {
    size_t component;
    double a, b, c;
  };
  struct Denominator {
    double a, b, c;
    std::vector<Numerator> numerators;
  };
  const std::vector<ComponentPlane>* planes_ = nullptr;
  std::vector<Denominator> shared_;  // the components with a fast path, by denominator
  std::vector<size_t> slow_;         // the non-flat components without one
};

// Sum L_i alpha_i.
LinearForm sum(const Barycentrics& b, const std::array<mpq_class, 3>& alpha);

// Sum L_i alpha_i over sum L_i beta_i.
Plane plane(const Barycentrics& b, const std::array<mpq_class, 3>& alpha,
            const std::array<mpq_class, 3>& beta);

}  // namespace glrc::ref
