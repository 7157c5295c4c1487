// cli::Options through nlohmann's ADL conversions (the worker's options, cli/session.cpp): every
// field to_json writes set to a value other than its default, written, read and written again.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/session.hpp"

namespace glrc::cli {
namespace {

Options every_worker_field_set() {
  Options o;
  o.model = "softpipe";
  o.subpixel_bits = 4;
  o.planes = Planes::snapped;
  o.tie_break = TieBreak::top_right;
  o.model_given = true;
  o.backend = gl::Backend::egl;
  o.driver = "zink";
  o.device = 2;
  o.tolerance = ToleranceMode::exact;
  o.strict_coverage = true;
  o.out = "out/ünï";
  o.spec_subpixel_bits = 6;
  o.varying_ulps = 12.5;
  o.depth_ulps = 0.25;
  o.threads = 3;
  return o;
}

TEST(OptionsRoundTrip, EveryWorkerFieldThroughToJsonAndFromJson) {
  const Options o = every_worker_field_set();
  const nlohmann::json j = o;
  const Options back = j.get<Options>();
  EXPECT_EQ(nlohmann::json(back).dump(), j.dump());
  EXPECT_EQ(back.model, "softpipe");
  EXPECT_EQ(back.planes, Planes::snapped);
  EXPECT_EQ(back.tie_break, TieBreak::top_right);
  EXPECT_EQ(back.backend, gl::Backend::egl);
  EXPECT_EQ(back.spec_subpixel_bits, 6);
  EXPECT_EQ(back.varying_ulps, 12.5);
  EXPECT_EQ(back.depth_ulps, 0.25);
  EXPECT_EQ(back.threads, 3);
  // And as the worker gets them, one line of text.
  EXPECT_EQ(options_json(options_from_json(options_json(o))), options_json(o));
}

TEST(OptionsRoundTrip, UnsetOptionalFieldsStayUnset) {
  const Options back = nlohmann::json(Options()).get<Options>();
  EXPECT_FALSE(back.spec_subpixel_bits);
  EXPECT_FALSE(back.varying_ulps);
  EXPECT_FALSE(back.depth_ulps);
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
