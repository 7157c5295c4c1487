// selftest/'s loop on stand-in renderers (the command runs it on real Mesa: tests/cli/
// test_selftest.cpp): one that draws exactly what the reference draws, so that every fault
// must be caught and no case may fail clean; and one whose every draw fails.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "casefile/casefile.hpp"
#include "ref/reference.hpp"
#include "selftest/faults.hpp"
#include "selftest/selftest.hpp"

namespace glrc::selftest {
namespace {

std::vector<Case> cases(const std::vector<std::string>& names) {
  std::vector<Case> out;
  for (const std::string& n : names)
    out.push_back(casefile::load(std::string(GLRC_SOURCE_DIR) + "/cases/" + n + ".json"));
  return out;
}

// Draws what the exact reference draws under the fixed default model.
class ReferenceRenderer : public gl::Renderer {
 public:
  ReferenceRenderer() { info_.subpixel_bits = 8; }
  const gl::GlInfo& info() const override { return info_; }
  Frame render(const Case& c) override {
    if (broken) throw gl::RenderError("glLinkProgram failed");
    return ref::render(c, Model{}).frame;
  }
  bool broken = false;

 private:
  gl::GlInfo info_;
};

TEST(SelftestLoop, APerfectImplementationCatchesEveryFaultAndFailsNothingClean) {
  const std::vector<Case> suite =
      cases({"face_on", "flat_provoking_last", "shared_centres_grid", "depth_range_partial",
             "noperspective_smooth", "fan_subpixel_rim_shared_edge", "depth_contest_hidden",
             "invariance_copy_less", "strip_flat_provoking_first", "fan_restart_index_ushort",
             "scissor_inside", "clip_control_upper_left_cull_back", "clip_control_zero_to_one_near",
             "clip_distance_one_plane", "frag_coord_lower_left", "front_facing_cw",
             "depth_clamp_partial_range", "polygon_offset_slope", "polygon_offset_saturates_far"});
  ReferenceRenderer r;
  size_t steps = 0;
  SelftestProgress progress;
  progress.step = [&](size_t, size_t, const std::string&) { ++steps; };
  const SelftestResult result = run_selftest(suite, r, check::CheckOptions{}, {}, progress);
  EXPECT_EQ(result.cases, suite.size());
  EXPECT_EQ(result.passed_clean, suite.size());
  EXPECT_TRUE(result.clean_failures.empty());
  ASSERT_EQ(result.faults.size(), faults().size());
  for (const FaultRow& row : result.faults) {
    EXPECT_GT(row.changed, 0) << row.name;
    EXPECT_GT(row.caught, 0) << row.name;
    EXPECT_LE(row.caught, row.changed) << row.name;
    EXPECT_EQ(row.errors, 0) << row.name;
    EXPECT_FALSE(row.example.empty()) << row.name;
  }
  EXPECT_EQ(result.missed(), 0);
  EXPECT_TRUE(result.ok());
  EXPECT_EQ(steps, suite.size() * (1 + faults().size()));
}

TEST(SelftestLoop, CleanFailuresAreReportedAndTheBaselineExpectsSome) {
  const std::vector<Case> suite = cases({"face_on", "fan"});
  ReferenceRenderer r;
  r.broken = true;
  std::vector<std::string> reported;
  SelftestProgress progress;
  progress.clean_failure = [&](const CaseResult& c) { reported.push_back(c.name); };
  report::Baseline baseline;
  baseline.expected["fan"] = "Error";
  const SelftestResult result = run_selftest(suite, r, check::CheckOptions{}, baseline, progress);
  EXPECT_EQ(result.passed_clean, 0u);
  EXPECT_EQ(result.expected_failures, 1);
  ASSERT_EQ(result.clean_failures.size(), 1u);
  EXPECT_EQ(result.clean_failures[0].name, "face_on");
  EXPECT_EQ(result.clean_failures[0].status, Status::error);
  EXPECT_EQ(reported, std::vector<std::string>{"face_on"});
  // No case passed clean, so no fault could be tried, and none counts as caught.
  for (const FaultRow& row : result.faults)
    EXPECT_EQ(row.changed, 0) << row.name;
  EXPECT_FALSE(result.ok());
}

}  // namespace
}  // namespace glrc::selftest
