#include "cli/expectations.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <stdexcept>

namespace glrc::cli {

namespace {
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}
}  // namespace

Baseline read_baseline(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error(
        file.string() + ": expected a baseline file of `case,Status` lines, " + "got " +
        (std::filesystem::exists(file, ec) ? "something else" : "no such file"));
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the baseline file");
  Baseline b;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    const auto comma = line.find(',');
    const std::string name = comma == std::string::npos ? "" : trim(line.substr(0, comma));
    const std::string status = comma == std::string::npos ? "" : trim(line.substr(comma + 1));
    if (name.empty() || status.empty() || status.find(',') != std::string::npos)
      throw std::runtime_error(file.string() + ":" + std::to_string(n) +
                               ": expected `case,Status`, got \"" + line + "\"");
    // The failing statuses of Mesa CI's fails files; Crash and Timeout come from runs with
    // worker processes, Error from a case the GL side could not render.
    constexpr std::array<const char*, 4> kStatuses = {"Fail", "Crash", "Timeout", "Error"};
    if (std::find(kStatuses.begin(), kStatuses.end(), status) == kStatuses.end())
      throw std::runtime_error(file.string() + ":" + std::to_string(n) +
                               ": expected a status of Fail, Crash, Timeout or Error, got \"" +
                               status + "\"");
    if (!b.expected.emplace(name, status).second)
      throw std::runtime_error(file.string() + ":" + std::to_string(n) +
                               ": expected each case once, got " + name + " again");
  }
  if (in.bad()) throw std::runtime_error(file.string() + ": cannot read the baseline file");
  return b;
}

void apply(const Baseline& b, CaseResult& r) {
  const auto it = b.expected.find(r.name);
  if (it == b.expected.end()) return;
  if (it->second == to_string(r.status)) {
    r.message = "expected " + it->second + ": " + r.message;
    r.status = Status::expected_fail;
  } else if (r.status == Status::fail || r.status == Status::error) {
    // Failing in another way than the baseline says is a change someone must look at.
    r.message = "expected " + it->second + ", got " + to_string(r.status) + ": " + r.message;
  } else if (r.status == Status::pass) {
    r.message = "listed as " + it->second + " in the baseline, but passes";
    r.status = Status::unexpected_pass;
  }
}

bool fails_run(Status s) {
  return s == Status::fail || s == Status::error || s == Status::unexpected_pass;
}

}  // namespace glrc::cli
