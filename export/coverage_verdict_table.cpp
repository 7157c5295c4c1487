#include "export/coverage_verdict_table.hpp"

#include "core/expectation.hpp"

namespace glrc::reproducer {

static_assert((edge::tie | edge::snapping | edge::shared | edge::unstable | edge::depth_order) ==
                  CoverageVerdictTable::kEdgeBitValues - 1,
              "the verdict table has a row for every value of the edge bits");

uint8_t label_code(const std::optional<CoverageStats::Label>& label) {
  using Label = CoverageStats::Label;
  if (!label) return 0;
  switch (*label) {
    case Label::exact_tie:
      return 1;
    case Label::within_snapping:
      return 2;
    case Label::gap:
      return 3;
    case Label::double_hit:
      return 4;
    case Label::fill_rule:
      return 5;
  }
  return 5;
}

CoverageVerdictTable::CoverageVerdictTable(bool counts, const Tolerance& tolerance)
    : counts_(counts) {
  using Label = CoverageStats::Label;
  using Observation = compare::CoverageObservation;
  for (int edges = 0; edges < kEdgeBitValues; ++edges)
    for (int kept = 0; kept < compare::kKeptKinds; ++kept)
      for (int count = 0; count < compare::kCountKinds; ++count)
        for (int admitted = 0; admitted < 2; ++admitted)
          labels_[size_t(edges)][size_t(kept)][size_t(count)][size_t(admitted)] =
              label_code(compare::coverage_verdict(
                  uint8_t(edges), counts, {Observation::Kept(kept), Observation::Count(count)},
                  admitted != 0));
  for (const Label l :
       {Label::exact_tie, Label::within_snapping, Label::gap, Label::double_hit, Label::fill_rule})
    fails_[label_code(l)] = compare::counts_against(l, tolerance);
}

uint8_t CoverageVerdictTable::label(uint8_t edges, const compare::CoverageObservation& gl,
                                    bool trace_admitted) const {
  return labels_.at(edges)[size_t(gl.kept)][size_t(gl.count)][trace_admitted ? 1 : 0];
}

}  // namespace glrc::reproducer
