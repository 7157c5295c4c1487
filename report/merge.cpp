#include "report/merge.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/text.hpp"
#include "core/verdict_inputs.hpp"
#include "report/format.hpp"

namespace glrc::report {

RunResults merge_shards(const std::vector<RunResults>& shards,
                        const std::vector<std::string>& names) {
  if (shards.empty() || shards.size() != names.size())
    throw std::invalid_argument("merge_shards: expected one name per shard, and a shard");
  // Every shard of one fraction, each once, from the same GL and options. A shard of no case
  // (more shards than cases: the suite's 6 in GitLab's `parallel: 8`) never started GL, and its
  // empty GL fields say nothing: GL is compared among the shards that had it.
  const RunInfo& first = shards.front().run;
  const auto had_gl = [](const RunInfo& r) { return !r.gl_renderer.empty(); };
  const auto with_gl = std::find_if(shards.begin(), shards.end(),
                                    [&](const RunResults& s) { return had_gl(s.run); });
  const RunInfo& gl_first = with_gl != shards.end() ? with_gl->run : first;
  const int n = first.fraction;
  // Read back, 1 <= fraction_start <= fraction holds (report::read_results_json checks it). The
  // shards seen are a map, not a table of `fraction` entries: that number comes from a file.
  std::map<int, size_t> seen;
  for (size_t k = 0; k < shards.size(); ++k) {
    const RunInfo& r = shards[k].run;
    if (r.interrupted)
      throw std::runtime_error("merge: " + names[k] +
                               ": an interrupted run: `glrefcheck run --resume " + names[k] +
                               "` completes it");
    if (r.fraction != n)
      throw std::runtime_error(
          fmt::format("merge: {}: expected a shard of --fraction {}, got --fraction {}", names[k],
                      n, r.fraction));
    if (r.total_cases != first.total_cases)
      throw std::runtime_error(
          fmt::format("merge: {}: expected a shard of a {}-case suite, got {} cases", names[k],
                      first.total_cases, r.total_cases));
    // What judged the shard, each named as results.json names it and by the option that sets it.
    // The options asked for first: shards of two backends differ in their GL library too, and
    // the backend is the difference to name.
    const bool gl = had_gl(r) && had_gl(gl_first);
    for (const auto& [field, option, value, value0, of_gl] :
         {std::tuple{"backend", "--backend", &r.backend, &first.backend, false},
          {"driver", "--driver", &r.driver, &first.driver, false},
          {"mesa_prefix", "--mesa", &r.mesa_prefix, &first.mesa_prefix, false},
          {"gl_renderer", "the driver: --backend, --driver, --mesa", &r.gl_renderer,
           &gl_first.gl_renderer, true},
          {"gl_version", "the driver: --mesa", &r.gl_version, &gl_first.gl_version, true},
          {"gl_library", "the driver: --mesa", &r.gl_library, &gl_first.gl_library, true},
          {"model", "--model, --subpixel-bits, --planes, --tie-break", &r.model, &gl_first.model,
           true},
          {"tolerance", "--tolerance, --spec-subpixel-bits", &r.tolerance, &gl_first.tolerance,
           true}})
      if ((gl || !of_gl) && *value != *value0)
        throw std::runtime_error(fmt::format(
            "merge: {}: expected shards judged alike, got run.{} \"{}\" where {} has \"{}\" (set "
            "by "
            "{}): run the shards with the same options",
            names[k], field, printable(*value, 100), names[0], printable(*value0, 100), option));
    // GL_SUBPIXEL_BITS as the driver reported it: the spec tolerance derives from it.
    if (gl && r.subpixel_bits != gl_first.subpixel_bits)
      throw std::runtime_error(fmt::format(
          "merge: {}: expected shards judged alike, got run.subpixel_bits {} where {} has {} "
          "(reported by the driver): run the shards on the same GL",
          names[k], r.subpixel_bits, names[0], gl_first.subpixel_bits));
    if (const auto d = verdict_input_difference(r.verdict_inputs, first.verdict_inputs))
      throw std::runtime_error(fmt::format(
          "merge: {}: expected shards judged alike, got {} {} where {} has {}: run the shards "
          "with the same options and files",
          names[k], d->name, d->value, names[0], d->other));
    if (const auto [it, added] = seen.emplace(r.fraction_start, k); !added)
      throw std::runtime_error(fmt::format("merge: {} and {} are both shard {} of {}",
                                           names[it->second], names[k], r.fraction_start, n));
  }
  // N distinct shards among the folders are all of them; the first gap is at most one past the
  // number of folders.
  for (int start = 1; start <= n; ++start)
    if (!seen.contains(start))
      throw std::runtime_error(fmt::format("merge: shard {} of {} is missing", start, n));

  // Case j of shard K is case K - 1 + j * N of the whole suite: shard K holds
  // ceil((total - K + 1) / N) cases. Checked before the table is made, so that a forged
  // total_cases is a line, not 2^62 elements.
  for (size_t k = 0; k < shards.size(); ++k) {
    const RunInfo& r = shards[k].run;
    const uint64_t start = uint64_t(r.fraction_start);
    const uint64_t holds =
        first.total_cases >= start ? (first.total_cases - start) / uint64_t(n) + 1 : 0;
    if (shards[k].cases.size() != holds)
      throw std::runtime_error(fmt::format(
          "merge: {}: shard {} of {} of a {}-case suite: expected {} "
          "cases, got {}",
          names[k], r.fraction_start, n, first.total_cases, holds, shards[k].cases.size()));
  }
  std::vector<std::optional<CaseResult>> merged(first.total_cases);
  RunInfo info = gl_first;  // the GL the shards ran on
  info.fraction = info.fraction_start = 1;
  info.seconds = 0;
  info.jobs = 0;
  for (const auto& shard : shards) {
    info.seconds = std::max(info.seconds, shard.run.seconds);  // shards run side by side
    info.jobs += shard.run.jobs;
    for (size_t j = 0; j < shard.cases.size(); ++j) {
      const size_t at = size_t(shard.run.fraction_start - 1) + j * size_t(n);
      if (at >= merged.size())
        throw std::runtime_error(
            fmt::format("merge: shard {} holds more cases than a {}-case suite has",
                        shard.run.fraction_start, merged.size()));
      merged[at] = shard.cases[j];
    }
  }
  std::vector<CaseResult> list;
  for (size_t k = 0; k < merged.size(); ++k) {
    if (!merged[k])
      throw std::runtime_error(
          fmt::format("merge: case {} of {} is in no shard", k + 1, merged.size()));
    list.push_back(std::move(*merged[k]));
  }
  std::map<std::string, size_t> named;
  for (size_t k = 0; k < list.size(); ++k) {
    const CaseResult& r = list[k];
    // Shards of one suite hold each case once: a name twice means shards of two suites (a case
    // renamed or added between the checkouts that ran them).
    if (const auto [it, added] = named.emplace(r.name, k); !added)
      throw std::runtime_error(fmt::format(
          "merge: expected shards of one suite, got case \"{}\" as case {} and case {} of {}: "
          "shards of different suites (cases added, removed or renamed between them)",
          printable(r.name, 80), it->second + 1, k + 1, list.size()));
  }
  return {info, std::move(list)};
}

std::string run_summary(const std::vector<CaseResult>& results, double seconds) {
  std::map<Status, int> count;
  for (const auto& r : results)
    ++count[r.status];
  std::string text = fmt::format("{}: {} pass, {} fail, {} expected fail, {} unexpected pass",
                                 count_text(results.size(), "case", "cases"), count[Status::pass],
                                 count[Status::fail], count[Status::expected_fail],
                                 count[Status::unexpected_pass]);
  for (Status s : {Status::crash, Status::timeout, Status::flake})
    if (count[s]) text += fmt::format(", {} {}", count[s], to_string(s));
  return text + fmt::format(", {} error, {} skip in {:.2f} s", count[Status::error],
                            count[Status::skip], seconds);
}

bool any_fails_run(const std::vector<CaseResult>& results) {
  return std::any_of(results.begin(), results.end(),
                     [](const CaseResult& r) { return fails_run(r.status); });
}

}  // namespace glrc::report
