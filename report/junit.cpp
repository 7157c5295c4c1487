// junit.xml: one testcase per case, for CI systems that chart test results.
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "report/format.hpp"
#include "report/report.hpp"

namespace glrc::report {
namespace {

// A failed check; Error (the case could not be judged at all) is JUnit's <error>.
bool is_failure(Status s) {
  return fails_run(s) && s != Status::error;
}

// A few lines under the failure message, enough to triage without opening results.json.
std::string stats_text(const CaseResult& r) {
  std::string text;
  for (const auto& ch : r.channels)
    text += fmt::format(
        "{}: max {} ulp, {}x allowed (p99 {}x), {} of {} over tolerance, {} non-finite\n", ch.name,
        ulps_text(ch.max_ulps), ratio_text(ch.max_ratio), ratio_text(ch.p99_ratio),
        ch.over_tolerance, ch.compared, ch.non_finite);
  const auto& cov = r.coverage;
  text += fmt::format(
      "coverage: {}; reference only {}, GL only {}, other primitive {}; exact tie {}, "
      "within snapping {}, fill-rule error {}, gaps {}, double hits {}\n",
      count_text(cov.failures, "failure", "failures"), cov.reference_only, cov.gl_only,
      cov.other_primitive, cov.exact_tie, cov.within_snapping, cov.fill_rule, cov.gaps,
      cov.double_hits);
  return text;
}

std::string testcase_xml(const CaseResult& r) {
  std::string xml = fmt::format(R"(    <testcase classname="glrefcheck" name="{}" time="{:.3f}")",
                                xml_escaped(r.name), r.seconds);
  std::string body;
  const std::string message = xml_escaped(r.message.empty() ? to_string(r.status) : r.message);
  if (is_failure(r.status)) {
    body = fmt::format("      <failure message=\"{}\" type=\"{}\">{}</failure>\n", message,
                       to_string(r.status), xml_escaped(stats_text(r)));
  } else if (r.status == Status::error) {
    // The harness could not judge the case at all; JUnit tells that apart from a failed check.
    body = fmt::format("      <error message=\"{}\" type=\"Error\"/>\n", message);
  } else if (r.status == Status::skip) {
    body = fmt::format("      <skipped message=\"{}\"/>\n", message);
  } else if (r.status == Status::expected_fail || r.status == Status::flake) {
    // Passing for CI, but say so: a known difference is still a difference.
    body = fmt::format("      <system-out>{}: {}&#10;{}</system-out>\n", to_string(r.status),
                       xml_escaped(r.message), xml_escaped(stats_text(r)));
  }
  if (body.empty()) return xml + "/>\n";
  return xml + ">\n" + body + "    </testcase>\n";
}

}  // namespace

void write_junit(const std::filesystem::path& file, const RunInfo& run,
                 const std::vector<CaseResult>& results) {
  size_t failures = 0, errors = 0, skipped = 0;
  for (const auto& r : results) {
    failures += is_failure(r.status);
    errors += r.status == Status::error;
    skipped += r.status == Status::skip;
  }
  const std::string counts =
      fmt::format(R"(tests="{}" failures="{}" errors="{}" skipped="{}" time="{:.3f}")",
                  results.size(), failures, errors, skipped, run.seconds);
  const std::string suite = xml_escaped("glrefcheck." + run.backend + "." + run.driver);

  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += fmt::format("<testsuites name=\"{}\" {}>\n", suite, counts);
  xml += fmt::format("  <testsuite name=\"{}\" {}>\n", suite, counts);
  xml += "    <properties>\n";
  for (const auto& [name, value] : {std::pair{"model", &run.model},
                                    {"model_source", &run.model_source},
                                    {"gl_vendor", &run.gl_vendor},
                                    {"gl_renderer", &run.gl_renderer},
                                    {"gl_version", &run.gl_version}})
    xml += fmt::format("      <property name=\"{}\" value=\"{}\"/>\n", name, xml_escaped(*value));
  xml += "    </properties>\n";
  for (const auto& r : results)
    xml += testcase_xml(r);
  xml += "  </testsuite>\n</testsuites>\n";

  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  write_file_atomically(file, xml);
}

}  // namespace glrc::report
