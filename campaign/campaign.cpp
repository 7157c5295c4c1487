#include "campaign/campaign.hpp"

#include "core/verdict_inputs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

namespace glrc::campaign {

const char* to_text(ShrinkEnd end) {
  switch (end) {
    case ShrinkEnd::not_asked:
      return "not shrunk (--no-shrink)";
    case ShrinkEnd::complete:
      return "shrunk";
    case ShrinkEnd::out_of_time:
      return "shrunk until its time ran out";
    case ShrinkEnd::interrupted:
      return "shrinking stopped by a signal";
  }
  return "shrunk";
}
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
      if (r.outcome == Status::skip) {
        ++st.skipped;
        if (out.skipped.size() < kSkippedExamples)
          out.skipped.push_back(
              {index[k], std::string(generator_for(o.generators, index[k]).name), r.message});
      }
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
        nf.shrink_end = o.shrink ? ShrinkEnd::interrupted : ShrinkEnd::not_asked;
        if (o.shrink && !stop()) {
          ShrinkOptions so = o.shrinking;
          so.stop = progress.stop;
          const Shrunk s = shrink(c, r, f, judge, so);
          nf.minimal = s.minimal;
          nf.minimal_result = s.result;
          nf.shrink_steps = s.steps, nf.shrink_checks = s.checks;
          nf.shrink_seconds = s.seconds, nf.shrink_complete = s.complete;
          nf.shrink_end = s.complete ? ShrinkEnd::complete
                          : stop()   ? ShrinkEnd::interrupted
                                     : ShrinkEnd::out_of_time;
        }
        nf.minimal.name = failure_file_name(f).substr(0, failure_file_name(f).size() - 5);
        nf.minimal.description = "Found by glrefcheck fuzz (" + replay_command(nf) + "), " +
                                 to_text(nf.shrink_end) + ": " + describe(f, nf.minimal_result);
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

namespace {

nlohmann::json stats_json(const CampaignStats& s) {
  return {{"cases", s.cases},
          {"triangles", s.triangles},
          {"pixels", s.pixels},
          {"failing_cases", s.failing_cases},
          {"skipped", s.skipped},
          {"seconds", s.seconds},
          {"checking_seconds", s.checking_seconds},
          {"triangles_per_second", s.triangles_per_second()},
          {"interrupted", s.interrupted}};
}

}  // namespace

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
  // One case replayed (fuzz --replay S:I): no campaign's shard, which merge refuses.
  if (r.options.only_index) campaign["replay"] = *r.options.only_index;
  // How the failures were shrunk: a shard shrunk otherwise has other minimal cases.
  campaign["shrink"] = r.options.shrink;
  campaign["shrink_seconds"] = r.options.shrinking.seconds;
  const nlohmann::json stats = stats_json(r.stats);
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
  nlohmann::json skipped = nlohmann::json::array();
  for (const SkippedCase& k : r.skipped)
    skipped.push_back(
        {{"index", k.index},
         {"generator", k.generator},
         {"replay", "glrefcheck fuzz --generator " + k.generator + " --replay " +
                        std::to_string(r.options.seed) + ":" + std::to_string(k.index)},
         {"message", k.message}});
  return {{"campaign", campaign},
          {"run", run},
          {"stats", stats},
          {"failures", failures},
          {"skipped", skipped}};
}

bool is_campaign_json(const nlohmann::json& results) {
  return results.is_object() && results.contains("campaign") && results.contains("stats") &&
         results.contains("failures");
}

