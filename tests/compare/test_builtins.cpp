// gl_FragCoord.w judged from both sides (docs/allowance.md, "Built-ins"): an implementation
// that evaluates 1/w_c in float, a few roundings from the exact value, passes; one that
// interpolates w_c linearly in window space and inverts it (a perspective-incorrect 1/w, wrong
// wherever the w_i differ) fails, as one that writes w_c itself does.
#include <gtest/gtest.h>

#include <cmath>

#include "compare/compare.hpp"
#include "ref/reference.hpp"

namespace glrc::compare {
namespace {

Case perspective() {
  Case c;
  c.name = "frag_coord_w";
  c.fb_width = 48, c.fb_height = 40;
  c.viewport = {0, 0, 48, 40};
  c.varyings = {builtin_varying(Builtin::frag_coord)};
  c.vertices = {{{-0.9f, -0.8f, -0.5f, 1}, {0, 0, 0, 0}},
                {{1.6f, -1.2f, 0.25f, 2}, {0, 0, 0, 0}},
                {{-0.5f, 3.0f, 1.5f, 4}, {0, 0, 0, 0}}};
  c.triangles = {{0, 1, 2}};
  return c;
}

TEST(Builtins, FragCoordWFromWInterpolatedLinearlyFails) {
  const Case c = perspective();
  const Expectation e = ref::render(c, Model{}, 8);
  double x[3], y[3], w[3];
  for (int i = 0; i < 3; ++i) {
    const auto& p = c.vertices[size_t(i)].clip;
    x[i] = (p[0] / p[3] + 1) * c.fb_width / 2, y[i] = (p[1] / p[3] + 1) * c.fb_height / 2;
    w[i] = p[3];
  }
  const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  Frame rounded = e.frame, linear_w = e.frame, not_inverted = e.frame;
  std::vector<float>& wr = rounded.components[3];
  for (size_t i = 0; i < e.frame.pixel_count(); ++i) {
    if (e.frame.primitive[i] < 0) continue;
    const double qx = double(i % size_t(c.fb_width)) + 0.5,
                 qy = double(i / size_t(c.fb_width)) + 0.5;
    double interpolated = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      interpolated += ((x[a] - qx) * (y[b] - qy) - (x[b] - qx) * (y[a] - qy)) / area * w[k];
    }
    wr[i] = std::nextafter(std::nextafter(wr[i], 1.0f), 1.0f);  // two ulps off
    linear_w.components[3][i] = float(1 / interpolated);
    not_inverted.components[3][i] = 1 / e.frame.components[3][i];
  }
  const Tolerance spec;
  EXPECT_EQ(compare(c, e, rounded, spec).status, Status::pass);
  const CaseResult linear = compare(c, e, linear_w, spec);
  EXPECT_EQ(linear.status, Status::fail);
  EXPECT_NE(linear.message.find("gl_FragCoord.w"), std::string::npos) << linear.message;
  EXPECT_EQ(compare(c, e, not_inverted, spec).status, Status::fail);
}

}  // namespace
}  // namespace glrc::compare
