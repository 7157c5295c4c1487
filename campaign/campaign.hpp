// A random campaign: generated cases checked in batches, each failure classified, the first
// case of every distinct failure (class and signature) shrunk to a minimal case, and counts of
// what was checked. Knows nothing of GL or processes: the Judge (shrink.hpp) checks cases, in
// `glrefcheck fuzz` on worker processes, in the tests on a planted fault.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "campaign/failure.hpp"
#include "campaign/generators.hpp"
#include "campaign/shrink.hpp"
#include "core/case.hpp"
#include "core/result.hpp"

namespace glrc::campaign {

struct CampaignOptions {
  uint64_t seed = 1;
  // Stop after this many cases of the campaign (over all shards), or after this many seconds,
  // whichever comes first; at least one must be set.
  std::optional<uint64_t> count;
  std::optional<double> seconds;
  std::vector<const Generator*> generators;  // not empty
  // Only this index (--replay S:I without --emit): the campaign of one case.
  std::optional<uint64_t> only_index;
  // Sharding: this campaign checks the indices i with i mod fraction == fraction_start - 1.
  int fraction = 1, fraction_start = 1;
  size_t batch = 16;  // cases handed to the judge at once
  bool shrink = true;
  ShrinkOptions shrinking;
};

// How a failure's shrinking ended: not asked for (--no-shrink), complete (no smaller case fails
// alike), out of time (CampaignOptions::shrinking's budget), or stopped by SIGINT or SIGTERM (or
// never begun, the signal having come first).
enum class ShrinkEnd { not_asked, complete, out_of_time, interrupted };
// "not shrunk (--no-shrink)", "shrunk", "shrunk until its time ran out", "shrinking stopped by a
// signal": how the minimal case's description and fuzz's line say it.
const char* to_text(ShrinkEnd end);

// One distinct failure: the first case that showed it, shrunk.
struct FoundFailure {
  Failure failure;
  std::string generator;
  uint64_t seed = 0, index = 0;   // the case that first showed it
  std::string first_description;  // describe() of that case's result
  Case minimal;                   // named "<signature>" with '/' as '_', described by describe()
  CaseResult minimal_result;
  int shrink_steps = 0, shrink_checks = 0;
  double shrink_seconds = 0;
  bool shrink_complete = false;
  ShrinkEnd shrink_end = ShrinkEnd::not_asked;
  double found_after = 0;          // seconds into the campaign when its first case was checked
  bool known = false;              // listed in the campaign's baseline (set by whoever has one)
  uint64_t cases = 0;              // cases of the campaign showing it
  std::vector<uint64_t> examples;  // the first few of their indices
};

struct CampaignStats {
  uint64_t cases = 0, triangles = 0;
  uint64_t pixels = 0;          // pixels either frame covered, over every case
  uint64_t failing_cases = 0;   // cases that showed at least one failure
  uint64_t skipped = 0;         // beyond GL's specified range, or undetermined: not judged
  double seconds = 0;           // the whole campaign
  double checking_seconds = 0;  // checking generated cases (not shrinking)
  bool interrupted = false;
  // Triangles of generated cases checked per second of checking them.
  double triangles_per_second() const {
    return checking_seconds > 0 ? double(triangles) / checking_seconds : 0;
  }
};

// A case the campaign did not judge (Status::skip: beyond GL's specified range, or NaN or Inf
// where the specification determines no value), kept so that a reader can see why.
struct SkippedCase {
  uint64_t index = 0;
  std::string generator, message;  // the case's generator, and the result's message
};
// How many skipped cases a campaign keeps: the first, by index.
inline constexpr size_t kSkippedExamples = 16;

struct CampaignResult {
  CampaignOptions options;
  CampaignStats stats;
  std::vector<FoundFailure> failures;  // in the order found
  std::vector<SkippedCase> skipped;    // the first kSkippedExamples skipped cases, by index
};

// What the campaign reports as it goes: after every batch (for a progress line), and when a new
// distinct failure is found (before shrinking it) and shrunk. Any may be empty.
struct CampaignProgress {
  std::function<void(const CampaignStats&, size_t distinct)> batch_done;
  std::function<void(const FoundFailure&)> found, shrunk;
  // Whether to stop now (an interrupt): checked between batches and shrink steps.
  std::function<bool()> stop;
};

// The message of a result the judge did not check because the campaign is being interrupted
// (its outcome Skip): such a case is not counted.
extern const char* const kNotChecked;

// Runs the campaign. `judge` checks each batch; a case it could not check should come back as
// a result that shows no failure.
CampaignResult run_campaign(const CampaignOptions& o, const Judge& judge,
                            const CampaignProgress& progress = {});

// The file name of a failure's minimal case in DIR/failures/: the signature, '/' as '_', then
// ".json" ("non_finite_noperspective.json").
std::string failure_file_name(const Failure& f);

// The campaign's results.json: {"campaign": {seed, count, seconds, generators, fraction,
// fraction_start}, "stats": {...}, "failures": [{class, detail, signature, description,
// known, generator, seed, index, replay, found_after_seconds, cases, examples, file, shrink:
// {steps, checks, seconds, complete}, triangles, varyings}]}. `run` is the run's description (GL
// strings and model) as the caller has it, stored as given under "run".
nlohmann::json campaign_json(const CampaignResult& r, const nlohmann::json& run);

// Whether `results` (a results.json's contents) is a campaign's, not a run's.
bool is_campaign_json(const nlohmann::json& results);

// Joins the results.json of a campaign's shards (`fuzz --fraction N --fraction-start K`, each K
// of 1..N once; the same seed, generators and count, on the same GL and model) into the
// results.json of the campaign unsharded, timings aside: counts added up, and each failure
// taken from the shard that met it first (the lowest index, whose minimal case the unsharded
// campaign shrinks too), with the cases and examples of every shard. `from[i]` is the shard of
// merged failure i. `sources` name the shards in messages. Throws std::runtime_error
// ("<source>: campaign.seed: expected 7 as the other shards, got 8") for shards of different
// campaigns, a shard twice or missing, or a field not as campaign_json writes it. A campaign
// bounded by --time has no fixed set of cases: its shards merge, but the result is not the
// unsharded one's.
nlohmann::json merge_campaigns(const std::vector<nlohmann::json>& shards,
                               const std::vector<std::string>& sources, std::vector<size_t>& from);

}  // namespace glrc::campaign
