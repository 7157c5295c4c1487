#include "campaign/campaign.hpp"

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace glrc::campaign {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

uint64_t covered_pixels(const CaseResult& r) {
  const CoverageStats& c = r.coverage;
  return c.both + c.reference_only + c.gl_only + c.other_primitive;
}

std::string replay_command(const FoundFailure& f) {
  return "glrefcheck fuzz --generator " + f.generator + " --replay " + std::to_string(f.seed) +
         ":" + std::to_string(f.index) + " --emit " + f.generator + "_" + std::to_string(f.seed) +
         "_" + std::to_string(f.index) + ".json";
}

}  // namespace

const char* const kNotChecked = "not checked: interrupted";

std::string failure_file_name(const Failure& f) {
  std::string name = f.signature();
  for (char& ch : name)
    if (ch == '/') ch = '_';
  return name + ".json";
}

CampaignResult run_campaign(const CampaignOptions& o, const Judge& judge,
                            const CampaignProgress& progress) {
  if (o.generators.empty()) throw std::invalid_argument("run_campaign: no generator");
  if (!o.count && !o.seconds) throw std::invalid_argument("run_campaign: neither count nor time");
  if (o.fraction < 1 || o.fraction_start < 1 || o.fraction_start > o.fraction)
    throw std::invalid_argument("run_campaign: fraction_start outside 1..fraction");
  const auto start = Clock::now();
  CampaignResult out;
  out.options = o;
  CampaignStats& st = out.stats;
  std::map<std::string, size_t> known;  // signature -> index into out.failures
  const auto stop = [&] { return progress.stop && progress.stop(); };
  const auto time_left = [&] { return !o.seconds || since(start) < *o.seconds; };
  uint64_t next = o.only_index ? *o.only_index : uint64_t(o.fraction_start - 1);
  const auto more = [&] {
    return (!o.count || next < *o.count) && (!o.only_index || next == *o.only_index);
  };
  while (more() && time_left() && !stop()) {
    std::vector<Case> batch;
    std::vector<uint64_t> index;
    while (batch.size() < std::max<size_t>(o.batch, 1) && more()) {
      batch.push_back(generate(o.generators, o.seed, next));
      index.push_back(next);
      next += o.only_index ? 1 : uint64_t(o.fraction);
    }
    const auto checking = Clock::now();
    const std::vector<CaseResult> results = judge(batch);
    st.checking_seconds += since(checking);
    for (size_t k = 0; k < batch.size() && k < results.size(); ++k) {
      const Case& c = batch[k];
      const CaseResult& r = results[k];
      // An interrupted batch's cases that were not checked do not count.
      if (r.outcome == Status::skip && r.message == kNotChecked) continue;
      ++st.cases;
      st.triangles += c.triangles.size();
      st.pixels += covered_pixels(r);
      if (r.outcome == Status::skip) ++st.skipped;
      const std::vector<Failure> found = failures_of(c, r);
      if (found.empty()) continue;
      ++st.failing_cases;
      for (const Failure& f : found) {
        const auto at = known.find(f.signature());
        if (at != known.end()) {
          FoundFailure& old = out.failures[at->second];
          ++old.cases;
          if (old.examples.size() < 8) old.examples.push_back(index[k]);
          continue;
        }
        known[f.signature()] = out.failures.size();
        FoundFailure nf;
        nf.failure = f;
        nf.generator = std::string(generator_for(o.generators, index[k]).name);
        nf.seed = o.seed, nf.index = index[k];
        nf.first_description = describe(f, r);
        nf.found_after = since(start);
        nf.cases = 1;
        nf.examples = {index[k]};
        nf.minimal = c;
        nf.minimal_result = r;
        if (progress.found) progress.found(nf);
        if (o.shrink && !stop()) {
          ShrinkOptions so = o.shrinking;
          so.stop = progress.stop;
          const Shrunk s = shrink(c, r, f, judge, so);
          nf.minimal = s.minimal;
          nf.minimal_result = s.result;
          nf.shrink_steps = s.steps, nf.shrink_checks = s.checks;
          nf.shrink_seconds = s.seconds, nf.shrink_complete = s.complete;
        }
        nf.minimal.name = failure_file_name(f).substr(0, failure_file_name(f).size() - 5);
        nf.minimal.description = "Found by glrefcheck fuzz (" + replay_command(nf) +
                                 ") and shrunk: " + describe(f, nf.minimal_result);
        for (char& ch : nf.minimal.description)
          if (ch == '\n' || ch == '\r') ch = ' ';
        out.failures.push_back(std::move(nf));
        if (progress.shrunk) progress.shrunk(out.failures.back());
      }
    }
    st.seconds = since(start);
    if (progress.batch_done) progress.batch_done(st, out.failures.size());
  }
  st.interrupted = stop();
  st.seconds = since(start);
  return out;
}

nlohmann::json campaign_json(const CampaignResult& r, const nlohmann::json& run) {
  nlohmann::json generators = nlohmann::json::array();
  for (const Generator* g : r.options.generators)
    generators.push_back(std::string(g->name));
  nlohmann::json campaign = {{"seed", r.options.seed},
                             {"generators", generators},
                             {"fraction", r.options.fraction},
                             {"fraction_start", r.options.fraction_start}};
  campaign["count"] = r.options.count ? nlohmann::json(*r.options.count) : nlohmann::json();
  campaign["seconds"] = r.options.seconds ? nlohmann::json(*r.options.seconds) : nlohmann::json();
  const CampaignStats& s = r.stats;
  const nlohmann::json stats = {{"cases", s.cases},
                                {"triangles", s.triangles},
                                {"pixels", s.pixels},
                                {"failing_cases", s.failing_cases},
                                {"skipped", s.skipped},
                                {"seconds", s.seconds},
                                {"checking_seconds", s.checking_seconds},
                                {"triangles_per_second", s.triangles_per_second()},
                                {"interrupted", s.interrupted}};
  nlohmann::json failures = nlohmann::json::array();
  for (const FoundFailure& f : r.failures)
    failures.push_back({{"class", std::string(name_of(f.failure.kind))},
                        {"detail", f.failure.detail},
                        {"signature", f.failure.signature()},
                        {"description", f.minimal.description},
                        {"first_description", f.first_description},
                        {"known", f.known},
                        {"generator", f.generator},
                        {"seed", f.seed},
                        {"index", f.index},
                        {"replay", replay_command(f)},
                        {"found_after_seconds", f.found_after},
                        {"cases", f.cases},
                        {"examples", f.examples},
                        {"file", "failures/" + failure_file_name(f.failure)},
                        {"triangles", f.minimal.triangles.size()},
                        {"varyings", f.minimal.varyings.size()},
                        {"shrink",
                         {{"steps", f.shrink_steps},
                          {"checks", f.shrink_checks},
                          {"seconds", f.shrink_seconds},
                          {"complete", f.shrink_complete}}}});
  return {{"campaign", campaign}, {"run", run}, {"stats", stats}, {"failures", failures}};
}

}  // namespace glrc::campaign
