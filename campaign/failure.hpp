// What a failing random case shows, in the few classes a campaign sorts and shrinks by, and a
// signature that tells two failures of one class apart (which channel, which qualifier), so
// that a campaign keeps one minimal case per distinct failure instead of one per case.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/case.hpp"
#include "core/names.hpp"
#include "core/result.hpp"

namespace glrc::campaign {

// In order of precedence: a case showing several is filed under the first.
//   crash, timeout, error: the worker died, ran past --timeout, or GL refused the draw;
//   non_finite:  NaN or Inf where the reference's value is finite;
//   gap, double_hit: a pixel of a shared edge reached by no fragment, or by two;
//   fill_rule:   a coverage difference the specification's freedom does not explain;
//   value:       a value or depth beyond the allowance (or the fixed tolerance).
// boundary: a coverage mismatch within snapping or on an exact tie, a failure only under strict
// coverage (Tolerance::allow_boundary false); its detail names the label.
enum class FailureClass {
  crash,
  timeout,
  error,
  non_finite,
  gap,
  double_hit,
  fill_rule,
  boundary,
  value
};

}  // namespace glrc::campaign

namespace glrc {
template <>
struct Names<campaign::FailureClass> {
  static constexpr std::array<std::pair<campaign::FailureClass, std::string_view>, 9> table{{
      {campaign::FailureClass::crash, "crash"},
      {campaign::FailureClass::timeout, "timeout"},
      {campaign::FailureClass::error, "error"},
      {campaign::FailureClass::non_finite, "non_finite"},
      {campaign::FailureClass::gap, "gap"},
      {campaign::FailureClass::double_hit, "double_hit"},
      {campaign::FailureClass::fill_rule, "fill_rule"},
      {campaign::FailureClass::boundary, "boundary"},
      {campaign::FailureClass::value, "value"},
  }};
};
}  // namespace glrc

namespace glrc::campaign {
struct Failure {
  FailureClass kind = FailureClass::value;
  // What else tells this failure apart, independent of the case's size and names: for
  // non_finite and value the channel's kind ("depth", or the varying's qualifier: "smooth",
  // "flat", "noperspective"); empty for the others.
  std::string detail;
  std::string signature() const;  // "non_finite/noperspective", "gap", "crash"
  bool operator==(const Failure&) const = default;
};

// Every failure result `r` of case `c` shows, in precedence order; empty when it shows none
// (a pass, a skip: beyond GL's specified range or undetermined, and an expected failure is
// judged by its outcome). A Fail whose statistics name no class (it should not happen) is
// `value` with detail "other".
std::vector<Failure> failures_of(const Case& c, const CaseResult& r);

// Why `name` (a --baseline entry) can name no campaign failure, or nothing when it can: a failure
// is named by its minimal case's file stem, the class and its detail joined by '_'
// ("non_finite_noperspective", "gap", "boundary_within_snapping"), not by the signature printed
// with '/'.
std::optional<std::string> failure_name_problem(std::string_view name);

// One line: the failure's class, then the first worst pixel or mismatch the result names
// ("non_finite: v1.y at (12, 7): GL NaN, reference 0.25").
std::string describe(const Failure& f, const CaseResult& r);

}  // namespace glrc::campaign
