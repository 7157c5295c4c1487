// The JSON view of a RunComparison (`glrefcheck compare --json FILE`), for scripts: every case
// with every channel, whether listed by the other views or not.
#include <nlohmann/json.hpp>

#include "report/comparison_sections.hpp"
#include "report/format.hpp"
#include "report/run_compare.hpp"

namespace glrc::report {
namespace {

nlohmann::json run_json(const RunInfo& r) {
  return {{"backend", r.backend},
          {"driver", r.driver},
          {"gl_renderer", r.gl_renderer},
          {"gl_version", r.gl_version},
          {"gl_vendor", r.gl_vendor},
          {"mesa_prefix", r.mesa_prefix},
          {"model", r.model},
          {"model_source", r.model_source},
          {"tolerance", r.tolerance}};
}

nlohmann::json optional_status(const std::optional<Status>& s) {
  return s ? nlohmann::json(to_string(*s)) : nlohmann::json(nullptr);
}

}  // namespace

std::string comparison_json(const RunComparison& c) {
  nlohmann::json summary = nlohmann::json::object();
  for (const CaseChange::Kind k : sections::kKinds)
    summary[to_string(k)] = c.count(k);
  nlohmann::json cases = nlohmann::json::array();
  for (const auto& cc : c.cases) {
    nlohmann::json channels = nlohmann::json::array();
    for (const auto& ch : cc.channels)
      channels.push_back({{"channel", ch.channel},
                          {"base_max_ulps", json_number(ch.base_max_ulps)},
                          {"current_max_ulps", json_number(ch.current_max_ulps)},
                          {"base_p99_ulps", json_number(ch.base_p99_ulps)},
                          {"current_p99_ulps", json_number(ch.current_p99_ulps)},
                          {"base_max_ratio", json_number(ch.base_max_ratio)},
                          {"current_max_ratio", json_number(ch.current_max_ratio)},
                          {"max_grew", ch.max_grew},
                          {"p99_grew", ch.p99_grew}});
    cases.push_back({{"name", cc.name},
                     {"kind", to_string(cc.kind)},
                     {"base", optional_status(cc.base)},
                     {"current", optional_status(cc.current)},
                     {"message", cc.message},
                     {"same_bits", cc.same_bits ? nlohmann::json(*cc.same_bits) : nullptr},
                     {"channels", std::move(channels)}});
  }
  const nlohmann::json doc = {
      {"base", run_json(c.base)},           {"current", run_json(c.current)},
      {"factor", json_number(c.factor)},    {"min_ulps", json_number(c.min_ulps)},
      {"summary", std::move(summary)},      {"regressions", c.has_regression()},
      {"bits_compared", c.bits_compared()}, {"bits_identical", c.bits_identical()},
      {"incomplete", c.incomplete},         {"cases", std::move(cases)}};
  // Case names and messages come from files and drivers; replace bad UTF-8 rather than throw.
  return doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace glrc::report
