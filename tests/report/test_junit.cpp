// junit.xml: counts per kind of outcome, one testcase per case, and escaping.
#include "report/report.hpp"
#include "tests/report/test_helpers.hpp"

namespace glrc::report::test {
namespace {

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

TEST_F(ReportTest, JunitCountsFailuresErrorsAndSkips) {
  const auto file = dir_ / "junit.xml";
  write_junit(
      file, run_info(),
      {passing_case(), nan_case(), with_status(Status::unexpected_pass, "fixed", "passes now"),
       with_status(Status::error, "broken", "GL context lost"),
       with_status(Status::skip, "skipped", "no GL"),
       with_status(Status::expected_fail, "known", "snapping differs")});
  const std::string xml = read_text(file);

  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>", 0), 0u);
  EXPECT_NE(xml.find(R"(<testsuite name="glrefcheck.osmesa.llvmpipe" tests="6" failures="2" )"
                     R"(errors="1" skipped="1" time="1.750">)"),
            std::string::npos)
      << xml;
  EXPECT_EQ(count(xml, "<testcase "), 6u);
  EXPECT_EQ(count(xml, "<failure "), 2u);
  EXPECT_EQ(count(xml, "<error "), 1u);
  EXPECT_EQ(count(xml, "<skipped "), 1u);
  EXPECT_NE(xml.find(R"(<testcase classname="glrefcheck" name="face_on" time="0.012"/>)"),
            std::string::npos);
  EXPECT_NE(xml.find(R"(<failure message="color.y: 1 non-finite value" type="Fail">)"),
            std::string::npos);
  EXPECT_NE(xml.find("color.y: max inf ulp, "), std::string::npos) << xml;
  EXPECT_NE(xml.find("gaps 0, double hits 0"), std::string::npos) << xml;
  EXPECT_NE(xml.find(R"(<error message="GL context lost")"), std::string::npos);
  // An expected failure passes, with a note.
  EXPECT_NE(xml.find("<system-out>ExpectedFail: snapping differs"), std::string::npos);
}

TEST_F(ReportTest, JunitEscapesNamesAndMessages) {
  const auto file = dir_ / "junit.xml";
  write_junit(file, run_info(),
              {with_status(Status::fail, "a<b>&c", "said \"no\" & 'why'\nsecond line\x01")});
  const std::string xml = read_text(file);
  EXPECT_NE(xml.find(R"(name="a&lt;b&gt;&amp;c")"), std::string::npos) << xml;
  EXPECT_NE(xml.find(R"(message="said &quot;no&quot; &amp; &apos;why&apos;&#10;second line?")"),
            std::string::npos)
      << xml;
  EXPECT_EQ(xml.find('\x01'), std::string::npos);
}

}  // namespace
}  // namespace glrc::report::test