namespace {

// A field of a shard, checked: one line naming the shard and the field otherwise.
const nlohmann::json& field(const nlohmann::json& j, const std::string& source,
                            const std::string& path, const char* key,
                            nlohmann::json::value_t type) {
  const std::string where = path.empty() ? key : path + "." + key;
  if (!j.is_object() || !j.contains(key))
    throw std::runtime_error(source + ": " + where + ": expected a field, got none");
  const nlohmann::json& v = j.at(key);
  const bool number = type == nlohmann::json::value_t::number_float;
  const bool unsigned_ok = type == nlohmann::json::value_t::number_unsigned;
  if ((number && !v.is_number()) || (unsigned_ok && !v.is_number_unsigned()) ||
      (!number && !unsigned_ok && v.type() != type))
    throw std::runtime_error(source + ": " + where + ": expected " +
                             (number        ? "a number"
                              : unsigned_ok ? "a whole number"
                                            : std::string(nlohmann::json(type).type_name())) +
                             ", got " + v.dump().substr(0, 80));
  return v;
}

// A shard's stats, each field checked, and checked against the others as a campaign counts them:
// one line naming the shard and the field for a hand-edited or damaged one.
CampaignStats checked_stats(const nlohmann::json& shard, const std::string& source) {
  using T = nlohmann::json::value_t;
  const auto& j = field(shard, source, "", "stats", T::object);
  const auto whole = [&](const char* key) {
    return field(j, source, "stats", key, T::number_unsigned).get<uint64_t>();
  };
  const auto seconds = [&](const char* key) {
    const double v = field(j, source, "stats", key, T::number_float).get<double>();
    if (!std::isfinite(v) || v < 0)
      throw std::runtime_error(source + ": stats." + key +
                               ": expected a finite number of seconds, 0 or more, got " +
                               j.at(key).dump());
    return v;
  };
  CampaignStats s;
  s.cases = whole("cases"), s.triangles = whole("triangles"), s.pixels = whole("pixels");
  s.failing_cases = whole("failing_cases"), s.skipped = whole("skipped");
  s.seconds = seconds("seconds"), s.checking_seconds = seconds("checking_seconds");
  // Failing and skipped cases are among the cases; the checking is part of the campaign's time.
  for (const auto& [key, n] : {std::pair{"failing_cases", s.failing_cases}, {"skipped", s.skipped}})
    if (n > s.cases)
      throw std::runtime_error(source + ": stats." + key + ": expected at most stats.cases (" +
                               std::to_string(s.cases) + "), got " + std::to_string(n));
  if (s.checking_seconds > s.seconds)
    throw std::runtime_error(source + ": stats.checking_seconds: expected at most stats.seconds (" +
                             j.at("seconds").dump() + "), got " + j.at("checking_seconds").dump());
  return s;
}

// Two shards' stats added, a count that would pass 2^64 refused (a forged shard, not a campaign).
CampaignStats summed(const CampaignStats& a, const CampaignStats& b, const std::string& source) {
  const auto add = [&](uint64_t x, uint64_t y, const char* key) {
    if (y > std::numeric_limits<uint64_t>::max() - x)
      throw std::runtime_error(source + ": stats." + key +
                               ": expected a count the shards' sum can hold, got " +
                               std::to_string(y) + " after " + std::to_string(x) +
                               " in the shards before (one of them forged?)");
    return x + y;
  };
  CampaignStats s;
  s.cases = add(a.cases, b.cases, "cases");
  s.triangles = add(a.triangles, b.triangles, "triangles");
  s.pixels = add(a.pixels, b.pixels, "pixels");
  s.failing_cases = add(a.failing_cases, b.failing_cases, "failing_cases");
  s.skipped = add(a.skipped, b.skipped, "skipped");
  s.seconds = a.seconds + b.seconds;
  s.checking_seconds = a.checking_seconds + b.checking_seconds;
  return s;
}

// A shard's run.verdict_inputs (absent in results before they were recorded: none).
std::map<std::string, std::string> verdict_inputs(const nlohmann::json& run,
                                                  const std::string& source) {
  std::map<std::string, std::string> inputs;
  if (!run.is_object() || !run.contains("verdict_inputs")) return inputs;
  const auto& j = run.at("verdict_inputs");
  if (!j.is_object())
    throw std::runtime_error(source + ": run.verdict_inputs: expected an object, got " +
                             j.dump().substr(0, 80));
  for (const auto& [name, value] : j.items()) {
    if (!value.is_string())
      throw std::runtime_error(source + ": run.verdict_inputs." + name + ": expected text, got " +
                               value.dump().substr(0, 80));
    inputs[name] = value.get<std::string>();
  }
  return inputs;
}

}  // namespace

