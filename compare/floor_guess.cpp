#include "compare/floor_guess.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "compare/comparator_state.hpp"
#include "compare/run_bounds.hpp"
#include "core/parallel.hpp"

namespace glrc::compare {

std::optional<double> floor_share(const ChannelAccumulator& acc, double plain, double pixels,
                                  size_t sampled, double margin) {
  constexpr int kRun = RunGrid::kRun;
  const double share = margin * double(acc.ulps.kept_after_compaction()) / (plain * kRun);
  if (plain * kRun * 2 < pixels || sampled < kFewestFloorSamples || share > 0.25)
    return std::nullopt;
  return share;
}

void sample_floor_keys(const std::vector<int32_t>& plain_runs, const UlpTable& table,
                       const ChannelAllowance& allowance, const Frame& reference,
                       const float* gl_values, const float* own_values, Channel ch,
                       const Comparator::ChannelBounds* bounds, std::vector<uint32_t>& ulps,
                       std::vector<uint32_t>& ratios) {
  constexpr int kSampledRuns = 4;  // run_bounds' sample too: one plain run in four
  constexpr int kRun = RunGrid::kRun;
  const RunGrid grid{reference.width, reference.height};
  // One pixel of each plain run, at an offset that moves from run to run; with bounds,
  // kSampledRuns neighbouring pixels of each run whose bounds run_bounds found (one in
  // kSampledRuns: as many pixels), each run's hi standing for the pixels' allowances.
  const int per_run = bounds ? kSampledRuns : 1;
  struct Sample {
    size_t run, first;
  };
  std::vector<Sample> samples;
  for (int row = 0; row < reference.height; ++row)
    for (int r = 0; r < grid.whole_runs_per_row(); ++r) {
      const size_t run = grid.index(row, r);
      if (plain_runs[run] < 0 || (bounds && !bounds->runs[run].computed)) continue;
      samples.push_back(
          {run, reference.index(r * kRun + (row * 37 + r * 11) % (kRun - per_run + 1), row)});
    }
  const float* own_allowed = allowance.per_pixel_values();
  ulps.reserve(ulps.size() + samples.size() * size_t(per_run));
  ratios.reserve(ratios.size() + samples.size() * size_t(per_run));
  for (size_t s = 0; s < samples.size(); ++s) {
    {
      // A sample's pixels are a row or more from the last one's: in no cache line the
      // processor fetches ahead by itself (measured on the quad: without this, nine tenths of
      // the sampling's time was spent waiting for them).
      const size_t ahead = samples[std::min(s + kPrefetchAhead, samples.size() - 1)].first;
      __builtin_prefetch(gl_values + ahead);
      __builtin_prefetch(own_values + ahead);
      // The allowance held per pixel (not a deferred one's) is a third such line: the quad's
      // comparison against an allowance held per pixel (diff's) took 70.3-72.2 ms of CPU
      // without this, 67.1-69.0 ms with it.
      if (own_allowed) __builtin_prefetch(own_allowed + ahead);
    }
    const size_t run = samples[s].run, first = samples[s].first;
    const int32_t p = plain_runs[run];
    for (size_t i = first; i < first + size_t(per_run); ++i) {
      const float g = gl_values[i], v = own_values[i];
      if (!std::isfinite(g) || !std::isfinite(v)) continue;
      const double ulp = table.ulp(p, ch);
      const double allowed = bounds ? bounds->runs[run].hi : allowance.at(i, ulp);
      const double abs_error = std::fabs(double(g) - double(v));
      ulps.push_back(order_key(float(abs_error * table.inverse_ulp(p, ch))));
      ratios.push_back(order_key(float(abs_error == 0 ? 0.0
                                       : allowed > 0  ? abs_error / allowed
                                                      : kInf)));
    }
  }
}

void assume_sampled_floors(ChannelAccumulator& acc, std::vector<uint32_t>& ulps,
                           std::vector<uint32_t>& ratios, double share) {
  if (ulps.size() < kFewestFloorSamples) return;
  const auto floor_of = [&](std::vector<uint32_t>& keys) -> std::optional<uint32_t> {
    const auto nth = keys.end() - ptrdiff_t(std::max(1.0, double(keys.size()) * share));
    std::nth_element(keys.begin(), nth, keys.end());
    uint32_t below = 0;
    for (auto it = keys.begin(); it != nth; ++it)
      if (*it < *nth) below = std::max(below, *it);
    if (below <= order_key(0.0f) || below >= order_key(std::numeric_limits<float>::infinity()))
      return std::nullopt;
    return below;
  };
  if (const auto floor = floor_of(ulps)) acc.ulps.assume_floor(*floor);
  if (const auto floor = floor_of(ratios)) acc.ratios.assume_floor(*floor);
}

void assume_floors(ChannelAccumulator& acc, const std::vector<int32_t>& plain_runs,
                   const UlpTable& table, const ChannelAllowance& allowance, const Frame& reference,
                   const float* gl_values, const float* own_values, Channel ch,
                   const Comparator::ChannelBounds* bounds) {
  const size_t plain =
      size_t(std::count_if(plain_runs.begin(), plain_runs.end(), [](int32_t p) { return p >= 0; }));
  const auto share = floor_share(acc, double(plain), double(reference.pixel_count()), plain);
  if (!share) return;
  std::vector<uint32_t> ulps, ratios;
  sample_floor_keys(plain_runs, table, allowance, reference, gl_values, own_values, ch, bounds,
                    ulps, ratios);
  assume_sampled_floors(acc, ulps, ratios, *share);
}

void Comparator::add_floor_sample(const Expectation& expected, const Frame& gl) {
  State& st = *state_;
  const Frame& reference = expected.frame;
  if (st.next_row != 0)
    throw std::logic_error("Comparator: a floor sample after the first slice of " + st.c.name);
  if (reference.width != st.width || gl.width != st.width || gl.height != reference.height ||
      reference.height > st.height || gl.components.size() != reference.components.size() ||
      reference.components.size() != size_t(st.c.component_count()) ||
      expected.edges.size() != reference.pixel_count())
    throw std::invalid_argument("compare: a floor sample of another shape for case " + st.c.name);
  // Plain runs as add_rows finds most of them: every pixel plainly its own, of one primitive
  // (a pixel add_rows judges against the reference's own fragment by another way is only left
  // out of the sample).
  constexpr int kRun = RunGrid::kRun;
  const RunGrid grid{reference.width, reference.height};
  const PlainlyOwn plainly_own(st.c, expected, gl);
  std::vector<int32_t> plain(grid.count(), -1);
  size_t plain_count = 0;
  for (int y = 0; y < reference.height; ++y)
    for (int r = 0; r < grid.whole_runs_per_row(); ++r) {
      const size_t first = reference.index(r * kRun, y);
      const int32_t p = reference.primitive[first];
      bool own = true;
      for (size_t i = first; own && i < first + kRun; ++i)
        own = reference.primitive[i] == p && plainly_own(i);
      if (!own) continue;
      plain[grid.index(y, r)] = p;
      ++plain_count;
    }
  st.sampled_rows += size_t(reference.height);
  st.sampled_plain += plain_count;
  st.sampled_ulps.resize(st.channels.size());
  st.sampled_ratios.resize(st.channels.size());
  parallel_for(int(st.channels.size()), st.threads, [&](int slot) {
    const Channel ch = Channel::at_slot(size_t(slot));
    const ChannelAllowance allowance(st.c, expected, st.r.tolerance, ch);
    std::optional<ChannelBounds> bounds;
    if (const DeferredAllowance* deferred = allowance.deferred())
      bounds = run_bounds(*deferred, plain, st.ulps, reference, ch);
    sample_floor_keys(plain, st.ulps, allowance, reference, gl.values(ch).data(),
                      reference.values(ch).data(), ch, bounds ? &*bounds : nullptr,
                      st.sampled_ulps[size_t(slot)], st.sampled_ratios[size_t(slot)]);
  });
}

void Comparator::guess_floors() {
  State& st = *state_;
  if (st.next_row != 0)
    throw std::logic_error("Comparator: floors guessed after the first slice of " + st.c.name);
  if (st.sampled_rows > 0) {
    st.floors_guessed = true;
    // The frame's plain runs as the sample's share of them over its rows.
    const double plain = double(st.sampled_plain) * double(st.height) / double(st.sampled_rows);
    const double pixels = double(st.width) * double(st.height);
    // Twice what a compaction keeps, not one and a half times: sample slices are a few places
    // of the frame, not all of it, and where the largest errors gather in a few of its rows
    // they may be over- or under-represented (the 4096x4096 scene's v6.w with 32 slices of four
    // rows: its shares' floor guessed too high, and the stream compared twice).
    constexpr double kMargin = 2;
    parallel_for(int(st.channels.size()), st.threads, [&](int slot) {
      ChannelAccumulator& acc = st.channels[size_t(slot)];
      if (const auto share = floor_share(acc, plain, pixels, st.sampled_plain, kMargin))
        assume_sampled_floors(acc, st.sampled_ulps[size_t(slot)], st.sampled_ratios[size_t(slot)],
                              *share);
    });
  }
  st.sampled_ulps = {}, st.sampled_ratios = {};
  st.sampled_rows = st.sampled_plain = 0;
}

bool Comparator::floors_held() const {
  for (const ChannelAccumulator& acc : state_->channels)
    if (!acc.ulps.complete() || !acc.ratios.complete()) return false;
  return true;
}

}  // namespace glrc::compare
