// The "transform" of a case: clip coordinates to the float bit, against hand computation and
// against independent long double math.
#include <cmath>
#include <random>

#include "casefile/transform.hpp"
#include "tests/casefile/test_helpers.hpp"

namespace glrc::casefile::test {
namespace {

TEST(Transform, CompiledWithoutContraction) {
  EXPECT_TRUE(fp_contraction_off());
}

TEST_F(CaseFileTest, PerspectiveAndTranslateByHand) {
  // fovy 90: tan 45 = 1, so P = diag(1/aspect, 1, -(f+n)/(f-n), 0) with P[3][2] = -2fn/(f-n),
  // P[2][3] = -1. near 1, far 3: z_c = -2 z_e - 3, w_c = -z_e.
  const Case c = load_text(R"({"description": "d",
    "transform": {"model": [{"translate": [0.25, -0.5, -2]}],
                  "projection": {"perspective": {"fovy_degrees": 90, "aspect": 2, "near": 1, "far": 3}}},
    "vertices": [{"position": [0.5, 0.25, 0.125]}, {"position": [-1, 1, 0.5]},
                 {"position": [0, 0, 0, 2]}]})");
  // Eye (0.75, -0.25, -1.875): clip (0.75/2, -0.25, 3.75 - 3, 1.875).
  EXPECT_EQ(c.vertices[0].clip, (std::array<float, 4>{0.375f, -0.25f, 0.75f, 1.875f}));
  // Eye (-0.75, 0.5, -1.5): clip (-0.375, 0.5, 0, 1.5).
  EXPECT_EQ(c.vertices[1].clip, (std::array<float, 4>{-0.375f, 0.5f, 0.0f, 1.5f}));
  // w = 2: eye (0.5, -1, -4, 2): clip (0.25, -1, 8 - 6, 4).
  EXPECT_EQ(c.vertices[2].clip, (std::array<float, 4>{0.25f, -1.0f, 2.0f, 4.0f}));
}

TEST_F(CaseFileTest, OpsApplyLastFirstAsInGlCode) {
  // M = T * R * S: the vertex is scaled, then rotated 90 degrees about z, then translated.
  // look_at from (0, 0, 5) to the origin, y up, is a translation by (0, 0, -5).
  const Case c = load_text(R"({"description": "d",
    "transform": {
      "model": [{"translate": [1, 2, -3]}, {"rotate": {"degrees": 90, "axis": [0, 0, 2]}},
                {"scale": [2, 0.5, 4]}],
      "view": [{"look_at": {"eye": [0, 0, 5], "center": [0, 0, 0], "up": [0, 1, 0]}}],
      "projection": {"frustum": {"left": -1, "right": 1, "bottom": -0.75, "top": 0.75,
                                 "near": 1, "far": 10}}},
    "vertices": [{"position": [0.5, 0.25, 0.125]}, {"position": [0, 0, 0]},
                 {"position": [1, 0, 0]}]})");
  // Scale: (1, 0.125, 0.5); rotate: (-0.125, 1, 0.5); translate: (0.875, 3, -2.5);
  // view: (0.875, 3, -7.5). Frustum: x_c = x, y_c = y / 0.75, z_c = -(11/9) z - 20/9, w_c = -z.
  EXPECT_EQ(c.vertices[0].clip,
            (std::array<float, 4>{0.875f, 4.0f, static_cast<float>(125.0L / 18.0L), 7.5f}));
  // Origin: eye (1, 2, -8): z_c = 88/9 - 20/9 = 68/9.
  EXPECT_EQ(c.vertices[1].clip, (std::array<float, 4>{1.0f, static_cast<float>(8.0L / 3.0L),
                                                      static_cast<float>(68.0L / 9.0L), 8.0f}));
  // (1, 0, 0): scaled (2, 0, 0), rotated (0, 2, 0), eye (1, 4, -8).
  EXPECT_EQ(c.vertices[2].clip, (std::array<float, 4>{1.0f, static_cast<float>(16.0L / 3.0L),
                                                      static_cast<float>(68.0L / 9.0L), 8.0f}));
}

