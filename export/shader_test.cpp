// A case as one piglit shader_test (shader_test.hpp): the case's draw with a fragment shader
// that judges and counts, a resolve draw, and probes of the verdict.
#include "export/shader_test.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <vector>

#include "compare/compare.hpp"
#include "core/text.hpp"
#include "export/coverage_verdict_table.hpp"
#include "export/expectation_shape.hpp"

namespace glrc::reproducer {
namespace {

// ---- Numbers as text that reads back as the same float32 ----

// Text assembled by appending (GCC 12 at -O3 reports a false -Wrestrict in operator+ on a
// string literal and a std::string).
template <typename... Parts>
std::string cat(const Parts&... parts) {
  std::string s;
  (s.append(std::string_view(parts)), ...);
  return s;
}

bool same_bits(float a, float b) {
  return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

// A decimal that shader_runner's parsers give back as `v` exactly: they call strtod and cast to
// float (strtof_hex for vertex data and probes), a double rounding that the shortest decimal can
// miss when it lies within 2^-53 of a midpoint between floats; each candidate is read back the
// same way, and "%.17g" of the float's double, which strtod reads exactly, always works.
std::string decimal(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v < 0 ? "-inf" : "inf";
  char text[64];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  if (ec == std::errc()) {
    std::string s(text, end);
    if (same_bits(float(std::strtod(s.c_str(), nullptr)), v)) return s;
  }
  std::snprintf(text, sizeof text, "%.9g", double(v));
  if (same_bits(float(std::strtod(text, nullptr)), v)) return text;
  std::snprintf(text, sizeof text, "%.17g", double(v));
  return text;
}

// A GLSL float literal of the finite float `v`: the shortest decimal strtof gives back (Mesa's
// GLSL lexer reads float literals with strtof), with a '.' or an exponent so that it is a float
// ("1.0", "-0.0", not the int literals "1" and "-0").
std::string glsl_float(float v) {
  char text[64];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  if (ec != std::errc()) throw std::logic_error("glsl_float: to_chars failed");
  std::string s(text, end);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// ---- What run judges, as ranges ----

// Whether `run` accepts the float g where the reference is e and the allowance a: GL's value
// must be finite and |g - e| <= a, both computed in double (compare/'s pixel_error).
bool accepted(float g, float e, double a) {
  return std::isfinite(g) && std::fabs(double(g) - double(e)) <= a;
}

// The smallest and largest float32 that `run` accepts for a finite reference e and allowance a
// >= 0: every float between them is accepted too, so a range check is the same judgement.
std::pair<float, float> accepted_range(float e, double a) {
  constexpr float kMax = std::numeric_limits<float>::max();
  auto clamp = [&](double x) { return float(std::clamp(x, -double(kMax), double(kMax))); };
  float lo = clamp(double(e) - a), hi = clamp(double(e) + a);
  // Rounding to float may have stepped one float too far or not far enough.
  while (!accepted(lo, e, a))
    lo = std::nextafter(lo, kMax);
  while (lo > -kMax && accepted(std::nextafter(lo, -kMax), e, a))
    lo = std::nextafter(lo, -kMax);
  while (!accepted(hi, e, a))
    hi = std::nextafter(hi, -kMax);
  while (hi < kMax && accepted(std::nextafter(hi, kMax), e, a))
    hi = std::nextafter(hi, kMax);
  return {lo, hi};
}

// ---- The case's states as shader_runner commands ----

// Which triangles the case culls, by their winding in window coordinates (GL_CCW front faces
// are the counter-clockwise ones, GL_CW front faces the clockwise ones).
enum class Culled { none, clockwise, counter_clockwise, all };
Culled culled(const Case& c) {
  switch (c.cull) {
    case CullFace::none:
      return Culled::none;
    case CullFace::front_and_back:
      return Culled::all;
    case CullFace::back:
      return c.front_face == FrontFace::ccw ? Culled::clockwise : Culled::counter_clockwise;
    case CullFace::front:
      return c.front_face == FrontFace::ccw ? Culled::counter_clockwise : Culled::clockwise;
  }
  return Culled::none;
}

// The GLSL condition under which a fragment belongs to a culled triangle: gl_FrontFacing is
// true for counter-clockwise triangles under GL's default GL_CCW, which shader_runner keeps.
const char* culled_condition(Culled culls) {
  switch (culls) {
    case Culled::none:
      return "false";
    case Culled::clockwise:
      return "!gl_FrontFacing";
    case Culled::counter_clockwise:
      return "gl_FrontFacing";
    case Culled::all:
      return "true";
  }
  return "false";
}

const char* glsl_type(int size) {
  static const char* const kTypes[] = {"float", "vec2", "vec3", "vec4"};
  return kTypes[std::clamp(size, 1, 4) - 1];
}

// A case file's qualifier names are GLSL's (core/case.hpp's Names<Interpolation>).
std::string_view glsl_qualifier(Interpolation i) {
  return name_of(i);
}

// Whether GL's clipper cuts triangle t: a vertex outside -w <= x, y, z <= w (w <= 0 included).
bool clipped(const Case& c, size_t t) {
  for (uint32_t v : c.triangles[t]) {
    const auto& p = c.vertices[v].clip;
    const float w = p[3];
    if (!(w > 0)) return true;
    for (int k = 0; k < 3; ++k)
      if (!(p[size_t(k)] >= -w && p[size_t(k)] <= w)) return true;
  }
  return false;
}

// `text` on one line: control characters as spaces.
std::string one_line(std::string_view text) {
  std::string t;
  for (const char ch : text)
    t += static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f ? ' ' : ch;
  return t;
}

// `text` as "# " comment lines of at most `width` characters, broken at spaces; control
// characters become spaces.
std::string comment_lines(std::string_view text, size_t width = 96) {
  return wrap_words(one_line(text), width, "# ");
}

// `text` for a GLSL comment: printable ASCII only (GLSL's character set), others as '?'.
std::string glsl_comment(std::string_view text) {
  std::string t;
  for (const char ch : text)
    t += ch >= 0x20 && ch < 0x7f ? ch : '?';
  return t;
}

// ---- The expectation, per pixel ----

// What the probes require at one pixel, as compare/ judges it (the verdict table: its label
// of each thing GL may do there). Traces are not checked here (the header says why): a trace is
// taken as admitted.
struct Decided {
  bool fragments = false;  // GL's fragment count must be the reference's
  bool primitive = false;  // GL's kept triangle must be the reference's
};

Decided decided(const Expectation& e, const CoverageVerdictTable& table, const Case& c, size_t i) {
  using Observation = compare::CoverageObservation;
  const uint8_t edges = e.edges[i];
  const auto fails = [&](Observation::Kept kept, Observation::Count count) {
    return table.fails(table.label(edges, {kept, count}, true));
  };
  const Frame& f = e.frame;
  Decided d;
  // The probes ask for the reference's count only where both fewer and more fragments fail (the
  // rules never fail one and pass the other); the count is taken without the depth test.
  d.fragments = table.counts() && fails(Observation::Kept::reference, Observation::Count::fewer) &&
                fails(Observation::Kept::reference, Observation::Count::more);
  // The probes cannot tell a candidate of the depth test from another triangle: the kept
  // triangle is the reference's to keep only where keeping either fails.
  d.primitive = fails(Observation::Kept::other, Observation::Count::same) &&
                fails(Observation::Kept::candidate, Observation::Count::same);
  // On the 24-bit depth buffer a fragment within its step of the clear value may be stored as
  // that value and fail the test against it, where the harness's 32-bit float depth keeps it.
  if (c.depth_func != DepthFunc::always && f.primitive[i] != Frame::kNoPrimitive &&
      std::fabs(f.depth[i] - c.depth_clear) <= 0x1p-23f)
    d.primitive = false;
  return d;
}

// One (pixel, triangle) pair whose values `run` judges: the reference's fragment or a candidate
// of the depth test, with the expected value and allowance of each channel (depth, components).
struct Pair {
  size_t pixel = 0;
  int32_t primitive = 0;
  std::vector<float> expected;
  std::vector<double> allowed;
  int tier = 0;  // the order in which pairs are chosen when not all fit
};

// Spread choice: `take` of `n` items, evenly spaced, in order.
std::vector<size_t> spread(size_t n, size_t take) {
  std::vector<size_t> chosen;
  if (take >= n) {
    for (size_t k = 0; k < n; ++k)
      chosen.push_back(k);
    return chosen;
  }
  for (size_t j = 0; j < take; ++j)
    chosen.push_back(j * n / take);
  return chosen;
}

// Rectangles (x, y, w, h) of pixels with equal expectation, covering exactly the pixels whose
// value is given: runs of each row, merged with identical runs of the rows above.
struct Rect {
  int x, y, w, h;
  std::pair<int, int> value;  // fragments, triangle
};
std::vector<Rect> rectangles(int width, int height,
                             const std::vector<std::optional<std::pair<int, int>>>& grid) {
  std::vector<Rect> done;
  std::map<std::tuple<int, int, std::pair<int, int>>, Rect> open;  // (x, w, value) -> rect
  for (int y = 0; y < height; ++y) {
    std::map<std::tuple<int, int, std::pair<int, int>>, Rect> next;
    for (int x = 0; x < width;) {
      const auto& v = grid[size_t(y) * size_t(width) + size_t(x)];
      if (!v) {
        ++x;
        continue;
      }
      int end = x + 1;
      while (end < width && grid[size_t(y) * size_t(width) + size_t(end)] == v)
        ++end;
      const auto key = std::make_tuple(x, end - x, *v);
      auto it = open.find(key);
      if (it != open.end()) {
        Rect r = it->second;
        ++r.h;
        next.emplace(key, r);
        open.erase(it);
      } else {
        next.emplace(key, Rect{x, y, end - x, 1, *v});
      }
      x = end;
    }
    for (auto& [key, r] : open)
      done.push_back(r);
    open = std::move(next);
  }
  for (auto& [key, r] : open)
    done.push_back(r);
  std::sort(done.begin(), done.end(),
            [](const Rect& a, const Rect& b) { return std::tie(a.y, a.x) < std::tie(b.y, b.x); });
  return done;
}

void check_shape(const Case& c, const Expectation& e, const Tolerance& t) {
  auto fail = [&](const std::string& why) {
    std::string message = "shader_test: case '";
    message += c.name;
    message += "': ";
    message += why;
    throw std::invalid_argument(message);
  };
  if (const std::string why = expectation_shape_error(c, e, t); !why.empty()) fail(why);
  for (const Varying& v : c.varyings)
    if (v.size < 1 || v.size > 4) fail("a varying has not 1 to 4 components");
}

std::string with_commas(size_t n) {
  const std::string digits = std::to_string(n);
  std::string s;
  for (size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) s += ',';
    s += digits[k];
  }
  return s;
}

}  // namespace

size_t shader_test_value_checks(int components) {
  const size_t channels = size_t(std::max(components, 0)) + 1;
  return std::max<size_t>(1, std::min(kMaxShaderTestValueChecks, kMaxShaderTestRanges / channels));
}

std::string shader_runner_command(const std::string& file) {
  std::string command = "PIGLIT_PLATFORM=surfaceless_egl shader_runner ";
  command += shell_word(file);
  command += " -auto -fbo";
  return command;
}

std::optional<std::string> shader_test_state_refusal(const Case& c) {
  if (c.depth_near != 0.0f || c.depth_far != 1.0f) {
    std::string why = "depth_range (near ";
    why += decimal(c.depth_near);
    why += ", far ";
    why += decimal(c.depth_far);
    why +=
        ") cannot be expressed in a shader_test: shader_runner has no glDepthRange command (only "
        "[0, 1])";
    return why;
  }
  if (culled(c) == Culled::all) {
    std::string why =
        "cull front_and_back cannot be expressed in a shader_test: shader_runner "
        "has no glCullFace command (its `enable` takes no GL_CULL_FACE), and a "
        "fragment shader that discards every fragment leaves the varyings unused, "
        "which the linker removes with their attributes (and shader_runner then "
        "refuses their vertex data)";
    return why;
  }
  if (c.cull != CullFace::none && c.depth_func != DepthFunc::always) {
    std::string why = "cull ";
    why += name_of(c.cull);
    why += " with depth_func ";
    why += name_of(c.depth_func);
    why +=
        " cannot be expressed in a shader_test: shader_runner has no "
        "glCullFace command (its `enable` takes no GL_CULL_FACE), and culling in the fragment "
        "shader cannot undo the depth writes of the early depth test that keeping only the "
        "depth test's winners needs";
    return why;
  }
  const size_t pixels = size_t(std::max(c.fb_width, 0)) * size_t(std::max(c.fb_height, 0));
  if (pixels > kMaxShaderTestPixels)
    return cat("a ", std::to_string(c.fb_width), "x", std::to_string(c.fb_height),
               " framebuffer; a shader_test takes at most ", with_commas(kMaxShaderTestPixels),
               " pixels: shrink the case first (glrefcheck fuzz --replay ...)");
  if (c.triangles.size() > kMaxShaderTestTriangles)
    return cat(with_commas(c.triangles.size()), " triangles; a shader_test takes at most ",
               with_commas(kMaxShaderTestTriangles),
               ": shrink the case first (glrefcheck fuzz --replay ...)");
  return std::nullopt;
}

std::optional<std::string> shader_test_refusal(const Case& c, const Expectation& expected,
                                               const Tolerance& tolerance) {
  if (auto why = shader_test_state_refusal(c)) return why;
  if (tolerance.mode == ToleranceMode::exact)
    return std::string(
        "exact tolerance (a driver model's bits) cannot be expressed in a shader_test, which "
        "checks ranges of values");
  if (c.depth_func != DepthFunc::always && c.depth_clear != 0.0f && c.depth_clear != 1.0f) {
    std::string why = "depth_clear ";
    why += decimal(c.depth_clear);
    why +=
        " with a depth test cannot be expressed in a shader_test: shader_runner's depth buffer has "
        "24 bits, which hold only 0 and 1 of the clear values exactly";
    return why;
  }
  if (c.depth_func != DepthFunc::always) {
    const compare::UlpTable ulps(c);
    const compare::ChannelAllowance depth(c, expected, tolerance, Channel::depth());
    const Frame& f = expected.frame;
    for (size_t i = 0; i < f.pixel_count() && i < f.primitive.size(); ++i) {
      const int32_t p = f.primitive[i];
      if (p == Frame::kNoPrimitive) continue;
      if (depth.at(i, ulps.ulp(p, Channel::depth())) < 0x1p-24) {
        std::string why = "depth_func ";
        why += name_of(c.depth_func);
        why += " with a depth allowance of ";
        char number[32];
        std::snprintf(number, sizeof number, "%.3g", depth.at(i, ulps.ulp(p, Channel::depth())));
        why += number;
        why += cat(" at pixel (", std::to_string(i % size_t(f.width)), ", ",
                   std::to_string(i / size_t(f.width)), ")");
        why +=
            " cannot be expressed in a shader_test: shader_runner's depth buffer has 24 bits, "
            "whose step 2^-24 could decide the depth test there";
        return why;
      }
    }
  }
  return std::nullopt;
}

ShaderTest shader_test(const Case& c, const Expectation& expected, const Tolerance& tolerance,
                       const ShaderTestSetup& setup) {
  if (auto why = shader_test_refusal(c, expected, tolerance)) {
    std::string message = "shader_test: case '";
    message += c.name;
    message += "': ";
    message += *why;
    throw std::invalid_argument(message);
  }
  check_shape(c, expected, tolerance);
  const Frame& f = expected.frame;
  const int width = f.width, height = f.height;
  const size_t pixels = f.pixel_count();
  const int components = c.component_count();
  const int channels = components + 1;  // depth, then every component
  const std::vector<std::string> names = component_names(c);
  const bool depth_test = c.depth_func != DepthFunc::always;
  const size_t triangles = c.triangles.size();
  const Culled culls = culled(c);
  ShaderTest result;

  // ---- Per pixel: what the probes decide, and where values are free of the reference ----
  const compare::UlpTable ulps(c);
  std::vector<compare::ChannelAllowance> allowances;
  for (Channel ch : channels_of(components))
    allowances.emplace_back(c, expected, tolerance, ch);

  const CoverageVerdictTable verdicts(f.fragments.size() == pixels, tolerance);
  std::vector<Decided> decisions(pixels);
  // Where the kept fragment's values are judged only at listed pairs: GL may keep a fragment
  // the reference does not judge, or the reference determines no value.
  std::vector<bool> free(pixels, false);
  for (size_t i = 0; i < pixels; ++i) {
    decisions[i] = decided(expected, verdicts, c, i);
    // No value determined: a reference that is NaN or Inf, or an unbounded allowance (any
    // number passes there, and NaN or Inf is not judged either).
    bool determined = true;
    if (const int32_t p = f.primitive[i]; p != Frame::kNoPrimitive)
      for (Channel ch : channels_of(components))
        if (!std::isfinite(f.values(ch)[i]) ||
            !std::isfinite(allowances[ch.slot()].at(i, ulps.ulp(p, ch))))
          determined = false;
    free[i] = !decisions[i].primitive || !determined;
  }

  // ---- The (pixel, triangle) pairs run judges, and the ones checked against ranges ----
  std::vector<bool> clipped_triangle(triangles);
  for (size_t t = 0; t < triangles; ++t)
    clipped_triangle[t] = clipped(c, t);
  auto edge_pixel = [&](size_t i) {
    const int x = int(i % size_t(width)), y = int(i / size_t(width));
    const int32_t p = f.primitive[i];
    const int dx[] = {1, -1, 0, 0}, dy[] = {0, 0, 1, -1};
    for (int n = 0; n < 4; ++n) {
      const int nx = x + dx[n], ny = y + dy[n];
      if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
      if (f.primitive[f.index(nx, ny)] != p) return true;
    }
    return false;
  };
  std::vector<Pair> pairs;
  {
    auto candidate = expected.candidates.begin();
    for (size_t i = 0; i < pixels; ++i) {
      const int32_t p = f.primitive[i];
      if (p != Frame::kNoPrimitive) {
        const int tier = free[i] ? 0 : clipped_triangle[size_t(p)] ? 1 : edge_pixel(i) ? 2 : 3;
        Pair r{i, p, {}, {}, tier};
        for (Channel ch : channels_of(components)) {
          r.expected.push_back(f.values(ch)[i]);
          r.allowed.push_back(allowances[ch.slot()].at(i, ulps.ulp(p, ch)));
        }
        pairs.push_back(std::move(r));
      }
      for (; candidate != expected.candidates.end() && candidate->pixel == i; ++candidate) {
        const Candidate& o = *candidate;
        Pair r{i, o.primitive, {}, {}, 0};
        // What the comparator allows GL's fragment there when it is this candidate's.
        const compare::Judged as_candidate{true, &o};
        for (Channel ch : channels_of(components)) {
          r.expected.push_back(o.value(ch));
          r.allowed.push_back(
              as_candidate.allowed(allowances[ch.slot()], i, ulps.ulp(o.primitive, ch), ch));
        }
        pairs.push_back(std::move(r));
      }
    }
  }
  result.value_pairs = pairs.size();
  std::vector<const Pair*> checks;
  {
    std::array<std::vector<const Pair*>, 4> tiers;
    for (const Pair& r : pairs)
      tiers[size_t(r.tier)].push_back(&r);
    std::array<std::vector<bool>, 4> taken;
    for (size_t t = 0; t < 4; ++t)
      taken[t].assign(tiers[t].size(), false);
    size_t budget = shader_test_value_checks(components);
    // First round: free pixels take at most half, so that a large unstable region does not
    // crowd out the clipped triangles; second round: what is left, in the same order.
    for (int round = 0; round < 2; ++round)
      for (size_t t = 0; t < 4 && budget > 0; ++t) {
        std::vector<size_t> open;
        for (size_t k = 0; k < tiers[t].size(); ++k)
          if (!taken[t][k]) open.push_back(k);
        const size_t take =
            std::min(open.size(), round == 0 && t == 0 ? std::min(budget, budget / 2 + 1) : budget);
        for (size_t k : spread(open.size(), take)) {
          taken[t][open[k]] = true;
          checks.push_back(tiers[t][open[k]]);
        }
        budget -= take;
      }
    std::sort(checks.begin(), checks.end(), [](const Pair* a, const Pair* b) {
      return std::tie(a->pixel, a->primitive) < std::tie(b->pixel, b->primitive);
    });
  }
  result.value_checks = checks.size();

  // Spans [start, end) of pixel indices (y * width + x) where coverage is free.
  std::vector<std::pair<size_t, size_t>> free_spans;
  for (size_t i = 0; i < pixels; ++i) {
    if (!free[i]) continue;
    if (!free_spans.empty() && free_spans.back().second == i)
      ++free_spans.back().second;
    else
      free_spans.emplace_back(i, i + 1);
  }

  // ---- The header ----
  std::string out;
  out.reserve(65536 + triangles * 3 * size_t(4 + components) * 16);
  out += cat(kShaderTestSignature, " of case ", one_line(c.name), "\n#\n");
  if (!c.description.empty()) {
    out += comment_lines(c.description);
    out += "#\n";
  }
  out += cat("# Written by: ", one_line(setup.exported_by), "\n#\n");
  {
    std::string what =
        "It draws this one case on GL as glrefcheck's GL harness draws it and checks it "
        "against glrefcheck's exact reference of model ";
    what += setup.model;
    what += ", under ";
    if (tolerance.mode == ToleranceMode::spec) {
      what +=
          "the specification's allowance for an implementation that reports GL_SUBPIXEL_BITS = ";
      what += std::to_string(tolerance.subpixel_bits);
      what += " (it must be what the driver reports: llvmpipe 8, softpipe 4).";
    } else {
      char number[128];
      std::snprintf(number, sizeof number, "%.9g ULPs of each attribute's scale, depth %.9g",
                    tolerance.varying_ulps, tolerance.depth_ulps);
      what += "fixed thresholds (";
      what += number;
      what += " ULPs of 1.0, flat values 0).";
    }
    out += comment_lines(what);
  }
  out += "#\n";
  const std::string file = setup.file_name.empty() ? cat(c.name, ".shader_test") : setup.file_name;
  out += "#   Run: ";
  out += shader_runner_command(file);
  out += "\n";
  out +=
      "#        (GALLIUM_DRIVER=softpipe picks Mesa's driver; a pass prints PIGLIT: {\"result\": "
      "\"pass\" })\n";
  out += "#\n";
  out += comment_lines(
      "How: the case is drawn (de-indexed, each triangle's index as a flat int), and its "
      "fragment shader counts each pixel's fragments and keeps the last one's triangle and "
      "verdict (atomics on a storage buffer); with a depth test it is drawn twice, first "
      "without the depth test only to count every fragment (a count through the depth test "
      "would depend on which of two fragments of close depths passes it, which is free), then "
      "with it only to keep the winners. The verdict is 1 for NaN or Inf in depth "
      "(gl_FragCoord.z) or any component, 2 for a value outside the range [lo, hi] stated for "
      "that pixel and triangle (the float32 values within the allowance of the exact value). A "
      "resolve draw then writes, per pixel, (fragments, kept triangle or -1, verdict, 1) into "
      "an RGBA32F texture, and the probes read it: the verdict must be 0 everywhere, and the "
      "fragments and the triangle must be the reference's wherever the specification decides "
      "them (away from the edge bits' freedom; a gap or double hit on a shared edge fails). "
      "Pixels are in window coordinates, (x, y) from the bottom left.");
  {
    std::string scope = "Values are checked against their ranges at ";
    scope += with_commas(checks.size());
    scope += " of the ";
    scope += with_commas(pairs.size());
    scope += " (pixel, triangle) pairs `glrefcheck run` judges";
    scope += checks.size() < pairs.size()
                 ? " (first where coverage is free, then on clipped triangles, then at edges, "
                   "then spread; the C reproducer, --format c, judges them all), and for NaN "
                   "and Inf everywhere."
                 : " (all of them), and for NaN and Inf everywhere.";
    out += "#\n";
    out += comment_lines(scope);
  }
  if (const std::optional<std::string> outside = outside_specified_range(c)) {
    std::string note = "Note: outside GL's specified range (";
    note += *outside;
    note += "): glrefcheck run reports a failure of this case as a skip.";
    out += "#\n";
    out += comment_lines(note);
  }
  if (culls != Culled::none) {
    out += "#\n";
    out += comment_lines(
        "Culling: shader_runner has no glCullFace or glFrontFace command, so the fragment shader "
        "discards the fragments of the triangles the case culls, by gl_FrontFacing. That draws "
        "what culling draws, but does not exercise the driver's culling itself.");
  }
  if (depth_test) {
    out += "#\n";
    out += comment_lines(
        "The depth test runs on shader_runner's 24-bit depth buffer (the harness's is 32-bit "
        "float); every covered pixel's depth allowance is at least its step, 2^-24.");
  }

  // ---- [require] ----
  const bool viewport_set = c.viewport.x != 0 || c.viewport.y != 0 || c.viewport.width != width ||
                            c.viewport.height != height;
  out += "\n[require]\nGL CORE >= 3.3\nGLSL >= 3.30\n";
  out += "GL_ARB_shader_storage_buffer_object\nGL_ARB_texture_storage\n";
  if (depth_test) out += "GL_ARB_shader_image_load_store\n";
  if (viewport_set) out += "GL_ARB_viewport_array\n";
  if (depth_test) out += "depthbuffer\n";
  out += cat("SIZE ", std::to_string(width), " ", std::to_string(height), "\n");

  // ---- [vertex shader]: the harness's, and the triangle's index ----
  out += "\n[vertex shader]\n#version 330 core\n";
  out += "layout(location = 0) in vec4 a_clip;\n";
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    const Varying& v = c.varyings[k];
    const std::string n = std::to_string(k);
    out += cat("layout(location = ", std::to_string(k + 1), ") in ", glsl_type(v.size), " a", n,
               ";\n");
    out += cat(glsl_qualifier(v.interpolation), " out ", glsl_type(v.size), " v", n, ";\n");
  }
  out += cat("layout(location = ", std::to_string(c.varyings.size() + 1), ") in int a_triangle;\n");
  out += "flat out int v_triangle;\n";
  out += "void main() {\n  gl_Position = a_clip;\n";
  for (size_t k = 0; k < c.varyings.size(); ++k)
    out += cat("  v", std::to_string(k), " = a", std::to_string(k), ";\n");
  out += "  v_triangle = a_triangle;\n}\n";

