// Shards of one sharded run merged back into the run they split (`glrefcheck merge`), and the
// summary line every run and merge ends with. Shards come from `run --fraction N
// --fraction-start K` as deqp-runner shards: case j of shard K is case K - 1 + j·N of the suite.
#pragma once

#include <string>
#include <vector>

#include "core/result.hpp"
#include "report/report.hpp"

namespace glrc::report {

// The whole run from its shards (`names[k]` names shards[k] in messages): every shard of one
// --fraction exactly once, of one suite, none interrupted, on the same GL, backend, model and
// tolerance; their cases interleaved back into the suite's order. The run's seconds are the
// longest shard's (shards run side by side), its jobs the sum. Throws std::runtime_error,
// one line starting "merge: " and naming the shard, on anything else; every field read from
// a file is checked before it sizes anything.
RunResults merge_shards(const std::vector<RunResults>& shards,
                        const std::vector<std::string>& names);

// The summary line: "45 cases: 42 pass, 0 fail, ..., 0 error, 0 skip in 1.23 s", every status
// that occurred, in a fixed order.
std::string run_summary(const std::vector<CaseResult>& results, double seconds);
// Whether any result fails the run (fails_run).
bool any_fails_run(const std::vector<CaseResult>& results);

}  // namespace glrc::report
