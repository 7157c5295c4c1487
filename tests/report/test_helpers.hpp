// Shared by the report tests: a private temporary directory per test (never the repository) and
// hand-made CaseResults covering every status and the non-finite cases.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace glrc::report::test {

using ReportTest = glrc::test::TempDirTest;

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

inline ChannelStats channel(const std::string& name, double max_ulps, double tolerance,
                            std::vector<WorstPixel> worst = {}) {
  ChannelStats ch;
  ch.name = name;
  ch.compared = 100;
  ch.max_ulps = max_ulps;
  ch.max_abs = max_ulps * 0x1p-23;
  ch.mean_ulps = max_ulps / 4;
  ch.rms_ulps = max_ulps / 3;
  ch.p99_ulps = max_ulps / 2;
  ch.tolerance_ulps = tolerance;
  ch.over_tolerance = max_ulps > tolerance ? 1 : 0;
  ch.worst = std::move(worst);
  return ch;
}

inline CaseResult passing_case() {
  CaseResult r;
  r.name = "face_on";
  r.description = "a triangle facing the viewer";
  r.status = Status::pass;
  r.seconds = 0.012;
  r.coverage.both = 900;
  r.coverage.neither = 3196;
  r.coverage.reference_only = 2;
  r.coverage.boundary = 2;
  r.coverage.mismatches = {{10, 20, 0, -1, true}, {11, 20, 0, -1, true}};
  r.channels = {channel("depth", 1.5, 16, {{3, 4, 0.25f, 0.250000030f, 0x1p-25, 0.5}}),
                channel("color.x", 3.1, 64, {{5, 6, 0.1f, 0.100000024f, 0x1p-25, 3.1}})};
  return r;
}

// GL gave NaN at one pixel of color.y: the channel's max is infinite, its mean NaN.
inline CaseResult nan_case() {
  CaseResult r;
  r.name = "nan_varying";
  r.status = Status::fail;
  r.message = "color.y: 1 non-finite value";
  r.seconds = 0.5;
  ChannelStats bad = channel("color.y", kInf, 64, {{7, 8, 0.5f, kNaNf, kInf, kInf}});
  bad.non_finite = 1;
  bad.over_tolerance = 1;
  bad.mean_ulps = std::numeric_limits<double>::quiet_NaN();
  r.channels = {channel("depth", 0, 16), bad};
  return r;
}

inline CaseResult with_status(Status s, const std::string& name, const std::string& message) {
  CaseResult r;
  r.name = name;
  r.status = s;
  r.message = message;
  r.seconds = 0.25;
  return r;
}

inline RunInfo run_info() {
  RunInfo run;
  run.backend = "osmesa";
  run.driver = "llvmpipe";
  run.model = "subpixel_bits=8 planes=snapped tie=top_left";
  run.model_source = "identify (cached)";
  run.gl_vendor = "Mesa";
  run.gl_renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  run.gl_version = "4.5 (Compatibility Profile) Mesa 22.3.6";
  run.seconds = 1.75;
  return run;
}

}  // namespace glrc::report::test
