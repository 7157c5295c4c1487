// What a Comparator gathers between slices, and what its passes share (internal to compare/).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "compare/channel_accumulator.hpp"
#include "compare/compare.hpp"
#include "compare/run_grid.hpp"

namespace glrc::compare {

// Comparator::State::judgement's values.
inline constexpr uint8_t kNotCompared = 0, kOwn = 1, kCandidate = 2;
// The first coverage mismatches a result keeps.
inline constexpr size_t kMismatchesKept = 64;

struct Comparator::State {
  State(const Case& the_case, const Tolerance& t, int w, int h, int threads_)
      : c(the_case), ulps(the_case), width(w), height(h), threads(threads_) {
    r.name = c.name;
    r.description = c.description;
    r.tolerance = t;
    r.coverage.fragments_checked = true;  // until a slice without counts says otherwise
    const std::vector<std::string> names = component_names(c);
    for (Channel ch : channels_of(int(names.size()))) {
      ChannelAccumulator& acc = channels.emplace_back(size_t(w) * size_t(std::max(h, 0)));
      acc.exact = t.mode == ToleranceMode::exact;
      acc.stats.name = ch.is_depth() ? "depth" : names[size_t(ch.component())];
    }
    fixed_ulps.assign(channels.size(), std::nullopt);
  }

  const Case& c;
  const UlpTable ulps;
  int width, height, next_row = 0;
  int threads;  // channels judged at once
  CaseResult r;
  std::vector<ChannelAccumulator> channels;       // depth, then each component
  std::vector<std::optional<double>> fixed_ulps;  // a channel's fixed allowance, if not per pixel
  // Per pixel of the slice add_rows compares: whether its values are compared, and against the
  // reference's own fragment or a candidate (judged_against), found once for every channel.
  std::vector<uint8_t> judgement;
  // Per run of ChannelAccumulator::kRun pixels of each row of the slice: the primitive when every
  // pixel of it is compared against the reference's own fragment of that primitive, else -1 (a
  // row's last, shorter run always: add_run takes whole runs). The same for every channel, so
  // found once.
  std::vector<int32_t> plain_runs;
  // Per run as plain_runs: 1 when every pixel of a whole run is compared against the reference's
  // own fragment, of whichever primitive (a plain run, or one where triangles meet), else 0.
  std::vector<uint8_t> own_runs;
  // add_floor_sample's keys by channel, and how many rows and plain runs they were taken from.
  std::vector<std::vector<uint32_t>> sampled_ulps, sampled_ratios;
  size_t sampled_rows = 0, sampled_plain = 0;
  bool floors_guessed = false;  // guess_floors() has run on a sample
  // The pixels count_excused found, for finish() to trace (at most kMostTracedPixels).
  struct Excused {
    size_t pixel = 0;  // window index
    CoverageStats::Pixel at;
    std::optional<CoverageStats::Label> label;  // coverage_label's
    CoverageStats::Label untraceable = CoverageStats::Label::fill_rule;
    uint16_t gl_fragments = 0;
  };
  std::vector<Excused> excused;
  uint64_t excused_beyond = 0;  // found beyond kMostTracedPixels
};

// The counter of label l.
inline uint64_t& label_counter(CoverageStats& cov, CoverageStats::Label l) {
  using Label = CoverageStats::Label;
  return l == Label::exact_tie         ? cov.exact_tie
         : l == Label::within_snapping ? cov.within_snapping
         : l == Label::gap             ? cov.gaps
         : l == Label::double_hit      ? cov.double_hits
                                       : cov.fill_rule;
}

// Whether pixel i is one of those most of a frame is: the same drawn triangle in both frames,
// no edge bit, as many fragments (where both frames have counts). judged_against gives such a
// pixel the reference's own fragment and coverage_label nothing, which is all this says
// without calling either. Inlined into add_rows' loop over every pixel.
class PlainlyOwn {
 public:
  PlainlyOwn(const Case& c, const Expectation& expected, const Frame& gl)
      : expected_(expected),
        gl_(gl),
        // coverage_label's own test: these frames both have fragment counts.
        counts_(expected.frame.fragments.size() == expected.frame.pixel_count() &&
                gl.fragments.size() == gl.pixel_count()),
        triangles_(int32_t(std::min<size_t>(c.triangles.size(), INT32_MAX))) {}
  [[gnu::always_inline]] bool operator()(size_t i) const {
    const Frame& reference = expected_.frame;
    const int32_t p = reference.primitive[i];
    return p == gl_.primitive[i] && p >= 0 && p < triangles_ && expected_.edges[i] == 0 &&
           (!counts_ || reference.fragments[i] == gl_.fragments[i]);
  }

 private:
  const Expectation& expected_;
  const Frame& gl_;
  const bool counts_;
  const int32_t triangles_;
};

}  // namespace glrc::compare
