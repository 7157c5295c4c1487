// Model, view and projection matrices in double precision, and the one rounding to float32.
//
// Why this file is compiled with -ffp-contract=off (root CMakeLists.txt): the reference's
// bit-exactness is tested by building it with -O0 and with -O3 -march=native -ffp-contract=fast
// and comparing frame digests. Clip coordinates come from here, so if the optimizing build fused
// a*b+c into an FMA (one rounding instead of two) in a matrix product, a clip coordinate could
// land on the other side of a float32 rounding boundary and every digest downstream would
// differ, although the reference itself is exact. With contraction off, every + and * here
// rounds once, in IEEE double, in source order, at any optimization level and on any x86-64
// CPU. fp_contraction_off() checks at run time that the flag really reached this file.
//
// GLM is header-only, so its functions are instantiated in this translation unit and get the
// same flag. (If another translation unit linked into the same binary instantiated the very same
// GLM templates with contraction on, the linker could keep either copy: keep GLM use for clip
// coordinates in this file only.)
//
// Why not glm::perspective and glm::rotate as they are: they call std::tan, std::sin and
// std::cos, whose last bit is not specified and may differ between C library versions, and
// glibc picks a different implementation (an FMA one) on CPUs that have FMA. The bits of a case
// would then depend on the machine. sincos_degrees() below uses only +, -, *, / and sqrt, which
// IEEE 754 rounds exactly; the two matrices are then built with GLM's own formulas around it.
// translate, scale, lookAt, frustum and ortho use no transcendental function and are GLM's.
#include "casefile/transform.hpp"

#include <cmath>
#include <stdexcept>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace glrc::casefile {

bool fp_contraction_off() {
  // a*a + c: the exact product 1 + 2^-29 + 2^-60 rounds to 1 + 2^-29 in double, so the sum is 0;
  // a fused multiply-add keeps 2^-60. volatile keeps the compiler from folding it.
  volatile double va = 1.0 + 0x1p-30, vc = -(1.0 + 0x1p-29);
  double a = va, c = vc;
  return a * a + c == 0.0;
}

namespace {

// sin and cos of t radians for t in [0, pi/4]: Taylor series to t^19 and t^20, whose truncation
// error there is below 2e-19, far under half an ulp; Horner order fixed.
void sincos_small(double t, double& s, double& c) {
  const double t2 = t * t;
  constexpr double s3 = -1.0 / 6.0, s5 = 1.0 / 120.0, s7 = -1.0 / 5040.0, s9 = 1.0 / 362880.0,
                   s11 = -1.0 / 39916800.0, s13 = 1.0 / 6227020800.0, s15 = -1.0 / 1307674368000.0,
                   s17 = 1.0 / 355687428096000.0, s19 = -1.0 / 121645100408832000.0;
  constexpr double c2 = -1.0 / 2.0, c4 = 1.0 / 24.0, c6 = -1.0 / 720.0, c8 = 1.0 / 40320.0,
                   c10 = -1.0 / 3628800.0, c12 = 1.0 / 479001600.0, c14 = -1.0 / 87178291200.0,
                   c16 = 1.0 / 20922789888000.0, c18 = -1.0 / 6402373705728000.0,
                   c20 = 1.0 / 2432902008176640000.0;
  double ps = s19;
  for (double k : {s17, s15, s13, s11, s9, s7, s5, s3})
    ps = ps * t2 + k;
  s = t + t * (t2 * ps);
  double pc = c20;
  for (double k : {c18, c16, c14, c12, c10, c8, c6, c4, c2})
    pc = pc * t2 + k;
  c = 1.0 + t2 * pc;
}

}  // namespace

void sincos_degrees(double degrees, double& s, double& c) {
  // Reduce in degrees, where the reductions are exact: fmod is exact, and r - 90 for r in
  // [90, 360) is a multiple of ulp(r) no larger than r, hence representable.
  double r = std::fmod(degrees, 360.0);
  if (r < 0) r += 360.0;  // may round for tiny negative r, to 360 at worst
  if (r >= 360.0) r -= 360.0;
  int quadrant = 0;
  while (r >= 90.0) {
    r -= 90.0;
    ++quadrant;
  }
  // r in [0, 90): use the octant [0, 45], where the series converges fastest; 90 - r is exact
  // for r in [45, 90] (Sterbenz).
  constexpr double kRadiansPerDegree = 0.017453292519943295;  // pi/180 rounded to double
  double s0, c0;
  if (r == 45.0) {
    s0 = c0 = std::sqrt(0.5);  // equal, so that tan(45) is exactly 1
  } else if (r > 45.0) {
    sincos_small((90.0 - r) * kRadiansPerDegree, c0, s0);
  } else {
    sincos_small(r * kRadiansPerDegree, s0, c0);
  }
  switch (quadrant) {
    case 0:
      s = s0, c = c0;
      break;
    case 1:
      s = c0, c = -s0;
      break;
    case 2:
      s = -s0, c = -c0;
      break;
    default:
      s = -c0, c = s0;
      break;
  }
}

