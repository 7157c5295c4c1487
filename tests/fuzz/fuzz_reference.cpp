// libFuzzer target: the reference and the comparator on small cases built straight from the
// fuzzer's bytes (no JSON: every byte decides geometry, values or state, so the fuzzer spends
// its time in ref/ and compare/, not in the parser). What must hold for any input the loader
// would accept (finite float32 clip coordinates and values):
//   - render() returns, with or without the allowance (no crash, no hang, no UB under the
//     sanitizers);
//   - every allowance of a covered pixel is a number >= 0 (never NaN: NaN is never a pass);
//   - the reference judged against itself never fails (it passes, or is outside the specified
//     range and skipped; or outside what GL specifies, where a covered pixel's own value is NaN
//     or Inf: compare::value_determined).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "compare/compare.hpp"
#include "core/case.hpp"
#include "ref/reference.hpp"

namespace {

using namespace glrc;

struct Bytes {
  const uint8_t* data;
  size_t size, at = 0;
  uint8_t byte() { return at < size ? data[at++] : 0; }
  // A finite float32 from four bytes; non-finite bit patterns become small integers, and a
  // quarter of the values are small integers anyway, so that exact ties and edges on pixel
  // centres (the hard cases) come up often.
  float number() {
    uint32_t bits = 0;
    for (int i = 0; i < 4; ++i)
      bits = bits << 8 | byte();
    float f;
    std::memcpy(&f, &bits, 4);
    if (!std::isfinite(f) || (bits & 3) == 0) return float(int(bits >> 24) - 128) / 16.0f;
    return f;
  }
};

void fail(const char* what) {
  std::fprintf(stderr, "fuzz_reference: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes in{data, size};
  Case c;
  c.name = "fuzz";
  c.fb_width = 1 + in.byte() % 24;
  c.fb_height = 1 + in.byte() % 24;
  c.viewport = {int(in.byte() % 5) - 2, int(in.byte() % 5) - 2, c.fb_width, c.fb_height};
  const uint8_t state = in.byte();
  c.cull = CullFace(state & 3);
  c.front_face = FrontFace(state >> 2 & 1);
  c.provoking = ProvokingVertex(state >> 3 & 1);
  c.depth_func = DepthFunc(state >> 4 & 1);
  if (state >> 5 & 1) c.depth_near = in.number(), c.depth_far = in.number();
  c.depth_near = std::clamp(c.depth_near, 0.0f, 1.0f);
  c.depth_far = std::clamp(c.depth_far, 0.0f, 1.0f);
  const int varyings = 1 + in.byte() % 2;
  for (int k = 0; k < varyings; ++k)
    c.varyings.push_back(
        {"v" + std::to_string(k), 1 + in.byte() % 2, Interpolation(in.byte() % 3)});
  const size_t vertices = 3 + in.byte() % 7;
  for (size_t i = 0; i < vertices; ++i) {
    Vertex v;
    for (float& x : v.clip)
      x = in.number();
    v.values.resize(size_t(c.component_count()));
    for (float& x : v.values)
      x = in.number();
    c.vertices.push_back(v);
  }
  const size_t triangles = 1 + in.byte() % 4;
  for (size_t t = 0; t < triangles; ++t)
    c.triangles.push_back({uint32_t(in.byte() % vertices), uint32_t(in.byte() % vertices),
                           uint32_t(in.byte() % vertices)});

  const Model m{int(in.byte() % 2) * 8, Planes::unsnapped, TieBreak::bottom_left};
  (void)ref::render(c, m);  // no allowance: the path `digest` takes
  const Expectation r = ref::render(c, m, 8);
  for (size_t i = 0; i < r.frame.pixel_count(); ++i) {
    if (r.frame.primitive[i] < 0) continue;
    if (!(r.allowed.depth[i] >= 0)) fail("depth allowance NaN or negative");
    for (const auto& component : r.allowed.components)
      if (!(component[i] >= 0)) fail("value allowance NaN or negative");
  }
  Tolerance tolerance;
  tolerance.subpixel_bits = 8;
  const CaseResult self = compare::compare(c, r, r.frame, tolerance);
  if (self.status == Status::fail) {
    std::fprintf(stderr, "fuzz_reference: %s\n", self.message.c_str());
    fail("the reference fails against itself");
  }
  return 0;
}
