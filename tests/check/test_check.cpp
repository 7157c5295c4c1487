// check/: the tolerance a case is judged by, what it is compared against, and check() itself.
// The renderer here is a stand-in that hands back frames the test chose (the reference's own,
// or one with a planted error): it tests the check's logic, never a driver; the GL tests and
// the suite run the check on real Mesa.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "driver_models/driver_models.hpp"
#include "ref/reference.hpp"

namespace glrc::check {
namespace {

Case load(const std::string& name) {
  return casefile::load(std::string(GLRC_SOURCE_DIR) + "/cases/" + name + ".json");
}

// Returns the frame it was given, or throws gl::RenderError when told to.
class FixedRenderer : public gl::Renderer {
 public:
  explicit FixedRenderer(Frame f, int subpixel_bits = 8) : frame_(std::move(f)) {
    info_.renderer = "fixed frame (test)";
    info_.subpixel_bits = subpixel_bits;
  }
  const gl::GlInfo& info() const override { return info_; }
  Frame render(const Case&) override {
    ++calls;
    if (fail) throw gl::RenderError("glDrawElements: GL_OUT_OF_MEMORY");
    return frame_;
  }
  bool fail = false;
  int calls = 0;

 private:
  gl::GlInfo info_;
  Frame frame_;
};

TEST(Tolerance, FreedomIsTheReportedBitsButNeverBelowFour) {
  CheckOptions o;
  EXPECT_EQ(freedom_bits(o, 8), 8);
  EXPECT_EQ(freedom_bits(o, 0), 4);  // GL requires at least 4; a driver saying 0 gets 4
  o.spec_subpixel_bits = 6;
  EXPECT_EQ(freedom_bits(o, 8), 6);
}

TEST(Tolerance, CaseFileThenOptionsExactWins) {
  Case c = load("face_on");
  c.tolerance.varying_ulps = 100;  // a case file naming a number turns to fixed ULPs
  CheckOptions o;
  Tolerance t = tolerance_for(c, o, 8);
  EXPECT_EQ(t.mode, ToleranceMode::ulps);
  EXPECT_EQ(t.varying_ulps, 100);
  EXPECT_EQ(t.depth_ulps, Tolerance{}.depth_ulps);
  EXPECT_EQ(t.subpixel_bits, 8);
  EXPECT_TRUE(t.allow_boundary);

  o.depth_ulps = 3;  // the command line's number overrides that one only
  t = tolerance_for(c, o, 8);
  EXPECT_EQ(t.mode, ToleranceMode::ulps);
  EXPECT_EQ(t.varying_ulps, 100);
  EXPECT_EQ(t.depth_ulps, 3);

  o = CheckOptions{};
  o.tolerance = ToleranceMode::exact;
  o.strict_coverage = true;
  t = tolerance_for(c, o, 8);
  EXPECT_EQ(t.mode, ToleranceMode::exact);
  EXPECT_FALSE(t.allow_boundary);

  EXPECT_EQ(tolerance_for(load("face_on"), CheckOptions{}, 8).mode, ToleranceMode::spec);
}

TEST(Tolerance, TextNamesTheModeAndTheFreedom) {
  CheckOptions o;
  EXPECT_EQ(tolerance_text(o, 2), "spec (subpixel bits 4)");
  o.varying_ulps = 1;
  EXPECT_EQ(tolerance_text(o, 8), "ulps");
  o.tolerance = ToleranceMode::exact;
  EXPECT_EQ(tolerance_text(o, 8), "exact");
}

TEST(Expectation, DriverModelReplacesTheFrameOnly) {
  const Case c = load("clip_near");
  CheckOptions o;
  const Expectation reference = expectation_for(c, o, 8);
  o.driver_model = driver_models::Driver::softpipe;
  const Expectation e = expectation_for(c, o, 8);
  const Frame softpipe = driver_models::render(c, driver_models::Driver::softpipe);
  EXPECT_EQ(ref::digest(e.frame), ref::digest(softpipe));
  EXPECT_NE(ref::digest(e.frame), ref::digest(reference.frame));
  EXPECT_EQ(model_text(o), "softpipe (bit-exact model of Mesa 22.3.6's driver)");
}

TEST(Check, TheReferencesOwnFramePassesAndAPlantedErrorFails) {
  const Case c = load("face_on");
  const CheckOptions o;
  const Frame reference = expectation_for(c, o, 8).frame;
  FixedRenderer same(reference);
  const Checked ok = check_with_frames(c, same, o);
  EXPECT_EQ(ok.result.status, Status::pass) << ok.result.message;
  EXPECT_EQ(ok.result.name, "face_on");
  EXPECT_EQ(ok.result.gl_digest, ref::digest(reference));
  EXPECT_GE(ok.result.seconds, 0.0);
  EXPECT_EQ(ref::digest(ok.gl), ref::digest(reference));

  // One covered pixel's first component off by 1e-3 relative: far beyond the allowance.
  Frame wrong = reference;
  size_t covered = 0;
  while (wrong.primitive[covered] < 0)
    ++covered;
  ASSERT_FALSE(wrong.components.empty());
  wrong.components[0][covered] = wrong.components[0][covered] * 1.001f + 1e-3f;
  FixedRenderer off(wrong);
  const CaseResult r = check(c, off, o);
  EXPECT_EQ(r.status, Status::fail);
  EXPECT_NE(r.gl_digest, ref::digest(reference));
}

TEST(Check, AGlErrorIsTheResultErrorNotAnException) {
  const Case c = load("face_on");
  FixedRenderer broken(Frame{});
  broken.fail = true;
  const CaseResult r = check(c, broken, CheckOptions{});
  EXPECT_EQ(r.status, Status::error);
  EXPECT_EQ(r.outcome, Status::error);
  EXPECT_EQ(r.name, "face_on");
  EXPECT_NE(r.message.find("GL_OUT_OF_MEMORY"), std::string::npos);
}

TEST(Check, ADriverModelIsNeverJudgedByTheSpecificationsAllowance) {
  const Case c = load("face_on");
  CheckOptions o;
  o.driver_model = driver_models::Driver::llvmpipe;
  FixedRenderer r(driver_models::render(c, driver_models::Driver::llvmpipe));
  EXPECT_THROW(check(c, r, o), std::invalid_argument);
  EXPECT_EQ(r.calls, 0);  // refused before anything is drawn
  o.tolerance = ToleranceMode::exact;
  EXPECT_EQ(check(c, r, o).status, Status::pass);  // the model's own frame, bit for bit
}

}  // namespace
}  // namespace glrc::check
