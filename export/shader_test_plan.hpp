// What a shader_test judges where (shader_test.hpp has the derivation): per pixel, what its
// probes decide and where coverage is free; the (pixel, triangle) pairs `run` judges, with their
// expected values and allowances; and which of them the fragment shader checks against ranges.
// All of it read from the expectation with compare/'s rules (the verdict table, the channels'
// allowances): nothing here restates one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"

namespace glrc::reproducer {

// What the probes require at one pixel, as compare/ judges it (the verdict table: its label of
// each thing GL may do there). Traces are not checked by a shader_test (shader_test.hpp says
// why): a trace is taken as admitted.
struct Decided {
  bool fragments = false;  // GL's fragment count must be the reference's
  bool primitive = false;  // GL's kept triangle must be the reference's
};

// One (pixel, triangle) pair whose values `run` judges: the reference's fragment or a candidate
// of the depth test, with the expected value and allowance of each channel, by slot.
struct ValuePair {
  size_t pixel = 0;
  int32_t primitive = 0;
  std::vector<float> expected;
  std::vector<double> allowed;
  int tier = 0;  // the order in which pairs are chosen when not all fit
};

struct ShaderTestPlan {
  std::vector<Decided> decided;  // per pixel
  std::vector<ValuePair> pairs;  // by pixel: the reference's fragment, then the candidates
  // The pairs the fragment shader checks against ranges, indices into `pairs` sorted by (pixel,
  // triangle): every pair where at most shader_test_value_checks fit, else that many, first
  // where coverage is free, then on triangles the clipper cuts, then at edges, then spread.
  std::vector<size_t> checks;
  // Spans [start, end) of pixel indices (y * width + x) where GL may keep a fragment whose
  // values the reference does not judge (coverage free), or the reference determines no value.
  std::vector<std::pair<size_t, size_t>> free_spans;
};

// The plan of case c's shader_test, for an expectation of the case's shape (allowance per pixel
// under ToleranceMode::spec) and a tolerance other than exact.
ShaderTestPlan plan_shader_test(const Case& c, const Expectation& expected,
                                const Tolerance& tolerance);

// The smallest and largest float32 that `run` accepts for a finite reference e and allowance a
// >= 0 (GL's value finite and |g - e| <= a in double, compare/'s pixel_error): every float between
// them is accepted too, so a range check is the same judgement.
std::pair<float, float> accepted_range(float e, double a);

}  // namespace glrc::reproducer
