// The comparator. Coverage first (which primitive covers each pixel), then, where both frames
// agree on the primitive, every varying component and depth, in ULPs of the attribute's scale:
// the coverage pass in coverage_pass.cpp, each channel's values in channel_pass.cpp.
#include "compare/compare.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>

#include "compare/comparator_state.hpp"
#include "compare/floor_guess.hpp"
#include "compare/messages.hpp"
#include "compare/run_bounds.hpp"
#include "core/parallel.hpp"

namespace glrc::compare {

Comparator::Comparator(const Case& c, const Tolerance& tolerance, int width, int height,
                       int threads)
    : state_(std::make_unique<State>(c, tolerance, width, height, thread_count(threads))) {}

Comparator::~Comparator() = default;

void Comparator::add_rows(const Expectation& expected, const Frame& gl, int y0) {
  State& st = *state_;
  const Case& c = st.c;
  const Tolerance& tolerance = st.r.tolerance;
  const Frame& reference = expected.frame;
  const bool spec = tolerance.mode == ToleranceMode::spec;
  if (reference.width != st.width || reference.width != gl.width || reference.height != gl.height ||
      y0 != st.next_row || reference.height < 0 || y0 + reference.height > st.height ||
      reference.components.size() != size_t(c.component_count()) ||
      reference.components.size() != gl.components.size() ||
      expected.edges.size() != reference.pixel_count() ||
      (spec && (expected.allowance_state() == AllowanceState::none ||
                !expected.allowance_shape_error().empty())))
    throw std::invalid_argument("compare: frames of different shape for case " + c.name);
  // A deferred allowance knows the first row of the frame it drew: it must be this slice's.
  if (expected.deferred && expected.deferred->first_row() != y0)
    throw std::invalid_argument("compare: a deferred allowance drawn for rows from " +
                                std::to_string(expected.deferred->first_row()) +
                                " compared as rows from " + std::to_string(y0) + ", for case " +
                                c.name);
  st.next_row += reference.height;

  // Coverage first, then the values where both frames name the same triangle (or GL a
  // candidate of the depth test), channel by channel.
  add_coverage(expected, gl, y0);

  // Then the values, channel by channel (depth, then each component), each in pixel order. The
  // channels share nothing but what they read, so several threads take one each: every
  // channel's figures are the same bits for any number of threads.
  // A frame compared whole guesses its floors from itself, unless they were guessed from
  // sample slices already (a stream of one slice).
  const bool whole = y0 == 0 && reference.height == st.height && !st.floors_guessed;
  parallel_for(int(st.channels.size()), st.threads, [&](int slot) {
    if (whole)
      add_whole_channel(expected, gl, Channel::at_slot(size_t(slot)));
    else
      add_slice_channel(expected, gl, y0, Channel::at_slot(size_t(slot)));
  });
}

void Comparator::add_whole_channel(const Expectation& expected, const Frame& gl, Channel ch) {
  State& st = *state_;
  ChannelAccumulator& acc = st.channels[ch.slot()];
  const ChannelAccumulator before = acc;
  const Frame& reference = expected.frame;
  const ChannelAllowance allowance(st.c, expected, st.r.tolerance, ch);
  std::optional<ChannelBounds> bounds;
  if (const DeferredAllowance* deferred = allowance.deferred())
    bounds = run_bounds(*deferred, st.plain_runs, st.ulps, reference, ch);
  ChannelBounds* known = bounds ? &*bounds : nullptr;
  assume_floors(acc, st.plain_runs, st.ulps, allowance, reference, gl.values(ch).data(),
                reference.values(ch).data(), ch, known);
  add_channel(expected, gl, 0, ch, known);
  if (acc.ulps.complete() && acc.ratios.complete()) return;
  acc = before;
  add_channel(expected, gl, 0, ch, known);
}

void Comparator::add_slice_channel(const Expectation& expected, const Frame& gl, int y0,
                                   Channel ch) {
  State& st = *state_;
  const ChannelAllowance allowance(st.c, expected, st.r.tolerance, ch);
  const DeferredAllowance* deferred = allowance.deferred();
  if (!deferred) return add_channel(expected, gl, y0, ch);
  // The slice's bounds as a whole frame's (run_bounds); the largest allowance the channel
  // certainly has is also the largest of the slices before (the tally's: it only grows). Its
  // floors are not guessed from the slice: a slice cannot be compared again should they not hold
  // (the caller may guess them from sample slices first: guess_floors).
  ChannelBounds bounds = run_bounds(*deferred, st.plain_runs, st.ulps, expected.frame, ch);
  bounds.largest_lo =
      std::max(bounds.largest_lo, st.channels[ch.slot()].tally.largest_allowance_ulps);
  add_channel(expected, gl, y0, ch, &bounds);
}

void Comparator::trace_excused(CoverageStats& cov, const TraceSource* traces) {
  State& st = *state_;
  cov.counts_untraced += st.excused_beyond;
  if (st.excused.empty()) return;
  if (!traces || !traces->gl || !traces->choices) {
    cov.counts_untraced += st.excused.size();
    return;
  }
  std::vector<size_t> pixels;
  pixels.reserve(st.excused.size());
  for (const State::Excused& e : st.excused)
    pixels.push_back(e.pixel);
  const std::vector<std::optional<FragmentTrace>> gl = traces->gl(pixels);
  const std::vector<FragmentChoices> choices = traces->choices(pixels);
  if (gl.size() != pixels.size() || choices.size() != pixels.size())
    throw std::logic_error("compare: a trace source gave " + std::to_string(gl.size()) +
                           " traces and " + std::to_string(choices.size()) + " choices for " +
                           std::to_string(pixels.size()) + " pixels");
  const Tolerance& t = st.r.tolerance;
  for (size_t k = 0; k < pixels.size(); ++k) {
    const State::Excused& e = st.excused[k];
    // A trace of another count than the frame's is not this frame's (a fault planted in the
    // frame alone, or a pass that went wrong): not judged.
    const std::optional<std::vector<FragmentTrace>> allowed =
        gl[k] && gl[k]->count == e.gl_fragments ? admitted(choices[k]) : std::nullopt;
    if (!allowed) {
      ++cov.counts_untraced;
      continue;
    }
    ++cov.counts_traced;
    const auto key = [](const FragmentTrace& i) { return std::tie(i.count, i.id_sum, i.hash_sum); };
    if (std::binary_search(allowed->begin(), allowed->end(), *gl[k],
                           [&](const auto& a, const auto& b) { return key(a) < key(b); }))
      continue;
    // No conforming implementation rasterizes these fragments here: the count's own label.
    if (e.label) {
      --label_counter(cov, *e.label);
      if (explained(*e.label)) --cov.boundary;
      if (counts_against(*e.label, t)) --cov.failures;
    }
    ++label_counter(cov, e.untraceable);
    ++cov.failures;
    CoverageStats::Pixel at = e.at;
    at.label = e.untraceable, at.boundary = false;
    cov.traced_failures.push_back(at);
    const auto kept = std::find_if(cov.mismatches.begin(), cov.mismatches.end(),
                                   [&](const auto& m) { return m.x == at.x && m.y == at.y; });
    if (kept != cov.mismatches.end())
      *kept = at;
    else if (cov.mismatches.size() < kMismatchesKept)
      cov.mismatches.push_back(at);
  }
}

CaseResult Comparator::finish(const TraceSource* traces) {
  State& st = *state_;
  trace_excused(st.r.coverage, traces);
  CaseResult r = std::move(st.r);
  for (size_t slot = 0; slot < st.channels.size(); ++slot) {
    ChannelAccumulator& acc = st.channels[slot];
    acc.stats.tolerance_ulps =
        st.fixed_ulps[slot] ? *st.fixed_ulps[slot] : acc.tally.largest_allowance_ulps;
    r.channels.push_back(acc.finish());
  }
  const Case& c = st.c;
  const auto& cov = r.coverage;
  bool pass = cov.failures == 0;
  for (const auto& ch : r.channels)
    pass = pass && ch.pass();
  r.status = pass ? Status::pass : Status::fail;
  if (!pass) r.message = failure_message(r);
  // A NaN or Inf where the specification determines no value (value_determined) is no failure,
  // and no pass either.
  if (pass)
    for (size_t slot = 0; slot < st.channels.size(); ++slot)
      if (const auto& p = st.channels[slot].undetermined_non_finite) {
        r.status = Status::skip;
        r.message = undetermined_message(r.channels[slot].name, *p);
        break;
      }
  // Beyond the magnitudes GL guarantees, a difference is no failure of the implementation.
  if (const auto why = pass ? std::nullopt : outside_specified_range(c)) {
    r.status = Status::skip;
    r.message = "outside GL's specified range: " + *why + "; GL drew: " + r.message;
  }
  r.outcome = r.status;
  return r;
}

CaseResult compare(const Case& c, const Expectation& expected, const Frame& gl,
                   const Tolerance& tolerance, int threads, const TraceSource* traces) {
  Comparator comparator(c, tolerance, expected.frame.width, expected.frame.height, threads);
  comparator.add_rows(expected, gl, 0);
  return comparator.finish(traces);
}

}  // namespace glrc::compare
