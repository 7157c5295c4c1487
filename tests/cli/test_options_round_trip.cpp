// cli::Options through nlohmann's ADL conversions (the worker's options, cli/session.cpp): every
// field to_json writes set to a value other than its default, written, read and written again.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/session.hpp"

namespace glrc::cli {
namespace {

Options every_worker_field_set() {
  Options o;
  o.model.name = "softpipe";
  o.model.subpixel_bits = 4;
  o.model.planes = Planes::snapped;
  o.model.tie_break = TieBreak::top_right;
  o.model.given = true;
  o.gl.backend = gl::Backend::egl;
  o.gl.driver = "zink";
  o.gl.device = 2;
  o.verdict.tolerance = ToleranceMode::exact;
  o.verdict.strict_coverage = true;
  o.out = "out/ünï";
  o.verdict.spec_subpixel_bits = 6;
  o.verdict.varying_ulps = 12.5;
  o.verdict.depth_ulps = 0.25;
  o.threads = 3;
  return o;
}

TEST(OptionsRoundTrip, EveryWorkerFieldThroughToJsonAndFromJson) {
  const Options o = every_worker_field_set();
  const nlohmann::json j = o;
  const Options back = j.get<Options>();
  EXPECT_EQ(nlohmann::json(back).dump(), j.dump());
  EXPECT_EQ(back.model.name, "softpipe");
  EXPECT_EQ(back.model.planes, Planes::snapped);
  EXPECT_EQ(back.model.tie_break, TieBreak::top_right);
  EXPECT_EQ(back.gl.backend, gl::Backend::egl);
  EXPECT_EQ(back.verdict.spec_subpixel_bits, 6);
  EXPECT_EQ(back.verdict.varying_ulps, 12.5);
  EXPECT_EQ(back.verdict.depth_ulps, 0.25);
  EXPECT_EQ(back.threads, 3);
  // And as the worker gets them, one line of text.
  EXPECT_EQ(options_json(options_from_json(options_json(o))), options_json(o));
}

TEST(OptionsRoundTrip, UnsetOptionalFieldsStayUnset) {
  const Options back = nlohmann::json(Options()).get<Options>();
  EXPECT_FALSE(back.verdict.spec_subpixel_bits);
  EXPECT_FALSE(back.verdict.varying_ulps);
  EXPECT_FALSE(back.verdict.depth_ulps);
  EXPECT_EQ(nlohmann::json(back).dump(), nlohmann::json(Options()).dump());
}

TEST(OptionsRoundTrip, ABadFieldIsAnInputErrorNamingIt) {
  nlohmann::json j = every_worker_field_set();
  j["subpixel_bits"] = 99;
  try {
    j.get<Options>();
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "options.subpixel_bits: expected a whole number from 0 to 16, got 99");
  }
  try {
    options_from_json(R"({"model": "bogus"})");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "the worker's options: options.model: expected one of identified, ideal, "
                 "llvmpipe, softpipe, got \"bogus\"");
  }
}

}  // namespace
}  // namespace glrc::cli