TEST_F(CaseFileTest, OrthoByHand) {
  const Case c = load_text(R"({"description": "d",
    "transform": {"projection": {"ortho": {"left": -2, "right": 6, "bottom": -1, "top": 3,
                                           "near": -1, "far": 3}}},
    "vertices": [{"position": [2, 1, -1]}, {"position": [6, 3, 1]}, {"position": [-2, -1, -3]}]})");
  // x_c = x/4 - 1/2, y_c = y/2 - 1/2, z_c = -z/2 - 1/2 (near plane z = 1 maps to -1).
  EXPECT_EQ(c.vertices[0].clip, (std::array<float, 4>{0, 0, 0, 1}));
  EXPECT_EQ(c.vertices[1].clip, (std::array<float, 4>{1, 1, -1, 1}));
  EXPECT_EQ(c.vertices[2].clip, (std::array<float, 4>{-1, -1, 1, 1}));
}

// Textbook matrices in long double (64-bit mantissa): 11 more bits than the double path, so
// both round to the same float unless a coordinate lies within ~1e-16 of a float rounding
// boundary, which the fixed seed below avoids.
using LMat = std::array<std::array<long double, 4>, 4>;  // [row][column]
LMat lmul(const LMat& a, const LMat& b) {
  LMat r{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        r[i][j] += a[i][k] * b[k][j];
  return r;
}
LMat lidentity() {
  LMat m{};
  for (int i = 0; i < 4; ++i)
    m[i][i] = 1;
  return m;
}

TEST_F(CaseFileTest, GeneralTransformMatchesIndependentLongDoubleMath) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::string vertices;
  std::vector<std::array<float, 3>> pos;
  for (int i = 0; i < 30; ++i) {
    pos.push_back({u(rng), u(rng), u(rng)});
    char buf[200];
    std::snprintf(buf, sizeof buf, R"(%s{"position": ["%a", "%a", "%a"]})", i ? ", " : "",
                  double(pos.back()[0]), double(pos.back()[1]), double(pos.back()[2]));
    vertices += buf;
  }
  const Case c = load_text(R"({"description": "d",
    "transform": {
      "model": [{"translate": [0.3125, -0.25, -4]}, {"rotate": {"degrees": 30, "axis": [1, 2, 3]}},
                {"scale": [1.5, 1.25, 0.75]}],
      "view": [{"rotate": {"degrees": -10, "axis": [1, 0, 0]}}],
      "projection": {"perspective": {"fovy_degrees": 60, "aspect": 1.25, "near": 0.5, "far": 100}}},
    "vertices": [)" + vertices +
                           "]}");

  const long double pi = 3.141592653589793238462643383279502884L;
  auto rotation = [&](long double deg, long double x, long double y, long double z) {
    const long double n = std::sqrt(x * x + y * y + z * z);
    x /= n, y /= n, z /= n;
    const long double a = deg * pi / 180, cs = std::cos(a), sn = std::sin(a), t = 1 - cs;
    LMat r = lidentity();
    r[0] = {t * x * x + cs, t * x * y - sn * z, t * x * z + sn * y, 0};
    r[1] = {t * x * y + sn * z, t * y * y + cs, t * y * z - sn * x, 0};
    r[2] = {t * x * z - sn * y, t * y * z + sn * x, t * z * z + cs, 0};
    return r;
  };
  LMat tr = lidentity();
  tr[0][3] = 0.3125L, tr[1][3] = -0.25L, tr[2][3] = -4;
  LMat sc = lidentity();
  sc[0][0] = 1.5L, sc[1][1] = 1.25L, sc[2][2] = 0.75L;
  const long double f = 1 / std::tan(30 * pi / 180), n = 0.5L, fa = 100;
  LMat p{};
  p[0][0] = f / 1.25L, p[1][1] = f, p[2][2] = (fa + n) / (n - fa), p[2][3] = 2 * fa * n / (n - fa);
  p[3][2] = -1;
  const LMat mvp = lmul(p, lmul(rotation(-10, 1, 0, 0), lmul(tr, lmul(rotation(30, 1, 2, 3), sc))));
  for (size_t i = 0; i < pos.size(); ++i) {
    const long double v[4] = {pos[i][0], pos[i][1], pos[i][2], 1};
    for (int r = 0; r < 4; ++r) {
      long double x = 0;
      for (int k = 0; k < 4; ++k)
        x += mvp[r][k] * v[k];
      EXPECT_EQ(bits(c.vertices[i].clip[r]), bits(static_cast<float>(x)))
          << "vertex " << i << " component " << r << ": " << c.vertices[i].clip[r] << " vs "
          << static_cast<float>(x);
    }
  }
}

