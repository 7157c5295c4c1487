// The "transform" of a case file: model, view and projection built from GLM operations in
// double precision, applied to object-space positions to give the float32 clip coordinates that
// both the reference and GL receive.
#pragma once

#include <array>
#include <vector>

namespace glrc::casefile {

// One model or view operation. Parameters are already validated by the loader.
struct TransformOp {
  enum class Kind { translate, rotate, scale, look_at };
  Kind kind = Kind::translate;
  std::array<double, 3> v{};       // translate, scale: the vector; rotate: the axis; look_at: eye
  double degrees = 0;              // rotate
  std::array<double, 3> center{};  // look_at
  std::array<double, 3> up{};      // look_at
};

struct Projection {
  enum class Kind { identity, perspective, frustum, ortho };
  Kind kind = Kind::identity;
  // perspective: fovy_degrees, aspect, near, far (4 used);
  // frustum, ortho: left, right, bottom, top, near, far.
  std::array<double, 6> p{};
};

struct Transform {
  std::vector<TransformOp> model;  // M = model[0] * model[1] * ...
  std::vector<TransformOp> view;   // V = view[0] * view[1] * ...
  Projection projection;           // P
};

// clip = P * V * M * position, in double, not yet rounded to float. A 3-component position
// gets w = 1 before it is passed here.
std::vector<std::array<double, 4>> to_clip(const Transform& t,
                                           const std::vector<std::array<double, 4>>& positions);

// sin and cos of an angle given in degrees, computed with +, -, *, / and sqrt only (see
// transform.cpp for why not std::sin). Exact at multiples of 90 degrees. Exposed for tests.
void sincos_degrees(double degrees, double& s, double& c);

// True when transform.cpp was compiled without floating-point contraction (a*b+c fused into
// one FMA), which the bit-exactness of clip coordinates across builds relies on.
bool fp_contraction_off();

}  // namespace glrc::casefile