  // ---- [fragment shader]: the verdict ----
  out += "\n[fragment shader]\n#version 330 core\n";
  out += "#extension GL_ARB_shader_storage_buffer_object : require\n";
  if (depth_test) {
    out += "#extension GL_ARB_shader_image_load_store : require\n";
    out += "// Only fragments that pass the depth test run in the case's draw (and are kept).\n";
    out += "layout(early_fragment_tests) in;\n";
  }
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    const Varying& v = c.varyings[k];
    out += cat(glsl_qualifier(v.interpolation), " in ", glsl_type(v.size), " v", std::to_string(k),
               ";  // ", glsl_comment(v.name), "\n");
  }
  out += "flat in int v_triangle;\n";
  out += depth_test ? "uniform int resolve;  // 0: the case's draw; 1: the resolve draw; 2: the "
                      "count, no depth test\n"
                    : "uniform int resolve;  // 0: the case's draw; 1: the resolve draw\n";
  out += "out vec4 colour;\n";
  const std::string pixel_count = std::to_string(pixels);
  out += "layout(std430, binding = 0) buffer Pixels {\n";
  out += cat("  uint fragments[", pixel_count, "];  // per pixel, y * WIDTH + x\n");
  out += cat("  uint kept[", pixel_count, "];  // max((triangle + 1) * 4 + verdict)\n");
  out += "};\n";
  out += cat("const int WIDTH = ", std::to_string(width), ";\n");
  out += cat("const int CHANNELS = ", std::to_string(channels), ";  // depth");
  for (const std::string& n : names)
    out += cat(", ", glsl_comment(n));
  out += "\n";
  if (!free_spans.empty()) {
    out +=
        "// Pixels where GL may keep a fragment whose values the reference does not judge (an "
        "edge\n// within the specification's freedom, or no value determined): spans [start, "
        "end) of y * WIDTH + x.\n";
    out += cat("const int FREE_SPANS = ", std::to_string(free_spans.size()), ";\n");
    out += cat("const int FREE[", std::to_string(2 * free_spans.size()), "] = int[](");
    std::string line;
    for (size_t s = 0; s < free_spans.size(); ++s) {
      const std::string item =
          cat(std::to_string(free_spans[s].first), ", ", std::to_string(free_spans[s].second),
              s + 1 < free_spans.size() ? "," : ");");
      if (!line.empty() && line.size() + 1 + item.size() > 96) {
        out += cat("\n    ", line);
        line.clear();
      }
      if (!line.empty()) line += ' ';
      line += item;
    }
    out += cat("\n    ", line, "\n");
    out +=
        "bool coverage_free(int i) {\n"
        "  int lo = 0, hi = FREE_SPANS;  // the first span ending after i\n"
        "  while (lo < hi) {\n"
        "    int mid = (lo + hi) / 2;\n"
        "    if (FREE[2 * mid + 1] <= i) lo = mid + 1; else hi = mid;\n"
        "  }\n"
        "  return lo < FREE_SPANS && FREE[2 * lo] <= i;\n"
        "}\n";
  }
  if (!checks.empty()) {
    out +=
        "// Stated ranges: where triangle t is kept at pixel (x, y), each channel within [lo, "
        "hi]\n// (lo > hi: the specification determines no value there, not judged).\n";
    out += cat("const int CHECKS = ", std::to_string(checks.size()), ";\n");
    out += "const ivec3 CHECK_AT[CHECKS] = ivec3[](";
    for (size_t n = 0; n < checks.size(); ++n) {
      const Pair& r = *checks[n];
      out += n % 6 == 0 ? "\n    " : " ";
      out += cat("ivec3(", std::to_string(r.pixel % size_t(width)), ", ",
                 std::to_string(r.pixel / size_t(width)), ", ", std::to_string(r.primitive), ")");
      if (n + 1 < checks.size()) out += ",";
    }
    out += ");\n";
    out += "const vec2 RANGE[CHECKS * CHANNELS] = vec2[](";
    for (size_t n = 0; n < checks.size(); ++n) {
      const Pair& r = *checks[n];
      out += "\n    ";
      for (int k = 0; k < channels; ++k) {
        const float e = r.expected[size_t(k)];
        const double a = r.allowed[size_t(k)];
        float lo = 1, hi = 0;
        if (std::isfinite(e) && std::isfinite(a) && a >= 0) std::tie(lo, hi) = accepted_range(e, a);
        out += cat(k > 0 ? ", " : "", "vec2(", glsl_float(lo), ", ", glsl_float(hi), ")");
      }
      // The pair and the exact values, for people.
      out += cat(n + 1 < checks.size() ? ",  // (" : ");  // (",
                 std::to_string(r.pixel % size_t(width)), ", ",
                 std::to_string(r.pixel / size_t(width)), ") t ", std::to_string(r.primitive), ": ",
                 decimal(r.expected[0]));
      for (int k = 1; k < channels; ++k)
        out += cat(", ", decimal(r.expected[size_t(k)]));
    }
    out += "\n";
  }
  out += "bool non_finite(float v) { return isnan(v) || isinf(v); }\n";
  out += "void main() {\n";
  out += "  ivec2 at = ivec2(gl_FragCoord.xy);\n";
  out += "  int i = at.y * WIDTH + at.x;\n";
  out += "  if (resolve == 1) {\n";
  out +=
      "    colour = vec4(float(fragments[i]), float(int(kept[i] / 4u) - 1), float(kept[i] % 4u), "
      "1.0);\n";
  out += "    return;\n  }\n";
  out += "  float v[CHANNELS] = float[](gl_FragCoord.z";
  for (size_t k = 0; k < c.varyings.size(); ++k) {
    const int size = c.varyings[k].size;
    const std::string n = cat("v", std::to_string(k));
    if (size == 1) {
      out += cat(", ", n);
    } else {
      for (int j = 0; j < size; ++j) {
        out += cat(", ", n, ".");
        out += "xyzw"[j];
      }
    }
  }
  out += ");\n";
  if (culls != Culled::none) {
    out += cat("  // cull ", name_of(c.cull), " with front_face ", name_of(c.front_face),
               ": no fragment of a ",
               culls == Culled::clockwise           ? "clockwise triangle"
               : culls == Culled::counter_clockwise ? "counter-clockwise triangle"
                                                    : "triangle",
               " (shader_runner has no glCullFace)\n");
    out += cat("  if (", culled_condition(culls), ") discard;\n");
  }
  if (depth_test) {
    out += "  if (resolve == 2) {  // the count: every fragment, no depth test\n";
    out += "    atomicAdd(fragments[i], 1u);\n";
    out += "    colour = vec4(0.0);\n";
    out += "    return;\n  }\n";
  }
  out += "  uint verdict = 0u;\n";
  if (!checks.empty()) {
    out += "  bool listed = false;\n";
    out += "  for (int n = 0; n < CHECKS; ++n) {\n";
    out += "    if (CHECK_AT[n] != ivec3(at, v_triangle)) continue;\n";
    out += "    listed = true;\n";
    out += "    for (int k = 0; k < CHANNELS; ++k) {\n";
    out += "      vec2 range = RANGE[n * CHANNELS + k];\n";
    out += "      if (range.x > range.y) continue;\n";
    out += "      if (non_finite(v[k])) verdict |= 1u;\n";
    out += "      else if (v[k] < range.x || v[k] > range.y) verdict |= 2u;\n";
    out += "    }\n  }\n";
  } else {
    out += "  bool listed = false;\n";
  }
  out += free_spans.empty() ? "  if (!listed)\n" : "  if (!listed && !coverage_free(i))\n";
  out += "    for (int k = 0; k < CHANNELS; ++k)\n";
  out += "      if (non_finite(v[k])) verdict |= 1u;\n";
  if (!depth_test) out += "  atomicAdd(fragments[i], 1u);\n";
  out += "  atomicMax(kept[i], uint(v_triangle + 1) * 4u + verdict);\n";
  out += "  colour = vec4(0.0);\n}\n";