namespace {

glm::dvec3 vec3(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

// glm::rotate's formula (Rodrigues, axis normalized), with sincos_degrees for the angle.
glm::dmat4 rotate(const glm::dmat4& m, double degrees, const glm::dvec3& v) {
  double s, c;
  sincos_degrees(degrees, s, c);
  const glm::dvec3 axis = glm::normalize(v);
  const glm::dvec3 temp = (1.0 - c) * axis;
  glm::dmat4 r(1.0);
  r[0][0] = c + temp[0] * axis[0];
  r[0][1] = temp[0] * axis[1] + s * axis[2];
  r[0][2] = temp[0] * axis[2] - s * axis[1];
  r[1][0] = temp[1] * axis[0] - s * axis[2];
  r[1][1] = c + temp[1] * axis[1];
  r[1][2] = temp[1] * axis[2] + s * axis[0];
  r[2][0] = temp[2] * axis[0] + s * axis[1];
  r[2][1] = temp[2] * axis[1] - s * axis[0];
  r[2][2] = c + temp[2] * axis[2];
  return m * r;
}

// glm::perspectiveRH_NO's formula (GL's [-1, 1] depth), with sincos_degrees for the tangent.
glm::dmat4 perspective(double fovy_degrees, double aspect, double n, double f) {
  double s, c;
  sincos_degrees(fovy_degrees / 2.0, s, c);
  const double tan_half = s / c;
  glm::dmat4 p(0.0);
  p[0][0] = 1.0 / (aspect * tan_half);
  p[1][1] = 1.0 / tan_half;
  p[2][2] = -(f + n) / (f - n);
  p[2][3] = -1.0;
  p[3][2] = -(2.0 * f * n) / (f - n);
  return p;
}

glm::dmat4 compose(const std::vector<TransformOp>& ops) {
  glm::dmat4 m(1.0);
  // Each GLM call returns m * op, so the list's first op ends up leftmost, the last one applies
  // to the vertex first: as in GL code calling translate, then rotate, then scale.
  for (const TransformOp& op : ops) {
    switch (op.kind) {
      case TransformOp::Kind::translate:
        m = glm::translate(m, vec3(op.v));
        break;
      case TransformOp::Kind::rotate:
        m = rotate(m, op.degrees, vec3(op.v));
        break;
      case TransformOp::Kind::scale:
        m = glm::scale(m, vec3(op.v));
        break;
      case TransformOp::Kind::look_at:
        m = m * glm::lookAtRH(vec3(op.v), vec3(op.center), vec3(op.up));
        break;
    }
  }
  return m;
}

glm::dmat4 projection(const Projection& p) {
  const auto& a = p.p;
  switch (p.kind) {
    case Projection::Kind::identity:
      return glm::dmat4(1.0);
    case Projection::Kind::perspective:
      return perspective(a[0], a[1], a[2], a[3]);
    case Projection::Kind::frustum:
      return glm::frustumRH_NO(a[0], a[1], a[2], a[3], a[4], a[5]);
    case Projection::Kind::ortho:
      return glm::orthoRH_NO(a[0], a[1], a[2], a[3], a[4], a[5]);
  }
  return glm::dmat4(1.0);
}

}  // namespace

std::vector<std::array<double, 4>> to_clip(const Transform& t,
                                           const std::vector<std::array<double, 4>>& positions) {
  static const bool contraction_off = fp_contraction_off();
  if (!contraction_off)
    throw std::logic_error(
        "casefile/transform.cpp was compiled with floating-point contraction; it needs "
        "-ffp-contract=off for build-independent clip coordinates");
  const glm::dmat4 m = compose(t.model), v = compose(t.view), p = projection(t.projection);
  std::vector<std::array<double, 4>> out;
  out.reserve(positions.size());
  for (const auto& pos : positions) {
    // One matrix at a time, as a vertex shader with three uniforms would: P * (V * (M * pos)).
    const glm::dvec4 clip = p * (v * (m * glm::dvec4(pos[0], pos[1], pos[2], pos[3])));
    out.push_back({clip.x, clip.y, clip.z, clip.w});
  }
  return out;
}

}  // namespace glrc::casefile