nlohmann::json merge_campaigns(const std::vector<nlohmann::json>& shards,
                               const std::vector<std::string>& sources, std::vector<size_t>& from) {
  using T = nlohmann::json::value_t;
  if (shards.empty()) throw std::runtime_error("no campaign shards");
  const auto& first = field(shards[0], sources[0], "", "campaign", T::object);
  const uint64_t fraction = field(first, sources[0], "campaign", "fraction", T::number_unsigned);
  std::vector<bool> seen(fraction + 1, false);
  nlohmann::json merged = shards[0];
  merged.erase("written_by");  // the shard's stamp: the merge's own comes when it is written
  // The run of the first shard that had GL (one of no case never started it): what the others'
  // GL is compared with, and the merged campaign's.
  nlohmann::json gl_run = shards[0].value("run", nlohmann::json::object());
  for (const nlohmann::json& shard : shards)
    if (const auto run = shard.value("run", nlohmann::json::object());
        !run.value("gl_renderer", std::string()).empty()) {
      gl_run = run;
      break;
    }
  merged["run"] = gl_run;
  CampaignStats total;
  nlohmann::json failures = nlohmann::json::array();
  std::vector<nlohmann::json> skipped;
  std::map<std::string, size_t> by_signature;
  from.clear();
  for (size_t k = 0; k < shards.size(); ++k) {
    const std::string& source = sources[k];
    const auto& campaign = field(shards[k], source, "", "campaign", T::object);
    for (const char* key :
         {"seed", "generators", "count", "seconds", "fraction", "shrink", "shrink_seconds"})
      if (campaign.value(key, nlohmann::json()) != first.value(key, nlohmann::json()))
        throw std::runtime_error(source + ": campaign." + key + ": expected " +
                                 first.value(key, nlohmann::json()).dump() +
                                 " as the first shard, got " +
                                 campaign.value(key, nlohmann::json()).dump().substr(0, 80));
    if (campaign.contains("replay"))
      throw std::runtime_error(source +
                               ": campaign.replay: expected a campaign shard, got one case "
                               "replayed (fuzz --replay): merge joins the shards of one campaign");
    const uint64_t start =
        field(campaign, source, "campaign", "fraction_start", T::number_unsigned);
    if (start < 1 || start > fraction || seen[start])
      throw std::runtime_error(source + ": campaign.fraction_start: expected one of 1.." +
                               std::to_string(fraction) + " not given by another shard, got " +
                               std::to_string(start));
    seen[start] = true;
    const auto& run = shards[k].value("run", nlohmann::json::object());
    const auto& run0 = gl_run;
    // Stopped by a signal: fewer cases than its shard of the campaign.
    if (shards[k].value("run", nlohmann::json::object()).value("interrupted", false) ||
        shards[k].value("stats", nlohmann::json::object()).value("interrupted", false))
      throw std::runtime_error(
          source + ": an interrupted campaign shard (stopped by a signal): run it again");
    // The options asked for first: shards of two backends differ in their GL library too, and
    // the backend is the difference to name.
    // A shard of no case (more shards than cases) never started GL: its GL fields say nothing.
    const bool gl = !run.value("gl_renderer", std::string()).empty() &&
                    !run0.value("gl_renderer", std::string()).empty();
    std::vector<const char*> keys = {"backend", "driver", "mesa_prefix"};
    if (gl)
      keys.insert(keys.end(), {"gl_renderer", "gl_version", "gl_library", "model", "tolerance",
                               "subpixel_bits"});
    for (const char* key : keys)
      if (run.value(key, nlohmann::json()) != run0.value(key, nlohmann::json()))
        throw std::runtime_error(
            source + ": run." + key + ": expected " + run0.value(key, nlohmann::json()).dump() +
            " as the first shard, got " + run.value(key, nlohmann::json()).dump().substr(0, 80));
    if (const auto d =
            verdict_input_difference(verdict_inputs(run, source), verdict_inputs(run0, sources[0])))
      throw std::runtime_error(source + ": expected shards judged alike, got " + d->name + " " +
                               d->value + " where " + sources[0] + " has " + d->other +
                               ": run the shards with the same options and files");
    const CampaignStats shard_stats = checked_stats(shards[k], source);
    // A campaign of --count C draws indices 0 .. C - 1; shard K of N those of K - 1 + j·N: all
    // of them unless --time stopped it first.
    if (const auto& count = campaign.value("count", nlohmann::json()); count.is_number_unsigned()) {
      const uint64_t c = count.get<uint64_t>();
      const uint64_t drawn = c > start - 1 ? (c - start) / fraction + 1 : 0;
      const bool timed = !campaign.value("seconds", nlohmann::json()).is_null();
      if (timed ? shard_stats.cases > drawn : shard_stats.cases != drawn)
        throw std::runtime_error(source + ": stats.cases: expected " + (timed ? "at most " : "") +
                                 std::to_string(drawn) + " (shard " + std::to_string(start) +
                                 " of " + std::to_string(fraction) + " of a " + std::to_string(c) +
                                 "-case campaign), got " + std::to_string(shard_stats.cases));
    }
    total = k == 0 ? shard_stats : summed(total, shard_stats, source);
    // The first skipped cases of every shard; the first of them all are the unsharded ones'.
    if (shards[k].contains("skipped")) {
      const auto& list = field(shards[k], source, "", "skipped", T::array);
      for (size_t i = 0; i < list.size(); ++i) {
        field(list[i], source, "skipped[" + std::to_string(i) + "]", "index", T::number_unsigned);
        skipped.push_back(list[i]);
      }
    }
    const auto& list = field(shards[k], source, "", "failures", T::array);
    std::set<std::string> shard_signatures;  // each distinct failure once per shard
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string path = "failures[" + std::to_string(i) + "]";
      const auto& f = list[i];
      const std::string signature = field(f, source, path, "signature", T::string);
      const uint64_t index = field(f, source, path, "index", T::number_unsigned);
      const uint64_t cases = field(f, source, path, "cases", T::number_unsigned);
      if (!shard_signatures.insert(signature).second)
        throw std::runtime_error(source + ": " + path +
                                 ".signature: expected a failure no other "
                                 "of the shard's has, got \"" +
                                 signature.substr(0, 80) + "\" again");
      // Shard K of N draws the indices K - 1 + j·N only.
      if (index % fraction != start - 1)
        throw std::runtime_error(source + ": " + path + ".index: expected an index of shard " +
                                 std::to_string(start) + " of " + std::to_string(fraction) +
                                 ", got " + std::to_string(index));
      // Each failing case counts once per signature it shows.
      if (cases < 1 || cases > shard_stats.failing_cases)
        throw std::runtime_error(
            source + ": " + path + ".cases: expected 1 to stats.failing_cases (" +
            std::to_string(shard_stats.failing_cases) + "), got " + std::to_string(cases));
      const auto& examples = field(f, source, path, "examples", T::array);
      const auto at = by_signature.find(signature);
      if (at == by_signature.end()) {
        by_signature[signature] = failures.size();
        failures.push_back(f);
        from.push_back(k);
        continue;
      }
      nlohmann::json& m = failures[at->second];
      std::vector<uint64_t> all = m["examples"].get<std::vector<uint64_t>>();
      for (const auto& e : examples)
        all.push_back(e.get<uint64_t>());
      std::sort(all.begin(), all.end());
      all.resize(std::min<size_t>(all.size(), 8));
      const uint64_t showing = m["cases"].get<uint64_t>() + cases;
      if (index < m["index"].get<uint64_t>()) {
        m = f;
        from[at->second] = k;
      }
      m["cases"] = showing;
      m["examples"] = all;
    }
  }
  for (uint64_t start = 1; start <= fraction; ++start)
    if (!seen[start])
      throw std::runtime_error("shard " + std::to_string(start) + " of " +
                               std::to_string(fraction) + " is missing");
  // In the order the unsharded campaign meets them: by the index that first showed each.
  std::vector<size_t> order(failures.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return failures[a]["index"].get<uint64_t>() < failures[b]["index"].get<uint64_t>();
  });
  nlohmann::json sorted = nlohmann::json::array();
  std::vector<size_t> sorted_from;
  for (const size_t i : order) {
    sorted.push_back(failures[i]);
    sorted_from.push_back(from[i]);
  }
  from = sorted_from;
  merged["failures"] = sorted;
  std::stable_sort(skipped.begin(), skipped.end(), [](const auto& a, const auto& b) {
    return a["index"].template get<uint64_t>() < b["index"].template get<uint64_t>();
  });
  skipped.resize(std::min(skipped.size(), kSkippedExamples));
  merged["skipped"] = skipped;
  merged["campaign"]["fraction"] = 1;
  merged["campaign"]["fraction_start"] = 1;
  merged["campaign"]["merged_shards"] = shards.size();
  merged["stats"] = stats_json(total);
  // The whole campaign's cases, as one unsharded run's record says them.
  if (merged.contains("run") && merged["run"].is_object())
    merged["run"]["total_cases"] = total.cases;
  return merged;
}

}  // namespace glrc::campaign