TEST(SinCosDegrees, ExactAtRightAnglesAndSymmetric) {
  for (double deg : {0.0, 90.0, 180.0, 270.0, 360.0, -90.0, 450.0, 720.0, -540.0}) {
    double s, c;
    sincos_degrees(deg, s, c);
    const long k = std::lround(deg / 90.0);
    const int q = int(((k % 4) + 4) % 4);
    EXPECT_EQ(s, (q == 1 ? 1.0 : q == 3 ? -1.0 : 0.0)) << deg;
    EXPECT_EQ(c, (q == 0 ? 1.0 : q == 2 ? -1.0 : 0.0)) << deg;
  }
  double s, c;
  sincos_degrees(45, s, c);
  EXPECT_EQ(s, c);
  EXPECT_EQ(s / c, 1.0);  // tan 45 exactly, so fovy_degrees 90 gives an exact projection
  sincos_degrees(-45, s, c);
  EXPECT_EQ(-s, c);
}

// In the first quadrant, against long double. The reference gets the same exact reduction to
// [0, 45] degrees as the implementation (cos x = sin(90 - x)), so that its own argument rounding,
// ~1e-19 absolute, stays far below an ulp of the result.
TEST(SinCosDegrees, WithinOneUlpOfLongDoubleInTheFirstQuadrant) {
  const long double pi = 3.141592653589793238462643383279502884L;
  auto ulp = [](double x) { return std::nextafter(std::fabs(x), 2.0) - std::fabs(x); };
  for (double deg = 0; deg <= 90.0; deg += 0.0390625) {
    double s, c;
    sincos_degrees(deg, s, c);
    const long double a = static_cast<long double>(deg) * pi / 180;
    const long double b = static_cast<long double>(90.0 - deg) * pi / 180;  // 90 - deg is exact
    const double ts = static_cast<double>(deg <= 45 ? std::sin(a) : std::cos(b));
    const double tc = static_cast<double>(deg <= 45 ? std::cos(a) : std::sin(b));
    EXPECT_LE(std::fabs(s - ts), ulp(ts)) << deg;
    EXPECT_LE(std::fabs(c - tc), ulp(tc)) << deg;
  }
}

// Outside it, the reduction in degrees is exact: the symmetries hold bit for bit.
TEST(SinCosDegrees, ExactReductionToTheFirstQuadrant) {
  for (double deg = 0; deg < 90.0; deg += 0.3671875) {
    double s, c;
    sincos_degrees(deg, s, c);
    for (int k = -8; k <= 8; ++k) {
      double sk, ck;
      sincos_degrees(deg + 90.0 * k, sk, ck);
      const int q = ((k % 4) + 4) % 4;
      const double want_s[4] = {s, c, -s, -c}, want_c[4] = {c, -s, -c, s};
      EXPECT_EQ(sk, want_s[q]) << deg << " + 90*" << k;
      EXPECT_EQ(ck, want_c[q]) << deg << " + 90*" << k;
    }
    double sn, cn;
    sincos_degrees(-deg, sn, cn);
    EXPECT_EQ(sn, -s) << deg;
    EXPECT_EQ(cn, c) << deg;
  }
}

}  // namespace
}  // namespace glrc::casefile::test
