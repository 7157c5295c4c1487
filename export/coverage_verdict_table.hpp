// The coverage verdict of a case as data: compare::coverage_verdict at every value of the edge
// bits, every observation and both outcomes of a fragment trace, and whether each label counts
// against the case. The reproducers look a pixel's label up in it (the C file embeds it, the
// shader_test's probes are chosen by it) instead of restating compare/'s rules, so that a rule
// changed there changes what they judge, and a pipeline feature needs changes only in how they
// draw.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "compare/rules.hpp"
#include "core/result.hpp"

namespace glrc::reproducer {

// A label as the C runtime numbers it (export/c_runtime/verdict.c, enum label): 0 for none,
// then exact tie, within snapping, gap, double hit, fill rule.
inline constexpr int kLabelCodes = 6;
uint8_t label_code(const std::optional<CoverageStats::Label>& label);

class CoverageVerdictTable {
 public:
  // Every value the edge bits (core/frame.hpp, edge::) can take.
  static constexpr int kEdgeBitValues = 32;

  // The table of a case whose frames have fragment counts (`counts`), under `tolerance` (which
  // labels the specification's freedom explains pass: Tolerance::allow_boundary; exact mode
  // passes none).
  CoverageVerdictTable(bool counts, const Tolerance& tolerance);

  // label_code of compare::coverage_verdict(edges, counts, gl, trace_admitted).
  uint8_t label(uint8_t edges, const compare::CoverageObservation& gl, bool trace_admitted) const;
  // Whether a pixel labelled `code` fails the case (compare::counts_against; never for 0).
  bool fails(uint8_t code) const { return fails_[code]; }

  bool counts() const { return counts_; }

 private:
  bool counts_;
  // [edges][kept][count][trace admitted]
  std::array<
      std::array<std::array<std::array<uint8_t, 2>, compare::kCountKinds>, compare::kKeptKinds>,
      kEdgeBitValues>
      labels_{};
  std::array<bool, kLabelCodes> fails_{};
};

}  // namespace glrc::reproducer
