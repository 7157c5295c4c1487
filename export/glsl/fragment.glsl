//@ The shader_test's fragment shader (export/shader_test.cpp fills it; export/text_template.hpp
//@ says how; shader_test.hpp has the derivation). Per fragment: NaN or Inf in any channel is
//@ verdict 1, a value outside the range stated for its (pixel, triangle) verdict 2; it counts the
//@ pixel's fragments and keeps max((triangle + 1) * 4 + verdict) with atomics. resolve 1 writes
//@ each pixel's (fragments, kept triangle or -1, verdict, 1) for the probes.
//@ Flags: depth_test (the case's; the count is then a draw of its own without it), culled (the
//@ case culls some triangles: discarded here), free_spans (pixels whose kept fragment's values
//@ are judged only at listed pairs), checks (pairs whose values are checked against ranges),
//@ depth_clamp (GL_DEPTH_CLAMP: the depth judged is gl_FragCoord.z clamped to [0, 1]).
#version 330 core
#extension GL_ARB_shader_storage_buffer_object : require
//@if depth_test
#extension GL_ARB_shader_image_load_store : require
// Only fragments that pass the depth test run in the case's draw (and are kept).
layout(early_fragment_tests) in;
//@end
@VARYINGS@
flat in int v_triangle;
//@if depth_test
uniform int resolve;  // 0: the case's draw; 1: the resolve draw; 2: the count, no depth test
//@else
uniform int resolve;  // 0: the case's draw; 1: the resolve draw
//@end
out vec4 colour;
layout(std430, binding = 0) buffer Pixels {
  uint fragments[@PIXELS@];  // per pixel, y * WIDTH + x
  uint kept[@PIXELS@];  // max((triangle + 1) * 4 + verdict)
};
const int WIDTH = @WIDTH@;
const int CHANNELS = @CHANNELS@;  // depth@CHANNEL_NAMES@
//@if free_spans
// Pixels where GL may keep a fragment whose values the reference does not judge (an edge
// within the specification's freedom, or no value determined): spans [start, end) of y * WIDTH + x.
const int FREE_SPANS = @FREE_SPANS@;
const int FREE[@FREE_COUNT@] = int[](@FREE@
bool coverage_free(int i) {
  int lo = 0, hi = FREE_SPANS;  // the first span ending after i
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (FREE[2 * mid + 1] <= i) lo = mid + 1; else hi = mid;
  }
  return lo < FREE_SPANS && FREE[2 * lo] <= i;
}
//@end
//@if checks
// Stated ranges: where triangle t is kept at pixel (x, y), each channel within [lo, hi]
// (lo > hi: the specification determines no value there, not judged).
const int CHECKS = @CHECKS@;
const ivec3 CHECK_AT[CHECKS] = ivec3[](@CHECK_AT@);
const vec2 RANGE[CHECKS * CHANNELS] = vec2[](@RANGES@
//@end
bool non_finite(float v) { return isnan(v) || isinf(v); }
void main() {
  ivec2 at = @PIXEL@;
  int i = at.y * WIDTH + at.x;
  if (resolve == 1) {
    colour = vec4(float(fragments[i]), float(int(kept[i] / 4u) - 1), float(kept[i] % 4u), 1.0);
    return;
  }
//@if depth_clamp
  // GL_DEPTH_CLAMP: the depth buffer, which the harness reads, takes z_w clamped to the depth
  // range [0, 1]; gl_FragCoord.z need not be. NaN stays NaN.
  float depth = isnan(gl_FragCoord.z) ? gl_FragCoord.z : clamp(gl_FragCoord.z, 0.0, 1.0);
//@else
  float depth = gl_FragCoord.z;
//@end
  float v[CHANNELS] = float[](depth@CHANNEL_VALUES@);
//@if culled
  // cull @CULL@ with front_face @FRONT_FACE@: no fragment of a @CULLED_KIND@ (shader_runner has no glCullFace)
  if (@CULLED_CONDITION@) discard;
//@end
//@if depth_test
  if (resolve == 2) {  // the count: every fragment, no depth test
    atomicAdd(fragments[i], 1u);
    colour = vec4(0.0);
    return;
  }
//@end
  uint verdict = 0u;
  bool listed = false;
//@if checks
  for (int n = 0; n < CHECKS; ++n) {
    if (CHECK_AT[n] != ivec3(at, v_triangle)) continue;
    listed = true;
    for (int k = 0; k < CHANNELS; ++k) {
      vec2 range = RANGE[n * CHANNELS + k];
      if (range.x > range.y) continue;
      if (non_finite(v[k])) verdict |= 1u;
      else if (v[k] < range.x || v[k] > range.y) verdict |= 2u;
    }
  }
//@end
//@if free_spans
  if (!listed && !coverage_free(i))
//@else
  if (!listed)
//@end
    for (int k = 0; k < CHANNELS; ++k)
      if (non_finite(v[k])) verdict |= 1u;
//@if !depth_test
  atomicAdd(fragments[i], 1u);
//@end
  atomicMax(kept[i], uint(v_triangle + 1) * 4u + verdict);
  colour = vec4(0.0);
}
