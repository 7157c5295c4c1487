// Two CaseResults field for field, every statistic bit for bit: a result reached another way
// (bands, reused frames, a streamed check) must be the very same one.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <utility>

#include "core/result.hpp"

namespace glrc::test {

inline void expect_same_result(const CaseResult& a, const CaseResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.gl_digest, b.gl_digest);
  const CoverageStats &x = a.coverage, &y = b.coverage;
  EXPECT_EQ(x.both, y.both);
  EXPECT_EQ(x.neither, y.neither);
  EXPECT_EQ(x.reference_only, y.reference_only);
  EXPECT_EQ(x.gl_only, y.gl_only);
  EXPECT_EQ(x.other_primitive, y.other_primitive);
  EXPECT_EQ(x.exact_tie, y.exact_tie);
  EXPECT_EQ(x.within_snapping, y.within_snapping);
  EXPECT_EQ(x.fill_rule, y.fill_rule);
  EXPECT_EQ(x.gaps, y.gaps);
  EXPECT_EQ(x.double_hits, y.double_hits);
  EXPECT_EQ(x.failures, y.failures);
  EXPECT_EQ(x.boundary, y.boundary);
  EXPECT_EQ(x.fragments_checked, y.fragments_checked);
  EXPECT_EQ(x.counts_traced, y.counts_traced);
  EXPECT_EQ(x.counts_untraced, y.counts_untraced);
  ASSERT_EQ(x.mismatches.size(), y.mismatches.size());
  for (size_t i = 0; i < x.mismatches.size(); ++i) {
    EXPECT_EQ(x.mismatches[i].x, y.mismatches[i].x);
    EXPECT_EQ(x.mismatches[i].y, y.mismatches[i].y);
    EXPECT_EQ(x.mismatches[i].label, y.mismatches[i].label);
  }
  ASSERT_EQ(a.channels.size(), b.channels.size());
  for (size_t k = 0; k < a.channels.size(); ++k) {
    const ChannelStats &p = a.channels[k], &q = b.channels[k];
    EXPECT_EQ(p.name, q.name);
    EXPECT_EQ(p.compared, q.compared);
    EXPECT_EQ(p.over_tolerance, q.over_tolerance);
    EXPECT_EQ(p.differing, q.differing);
    EXPECT_EQ(p.non_finite, q.non_finite);
    for (auto [u, v] : {std::pair{p.max_abs, q.max_abs},
                        {p.max_ulps, q.max_ulps},
                        {p.mean_ulps, q.mean_ulps},
                        {p.rms_ulps, q.rms_ulps},
                        {p.p99_ulps, q.p99_ulps},
                        {p.max_ratio, q.max_ratio},
                        {p.p99_ratio, q.p99_ratio},
                        {p.tolerance_ulps, q.tolerance_ulps}})
      EXPECT_EQ(std::bit_cast<uint64_t>(u), std::bit_cast<uint64_t>(v)) << p.name;
    ASSERT_EQ(p.worst.size(), q.worst.size());
    for (size_t i = 0; i < p.worst.size(); ++i) {
      EXPECT_EQ(p.worst[i].x, q.worst[i].x);
      EXPECT_EQ(p.worst[i].y, q.worst[i].y);
      EXPECT_EQ(p.worst[i].ratio, q.worst[i].ratio);
      EXPECT_EQ(p.worst[i].ulps, q.worst[i].ulps);
    }
  }
}

}  // namespace glrc::test
