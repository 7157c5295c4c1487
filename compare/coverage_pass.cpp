// The coverage of a slice (Comparator::add_rows' first pass): which primitive covers each pixel
// in both frames, the mismatches labelled (coverage_label) and counted, and for every pixel
// whether its values are compared, and against what, for the channel passes after it.
#include <algorithm>
#include <vector>

#include "compare/comparator_state.hpp"
#include "core/parallel.hpp"

namespace glrc::compare {

// One pass over a slice's pixels, on every thread: blocks of rows, each counted apart and added
// in order, so that the counts are sums and the first mismatches kept are the first of the
// blocks' own first ones, in order. Which pixels are compared is kept as one byte per pixel of
// the slice (State::judgement), with the slice's plain and own runs (State::plain_runs,
// State::own_runs); a candidate is looked up again in each channel's pass (rare: only where
// the depth test's order is free).
class Comparator::CoveragePass {
 public:
  CoveragePass(State& st, const Expectation& expected, const Frame& gl, int y0)
      : st_(st),
        expected_(expected),
        reference_(expected.frame),
        gl_(gl),
        y0_(y0),
        grid_{reference_.width, reference_.height},
        plainly_own_(st.c, expected, gl),
        counts_(counts_checked(expected, gl)) {}

  void run() {
    st_.judgement.resize(reference_.pixel_count());
    judgement_ = st_.judgement.data();
    CoverageStats& cov = st_.r.coverage;
    cov.fragments_checked = cov.fragments_checked && counts_;
    st_.plain_runs.assign(grid_.count(), -1);
    st_.own_runs.assign(st_.plain_runs.size(), 0);
    const int blocks = std::clamp(4 * st_.threads, 1, std::max(reference_.height, 1));
    std::vector<Block> parts(static_cast<size_t>(blocks));
    parallel_for(blocks, st_.threads, [&](int b) {
      const int first = int(int64_t(reference_.height) * b / blocks);
      const int end = int(int64_t(reference_.height) * (b + 1) / blocks);
      for (int y = first; y < end; ++y) {
        for (int x = 0; x < reference_.width; ++x)
          judge(x, y, parts[size_t(b)]);
        find_runs(y);
      }
    });
    for (const Block& part : parts)
      add(part);
  }

 private:
  // A block of rows' counts, and the pixels whose fragment counts it found excused.
  struct Block {
    CoverageStats counts;
    std::vector<State::Excused> excused;
  };

  // Pixel (x, y) of the slice: whether its values are compared, and against what; a mismatch
  // labelled and counted.
  void judge(int x, int y, Block& block) {
    const size_t i = reference_.index(x, y);
    CoverageStats& cv = block.counts;
    if (plainly_own_(i)) {
      judgement_[i] = kOwn;
      ++cv.both;
      return;
    }
    const Tolerance& tolerance = st_.r.tolerance;
    const int32_t pr = reference_.primitive[i], pg = gl_.primitive[i];
    const Judged judged = judged_against(st_.c, expected_, gl_, i, tolerance);
    judgement_[i] = !judged.compared ? kNotCompared : judged.candidate ? kCandidate : kOwn;
    if (pr == pg && pr == Frame::kNoPrimitive) {
      ++cv.neither;
    } else if (judged.compared) {
      ++cv.both;
    } else if (pg == Frame::kNoPrimitive) {
      ++cv.reference_only;
    } else if (pr == Frame::kNoPrimitive) {
      ++cv.gl_only;
    } else {
      ++cv.other_primitive;
    }
    using Label = CoverageStats::Label;
    const uint8_t edges = expected_.edges[i];
    const CoverageObservation seen = observe(expected_, gl_, i);
    const std::optional<Label> label = coverage_label(edges, counts_, seen);
    if (count_excused(edges, counts_, label, seen.count))
      block.excused.push_back(
          {size_t(y0_ + y) * size_t(st_.width) + size_t(x),
           {x, y0_ + y, pr, pg, label && explained(*label), label.value_or(Label::within_snapping)},
           label,
           untraceable_label(edges, seen.count),
           gl_.fragments[i]});
    if (!label) return;
    ++label_counter(cv, *label);
    const bool free = explained(*label);
    if (free) ++cv.boundary;
    if (counts_against(*label, tolerance)) ++cv.failures;
    if (cv.mismatches.size() < kMismatchesKept)
      cv.mismatches.push_back({x, y0_ + y, pr, pg, free, *label});
  }

  // Row y's plain and own runs, now that its judgement is known (whole runs only: add_run's).
  void find_runs(int y) {
    constexpr int kRun = RunGrid::kRun;
    for (int r = 0; r < grid_.whole_runs_per_row(); ++r) {
      const size_t first_pixel = reference_.index(r * kRun, y);
      const int32_t p = reference_.primitive[first_pixel];
      bool own = true, plain = true;
      for (int j = 0; j < kRun; ++j) {
        own = own && judgement_[first_pixel + size_t(j)] == kOwn;
        plain = plain && reference_.primitive[first_pixel + size_t(j)] == p;
      }
      const size_t run = grid_.index(y, r);
      st_.own_runs[run] = uint8_t(own);
      if (own && plain) st_.plain_runs[run] = p;
    }
  }

  // A block's counts added to the case's, in block order.
  void add(const Block& part) {
    CoverageStats& cov = st_.r.coverage;
    const CoverageStats& cv = part.counts;
    cov.neither += cv.neither, cov.both += cv.both, cov.reference_only += cv.reference_only;
    cov.gl_only += cv.gl_only, cov.other_primitive += cv.other_primitive;
    cov.exact_tie += cv.exact_tie, cov.within_snapping += cv.within_snapping;
    cov.gaps += cv.gaps, cov.double_hits += cv.double_hits, cov.fill_rule += cv.fill_rule;
    cov.boundary += cv.boundary, cov.failures += cv.failures;
    for (const CoverageStats::Pixel& m : cv.mismatches)
      if (cov.mismatches.size() < kMismatchesKept) cov.mismatches.push_back(m);
    for (const State::Excused& e : part.excused)
      if (st_.excused.size() < kMostTracedPixels)
        st_.excused.push_back(e);
      else
        ++st_.excused_beyond;
  }

  State& st_;
  const Expectation& expected_;
  const Frame& reference_;
  const Frame& gl_;
  const int y0_;
  const RunGrid grid_;
  const PlainlyOwn plainly_own_;
  const bool counts_;  // both frames have fragment counts
  // State::judgement's data, taken once it has the slice's size: a store through the vector
  // would load its data pointer again at every pixel.
  uint8_t* judgement_ = nullptr;
};

void Comparator::add_coverage(const Expectation& expected, const Frame& gl, int y0) {
  CoveragePass(*state_, expected, gl, y0).run();
}

}  // namespace glrc::compare