  // ---- [vertex data]: every triangle's three vertices, then the resolve draw's two ----
  out += "\n[vertex data]\n";
  out += "a_clip/float/vec4";
  for (size_t k = 0; k < c.varyings.size(); ++k)
    out += cat(" a", std::to_string(k), "/float/", glsl_type(c.varyings[k].size));
  out += " a_triangle/int/int\n";
  for (size_t t = 0; t < triangles; ++t)
    for (uint32_t vi : c.triangles[t]) {
      const Vertex& v = c.vertices[vi];
      std::string row;
      for (float x : v.clip) {
        row += decimal(x);
        row += ' ';
      }
      for (float x : v.values) {
        row += ' ';
        row += decimal(x);
      }
      row += cat("  ", std::to_string(t), "\n");
      out += row;
    }
  {
    std::string zeros;
    for (int k = 0; k < components; ++k)
      zeros += " 0";
    const char* const corners[] = {"-1 -1", "1 -1", "1 1", "-1 -1", "1 1", "-1 1"};
    for (const char* corner : corners) {
      out += corner;
      out += " 0 1 ";
      out += zeros;
      out += "  -1\n";
    }
  }

  // ---- [test] ----
  out += "\n[test]\n";
  out += "# The case's states (the harness's depth test with GL_ALWAYS is no depth test here).\n";
  out += cat("ssbo 0 ", std::to_string(pixels * 8), "\n");
  if (viewport_set)
    out +=
        cat("viewport indexed 0 ", std::to_string(c.viewport.x), " ", std::to_string(c.viewport.y),
            " ", std::to_string(c.viewport.width), " ", std::to_string(c.viewport.height), "\n");
  if (c.provoking == ProvokingVertex::first) out += "provoking vertex first\n";
  const std::string draw_case =
      triangles > 0 ? cat("draw arrays GL_TRIANGLES 0 ", std::to_string(triangles * 3), "\n") : "";
  if (depth_test) {
    out +=
        "# Every fragment counted first, without the depth test; then the case's draw with it.\n";
    out += "uniform int resolve 2\n";
    out += draw_case;
    out += "uniform int resolve 0\n";
    out +=
        cat("clear depth ", c.depth_clear == 0.0f ? "0" : "1", "\nclear\nenable GL_DEPTH_TEST\n");
    std::string func(name_of(c.depth_func));  // GL's name is the case file's, upper case
    std::transform(func.begin(), func.end(), func.begin(),
                   [](char ch) { return char(ch - 'a' + 'A'); });
    out += cat("depthfunc GL_", func, "\n");
  }
  out += draw_case;
  out += "memory barrier GL_SHADER_STORAGE_BARRIER_BIT\n";
  out +=
      "\n# Resolve: per pixel (fragments, kept triangle or -1, verdict, 1) into an RGBA32F "
      "texture.\n";
  if (depth_test) out += "disable GL_DEPTH_TEST\n";
  if (viewport_set)
    out += cat("viewport indexed 0 0 0 ", std::to_string(width), " ", std::to_string(height), "\n");
  out += cat("texture storage 0 2D GL_RGBA32F (1 ", std::to_string(width), " ",
             std::to_string(height), ")\n");
  out += "fb tex 2d 0\n";
  out += "uniform int resolve 1\n";
  out += cat("draw arrays GL_TRIANGLES ", std::to_string(triangles * 3), " 6\n");

