// Two runs side by side: the classification of every case (regression, fix, ... precision)
// and the growth of its error per channel. The views of a RunComparison are in
// comparison_text.cpp, comparison_markdown.cpp, comparison_json.cpp and html.cpp.
#include "report/run_compare.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

namespace glrc::report {
namespace {

using Kind = CaseChange::Kind;

// Outcomes are pass, fail, crash, timeout, error or skip. The expectation statuses fold into
// them, so that results written by anything that filled `outcome` from `status` still compare
// (deqp-runner's Flake is a case that passed on a retry).
Status outcome_of(Status s) {
  switch (s) {
    case Status::expected_fail:
      return Status::fail;
    case Status::unexpected_pass:
    case Status::flake:
      return Status::pass;
    default:
      return s;
  }
}

bool passes(Status s) {
  return s == Status::pass;
}

// A crash or a timeout checks nothing at all, so reaching one from a failure that still
// compared pixels (or stopped at a GL error) loses information even though both runs fail.
bool unchecked(Status s) {
  return s == Status::crash || s == Status::timeout;
}

Kind classify(Status base, Status current) {
  base = outcome_of(base), current = outcome_of(current);
  if (base == Status::skip || current == Status::skip) return Kind::skipped;
  if (passes(base) != passes(current)) return passes(base) ? Kind::regression : Kind::fix;
  if (base == current) return Kind::unchanged;  // precision is decided from the channels
  return unchecked(current) && !unchecked(base) ? Kind::regression : Kind::changed;
}

// current > factor * max(base, min_ulps). A NaN current is never within any bound; a NaN base
// is no bound at all, so only a NaN current counts.
bool grew(double base, double current, double factor, double min_ulps) {
  if (std::isnan(current)) return true;
  return current > factor * std::max(base, min_ulps);
}

std::vector<ChannelChange> channel_changes(const CaseResult& base, const CaseResult& current,
                                           double factor, double min_ulps) {
  std::vector<ChannelChange> out;
  for (const auto& now : current.channels) {
    if (now.compared == 0) continue;
    const auto before = std::find_if(base.channels.begin(), base.channels.end(),
                                     [&](const ChannelStats& ch) { return ch.name == now.name; });
    if (before == base.channels.end() || before->compared == 0) continue;
    ChannelChange ch;
    ch.channel = now.name;
    ch.base_max_ulps = before->max_ulps, ch.current_max_ulps = now.max_ulps;
    ch.base_p99_ulps = before->p99_ulps, ch.current_p99_ulps = now.p99_ulps;
    ch.base_max_ratio = before->max_ratio, ch.current_max_ratio = now.max_ratio;
    ch.max_grew = grew(ch.base_max_ulps, ch.current_max_ulps, factor, min_ulps);
    ch.p99_grew = grew(ch.base_p99_ulps, ch.current_p99_ulps, factor, min_ulps);
    out.push_back(std::move(ch));
  }
  return out;
}

bool any_grew(const CaseChange& c) {
  return std::any_of(c.channels.begin(), c.channels.end(),
                     [](const ChannelChange& ch) { return ch.max_grew || ch.p99_grew; });
}

}  // namespace

const char* to_string(CaseChange::Kind k) {
  switch (k) {
    case Kind::regression:
      return "regression";
    case Kind::fix:
      return "fix";
    case Kind::changed:
      return "changed";
    case Kind::added:
      return "added";
    case Kind::removed:
      return "removed";
    case Kind::skipped:
      return "skipped";
    case Kind::precision:
      return "precision";
    case Kind::unchanged:
      return "unchanged";
  }
  return "unchanged";
}

size_t RunComparison::count(CaseChange::Kind k) const {
  return size_t(
      std::count_if(cases.begin(), cases.end(), [&](const CaseChange& c) { return c.kind == k; }));
}

// Identical statistics do not mean identical pixels: the frame digests say whether a Mesa change
// touched the rasterizer's output at all.
std::string bits_summary(const RunComparison& c) {
  const size_t n = c.bits_compared(), same = c.bits_identical();
  if (n == 0) return "GL frames: no digests to compare bit for bit";
  if (same == n) return fmt::format("GL frames: all {} bit-identical to base", n);
  return fmt::format("GL frames: {} of {} bit-identical to base, {} with other bits", same, n,
                     n - same);
}

size_t RunComparison::bits_compared() const {
  return size_t(std::count_if(cases.begin(), cases.end(),
                              [](const CaseChange& c) { return c.same_bits.has_value(); }));
}

size_t RunComparison::bits_identical() const {
  return size_t(std::count_if(cases.begin(), cases.end(),
                              [](const CaseChange& c) { return c.same_bits.value_or(false); }));
}

RunComparison compare_runs(const RunResults& base, const RunResults& current, double factor,
                           double min_ulps) {
  RunComparison out;
  out.base = base.run, out.current = current.run;
  out.factor = factor, out.min_ulps = min_ulps;
  for (const auto& [label, side] : {std::pair{"base", &base}, {"current", &current}}) {
    const RunInfo& r = side->run;
    // Its shard's size: every `fraction`-th case from `fraction_start` of `total_cases` (0: a
    // results.json from before the field, which says nothing of it).
    const uint64_t total = r.total_cases, start = uint64_t(std::max(r.fraction_start, 1)),
                   fraction = uint64_t(std::max(r.fraction, 1));
    const uint64_t expected = total >= start ? (total - start) / fraction + 1 : 0;
    if (r.interrupted)
      out.incomplete.push_back(
          fmt::format("{}: interrupted after {} of {} cases", label, side->cases.size(), expected));
    else if (total > 0 && side->cases.size() != expected)
      out.incomplete.push_back(
          fmt::format("{}: {} of {} cases", label, side->cases.size(), expected));
  }
  // Shards of one fraction compare case for case; a shard against the whole suite (or another
  // shard) would call every case outside it removed or added.
  const auto shard = [](const RunInfo& r) {
    return r.fraction > 1 ? fmt::format("shard {} of {}", r.fraction_start, r.fraction)
                          : std::string("the whole suite");
  };
  if (base.run.fraction != current.run.fraction ||
      base.run.fraction_start != current.run.fraction_start)
    out.incomplete.push_back(fmt::format(
        "current: {}, base: {} (merge the shards first, or compare shards of one fraction)",
        shard(current.run), shard(base.run)));

  std::unordered_map<std::string, const CaseResult*> in_base, in_current;
  for (const auto& r : base.cases)
    in_base.emplace(r.name, &r);
  for (const auto& r : current.cases)
    in_current.emplace(r.name, &r);

  for (const auto& now : current.cases) {
    CaseChange c;
    c.name = now.name;
    c.current = now.outcome;
    c.message = now.message;
    const auto found = in_base.find(now.name);
    if (found == in_base.end()) {
      c.kind = Kind::added;
    } else {
      const CaseResult& before = *found->second;
      c.base = before.outcome;
      c.kind = classify(before.outcome, now.outcome);
      c.channels = channel_changes(before, now, factor, min_ulps);
      if (!before.gl_digest.empty() && !now.gl_digest.empty())
        c.same_bits = before.gl_digest == now.gl_digest;
      if (c.kind == Kind::unchanged && any_grew(c)) c.kind = Kind::precision;
    }
    out.cases.push_back(std::move(c));
  }
  for (const auto& before : base.cases) {
    if (in_current.count(before.name)) continue;
    CaseChange c;
    c.name = before.name;
    c.kind = Kind::removed;
    c.base = before.outcome;
    c.message = before.message;
    out.cases.push_back(std::move(c));
  }
  return out;
}

}  // namespace glrc::report
