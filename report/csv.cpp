// results.csv and failures.csv in deqp-runner's format, which Mesa CI's tooling reads: one
// `case,Status,seconds` line per case, no header. A failures.csv can serve as the next run's
// --baseline.
#include <stdexcept>

#include <fmt/format.h>

#include "report/report.hpp"

namespace glrc::report {
namespace {

void write_csv(const std::filesystem::path& file, const std::vector<CaseResult>& results,
               bool failures_only) {
  std::string text;
  for (const auto& r : results)
    if (!failures_only || fails_run(r.status))
      text += fmt::format("{},{},{:.6f}\n", r.name, to_string(r.status), r.seconds);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  write_file_atomically(file, text);
}

}  // namespace

const char* csv_breaking(const std::string& name) {
  if (name.empty()) return "no character at all";
  for (const char ch : name) {
    if (ch == ',') return "a comma";
    if (ch == '"') return "a double quote";
    if (ch == '\n' || ch == '\r') return "a line break";
    if ((unsigned char)ch < 0x20 || ch == 0x7f) return "a control character";
  }
  if (name.front() == ' ' || name.back() == ' ') return "a space at an end (baselines trim it)";
  return nullptr;
}

void write_results_csv(const std::filesystem::path& file, const std::vector<CaseResult>& results) {
  write_csv(file, results, false);
}

void write_failures_csv(const std::filesystem::path& file, const std::vector<CaseResult>& results) {
  write_csv(file, results, true);
}

void write_run_files(const std::filesystem::path& dir, const RunInfo& run,
                     const std::vector<CaseResult>& results) {
  write_results_json(dir / "results.json", run, results);
  write_results_csv(dir / "results.csv", results);
  write_failures_csv(dir / "failures.csv", results);
  write_junit(dir / "junit.xml", run, results);
}

}  // namespace glrc::report
