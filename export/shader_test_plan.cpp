#include "export/shader_test_plan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include "compare/compare.hpp"
#include "export/coverage_verdict_table.hpp"
#include "export/shader_test.hpp"

namespace glrc::reproducer {
namespace {

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

// Whether a 4-neighbour of pixel i is drawn by another triangle than i.
bool edge_pixel(const Frame& f, size_t i) {
  const int x = int(i % size_t(f.width)), y = int(i / size_t(f.width));
  const int32_t p = f.primitive[i];
  const int dx[] = {1, -1, 0, 0}, dy[] = {0, 0, 1, -1};
  for (int n = 0; n < 4; ++n) {
    const int nx = x + dx[n], ny = y + dy[n];
    if (nx < 0 || ny < 0 || nx >= f.width || ny >= f.height) continue;
    if (f.primitive[f.index(nx, ny)] != p) return true;
  }
  return false;
}

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

// Every (pixel, triangle) pair run judges, by pixel: the reference's fragment, with its tier (0
// where the pixel is free, 1 on a clipped triangle, 2 at an edge, 3 elsewhere), then the
// candidates of the depth test (tier 0). `free` (per pixel) is set where coverage is free
// (decided) or the reference's fragment has no determined value: a reference that is NaN or
// Inf, or an unbounded allowance (any number passes there, and NaN or Inf is not judged either).
std::vector<ValuePair> value_pairs(const Case& c, const Expectation& expected,
                                   const std::vector<Decided>& decided,
                                   const std::vector<compare::ChannelAllowance>& allowances,
                                   const compare::UlpTable& ulps, std::vector<bool>& free) {
  const Frame& f = expected.frame;
  std::vector<bool> clipped_triangle(c.triangles.size());
  for (size_t t = 0; t < c.triangles.size(); ++t)
    clipped_triangle[t] = clipped(c, t);
  const std::vector<Channel> channels = channels_of(c.component_count());
  free.assign(f.pixel_count(), false);
  std::vector<ValuePair> pairs;
  auto candidate = expected.candidates.begin();
  for (size_t i = 0; i < f.pixel_count(); ++i) {
    free[i] = !decided[i].primitive;
    if (const int32_t p = f.primitive[i]; p != Frame::kNoPrimitive) {
      ValuePair r{i, p, {}, {}, 0};
      for (Channel ch : channels) {
        r.expected.push_back(f.values(ch)[i]);
        r.allowed.push_back(allowances[ch.slot()].at(i, ulps.ulp(p, ch)));
        if (!std::isfinite(r.expected.back()) || !std::isfinite(r.allowed.back())) free[i] = true;
      }
      r.tier = free[i] ? 0 : clipped_triangle[size_t(p)] ? 1 : edge_pixel(f, i) ? 2 : 3;
      pairs.push_back(std::move(r));
    }
    for (; candidate != expected.candidates.end() && candidate->pixel == i; ++candidate) {
      const Candidate& o = *candidate;
      ValuePair r{i, o.primitive, {}, {}, 0};
      // What the comparator allows GL's fragment there when it is this candidate's.
      const compare::Judged as_candidate{true, &o};
      for (Channel ch : channels) {
        r.expected.push_back(o.value(ch));
        r.allowed.push_back(
            as_candidate.allowed(allowances[ch.slot()], i, ulps.ulp(o.primitive, ch), ch));
      }
      pairs.push_back(std::move(r));
    }
  }
  return pairs;
}

// The pairs checked: shader_test_value_checks of them, by tier.
std::vector<size_t> chosen_checks(const std::vector<ValuePair>& pairs, int components) {
  std::array<std::vector<size_t>, 4> tiers;
  for (size_t n = 0; n < pairs.size(); ++n)
    tiers[size_t(pairs[n].tier)].push_back(n);
  std::array<std::vector<bool>, 4> taken;
  for (size_t t = 0; t < 4; ++t)
    taken[t].assign(tiers[t].size(), false);
  std::vector<size_t> checks;
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
  std::sort(checks.begin(), checks.end(), [&](size_t a, size_t b) {
    return std::tie(pairs[a].pixel, pairs[a].primitive) <
           std::tie(pairs[b].pixel, pairs[b].primitive);
  });
  return checks;
}

bool accepted(float g, float e, double a) {
  return std::isfinite(g) && std::fabs(double(g) - double(e)) <= a;
}

}  // namespace

ShaderTestPlan plan_shader_test(const Case& c, const Expectation& expected,
                                const Tolerance& tolerance) {
  const Frame& f = expected.frame;
  const size_t pixels = f.pixel_count();
  const compare::UlpTable ulps(c);
  std::vector<compare::ChannelAllowance> allowances;
  for (Channel ch : channels_of(c.component_count()))
    allowances.emplace_back(c, expected, tolerance, ch);
  const CoverageVerdictTable verdicts(f.fragments.size() == pixels, tolerance);
  ShaderTestPlan plan;
  plan.decided.resize(pixels);
  for (size_t i = 0; i < pixels; ++i)
    plan.decided[i] = decided(expected, verdicts, c, i);
  std::vector<bool> free;
  plan.pairs = value_pairs(c, expected, plan.decided, allowances, ulps, free);
  plan.checks = chosen_checks(plan.pairs, c.component_count());
  for (size_t i = 0; i < pixels; ++i) {
    if (!free[i]) continue;
    if (!plan.free_spans.empty() && plan.free_spans.back().second == i)
      ++plan.free_spans.back().second;
    else
      plan.free_spans.emplace_back(i, i + 1);
  }
  return plan;
}

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

}  // namespace glrc::reproducer