  out +=
      "\n# Values: the verdict (third) is 0 at every pixel: no NaN or Inf (1), nothing outside "
      "its range (2).\n";
  out += "tolerance 1e9 1e9 0.25 1e9\n";
  out += "probe all rgba 0 0 0 1\n";

  // Coverage: rectangles of equal expectation. Either in three groups by what is decided
  // (fragments and triangle, fragments only, triangle only), or as two grids (fragments where
  // decided, triangle where decided), whichever takes fewer probes: one triangle needs half as
  // many in groups, a mesh with pixel centres on its shared edges (where only the count is
  // decided) far fewer in grids.
  struct Group {
    const char* heading;
    const char* tolerance;
    std::vector<std::optional<std::pair<int, int>>> grid;
    std::vector<Rect> rects;
  };
  auto encode = [&](bool grids) {
    std::vector<Group> groups;
    if (grids) {
      groups.push_back(
          {"# Coverage: fragments (first channel) wherever the reference decides them "
           "(the others are not compared here).\n",
           "tolerance 0.25 1e9 1e9 0.25\n",
           {},
           {}});
      groups.push_back(
          {"# Kept triangle (second channel, -1: none) wherever the reference decides "
           "it (the others are not compared here).\n",
           "tolerance 1e9 0.25 1e9 0.25\n",
           {},
           {}});
    } else {
      groups.push_back(
          {"# Coverage: fragments (first) and kept triangle (second, -1: none) where "
           "the reference decides both.\n",
           "tolerance 0.25 0.25 1e9 0.25\n",
           {},
           {}});
      groups.push_back(
          {"# Fragments only, where the kept triangle is free (an edge within the "
           "specification's freedom).\n",
           "tolerance 0.25 1e9 1e9 0.25\n",
           {},
           {}});
      groups.push_back(
          {"# Kept triangle only, where the fragment count is free (the snapping "
           "band of an outer edge).\n",
           "tolerance 1e9 0.25 1e9 0.25\n",
           {},
           {}});
    }
    for (Group& g : groups)
      g.grid.assign(pixels, std::nullopt);
    for (size_t i = 0; i < pixels; ++i) {
      const Decided d = decisions[i];
      const int count = f.fragments.empty() ? 0 : int(f.fragments[i]), triangle = f.primitive[i];
      if (grids) {
        if (d.fragments) groups[0].grid[i] = std::pair{count, 0};
        if (d.primitive) groups[1].grid[i] = std::pair{0, triangle};
      } else {
        const int group = d.fragments && d.primitive ? 0 : d.fragments ? 1 : d.primitive ? 2 : -1;
        if (group >= 0) groups[size_t(group)].grid[i] = std::pair{count, triangle};
      }
    }
    for (Group& g : groups)
      g.rects = rectangles(width, height, g.grid);
    return groups;
  };
  auto probes = [](const std::vector<Group>& groups) {
    size_t n = 0;
    for (const Group& g : groups)
      n += g.rects.size();
    return n;
  };
  std::vector<Group> groups = encode(false);
  if (std::vector<Group> other = encode(true); probes(other) < probes(groups))
    groups = std::move(other);
  for (size_t i = 0; i < pixels; ++i)
    if (decisions[i].fragments || decisions[i].primitive) ++result.pixels_decided;
  for (const Group& g : groups) {
    if (g.rects.empty()) continue;
    out += "\n";
    out += g.heading;
    out += g.tolerance;
    for (const Rect& r : g.rects) {
      out += cat("probe rect rgba (", std::to_string(r.x), ", ", std::to_string(r.y), ", ",
                 std::to_string(r.w), ", ", std::to_string(r.h), ") (",
                 std::to_string(r.value.first), ", ", std::to_string(r.value.second), ", 0, 1)\n");
      ++result.coverage_probes;
    }
  }
  result.text = std::move(out);
  return result;
}

}  // namespace glrc::reproducer
