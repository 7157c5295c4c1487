// check: one case, end to end. The exact reference (ref/) or a bit-exact driver model's frame
// (driver_models/) is what GL's frame (gl_harness/) is compared against (compare/), under the
// tolerance the case file and the options give. `run`'s workers, `diff`, `selftest` and the
// tests all judge a case through this, so a verdict is decided in one place.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compare/compare.hpp"
#include "core/case.hpp"
#include "core/expectation.hpp"
#include "core/fragment_trace.hpp"
#include "core/model.hpp"
#include "core/result.hpp"
#include "driver_models/driver_models.hpp"
#include "gl_harness/gl_harness.hpp"

namespace glrc::ref {
struct CaseSetup;  // ref/mesh.hpp
}  // namespace glrc::ref

namespace glrc::check {

// What a case is judged by: the model, a driver model, the tolerance and what changes it. Two
// runs whose Judging differs may give different verdicts (cli/ records it with each result).
// The defaults judge by the specification's allowance for the exact reference with the fixed
// default model.
struct Judging {
  // The reference's choices where GL leaves them to the implementation (subpixel bits, attribute
  // planes, tie rule): the model that judges the case, identified or given.
  Model model;
  // Compare against this driver model's frame instead of the reference's (`--model llvmpipe`).
  // The reference still renders: its edge bits name ties and snapping bands. A driver model is
  // judged bit for bit or by fixed ULPs, never by the specification's allowance (check()
  // throws std::invalid_argument otherwise).
  std::optional<driver_models::Driver> driver_model;
  // spec: the case file's tolerance (the specification's allowance unless the case says
  // otherwise); ulps: fixed thresholds (varying_ulps, depth_ulps; the case's for one not given);
  // exact: bit for bit, whatever the case file says.
  ToleranceMode tolerance = ToleranceMode::spec;
  std::optional<double> varying_ulps, depth_ulps;  // ULPs of each attribute's scale; >= 0
  // The position freedom of the specification's allowance, in subpixel bits, instead of the
  // GL_SUBPIXEL_BITS the implementation reports.
  std::optional<int> spec_subpixel_bits;
  // Coverage differences within the snapping band fail too (GL allows them).
  bool strict_coverage = false;
};

// How a case is checked: none of it changes a verdict or a statistic, bit for bit.
struct Execution {
  // Threads drawing the reference (ref::render) and judging the channels (compare::compare); the
  // same bits for any number; 0: every core this process may use.
  int threads = 1;
  // A case whose frame (frame_bytes) is larger than this is checked slice of rows by slice of
  // rows (streamed): the reference rendered, GL's frame read back and the two compared one slice
  // at a time, so that neither is held whole. Same verdict and statistics, bit for bit; no
  // frames are kept (Checked::streamed: report::write_streamed_diff_images makes the heatmaps
  // from the slices again). Not with a driver model.
  size_t whole_frame_bytes = size_t(256) << 20;
  // About how many bytes of frame one slice of a streamed case holds.
  size_t slice_bytes = size_t(16) << 20;
  // The reference's component allowances computed only where the comparison needs them
  // (ref::render_deferred), in a case where that pays (deferral_pays): the same verdict and
  // statistics, bit for bit, in less time; Checked::expected then holds them deferred
  // (complete_allowance fills them in for a heatmap). Not with a driver model. A streamed case
  // defers them slice by slice (ref::render_rows_deferred).
  bool deferred_allowance = false;
};

// Both: what check() takes. Functions that need only one of them take that one.
struct CheckOptions : Judging, Execution {};

// Whether deferring case c's component allowances (CheckOptions::deferred_allowance) is likely
// to save time: it has components, and its triangles are large, on average at least 4096
// pixels of the framebuffer each. The comparison bounds the allowances over runs of 64 pixels
// of one triangle; where a row of 64 pixels crosses several triangles, each stretch is bounded
// apart, which costs about what computing the allowance costs (measured on a 2-core VM: 10,000
// triangles in 256x256 checked 11% slower deferred, the 1024x1024 quad of two 7% faster).
bool deferral_pays(const Case& c);

// The bytes of one Frame of case c: every pixel's primitive, depth, fragment count and
// components, 4 bytes each.
size_t frame_bytes(const Case& c);
// The rows of one slice of a streamed case: about o.slice_bytes of frame, at least 1, at most
// the framebuffer's height.
int slice_rows(const Case& c, const Execution& o);
// Rows [y0, y0 + rows) of expectation_for (no driver model): ref::render_rows.
Expectation expectation_rows(const Case& c, const CheckOptions& o, int reported_bits, int y0,
                             int rows);

// The subpixel bits of the position freedom: spec_subpixel_bits, else what the implementation
// reports, never below the 4 GL requires (OpenGL 4.6 section 14.6.1's minimum).
int freedom_bits(const Judging& o, int reported_bits);

// The mode the options set over any case file's, decided here only: exact when asked for; ulps
// when asked for or when a threshold (varying_ulps, depth_ulps) is given; nullopt otherwise
// (spec: each case is judged by its file's mode, the specification's allowance unless it says
// otherwise).
std::optional<ToleranceMode> mode_override(const Judging& o);

// What in `o` cannot judge a case, in a few words, or nullopt: a driver model under the
// specification's allowance (it would pass whatever the model gets wrong by less than the
// allowance: the model is there to be matched bit for bit or by fixed ULPs); exact with ULP
// thresholds. check() throws std::invalid_argument with it; cli/ says it before any work.
std::optional<std::string> judging_problem(const Judging& o);

// The tolerance of case `c`: the defaults, then the case file's, then the options' (exact
// wins; ULPs given turn to fixed thresholds; strict coverage drops the boundary allowance).
Tolerance tolerance_for(const Case& c, const Judging& o, int reported_bits);

// What the case is compared against: the exact reference under o.model with the allowance for
// an implementation reporting `reported_bits`, its frame replaced by the driver model's when
// o.driver_model is set.
// `storage`: a previous Expectation whose buffers are reused (ref::render's).
Expectation expectation_for(const Case& c, const CheckOptions& o, int reported_bits,
                            Expectation storage = {});

// RunInfo's words for the tolerance: "exact", "ulps" or "spec (subpixel bits N)".
std::string tolerance_text(const Judging& o, int reported_bits);
// RunInfo's words for the model: o.model.describe(), or the driver model's name.
std::string model_text(const Judging& o);

// What judges the coverage the edge bits excuse (compare::TraceSource), for case c just drawn
// by `renderer` (its traces are of the case it drew last): GL's traces from the renderer's
// counting pass, the reference's choices from ref::fragment_choices under o's model and the
// freedom of `reported_bits`. None with a driver model, whose frame is matched bit for bit or by
// fixed ULPs. Holds references to c, renderer and o. `setup`: where given, the reference's own
// set-up of c's triangles under o.model (ref::render's), reused instead of set up again.
std::optional<compare::TraceSource> trace_source(const Case& c, gl::Renderer& renderer,
                                                 const CheckOptions& o, int reported_bits,
                                                 std::shared_ptr<const ref::CaseSetup> setup = {});

// For a reproducer of case c drawn to `expected` (expectation_for's, no driver model): at every
// pixel whose coverage its edge bits may excuse (edge::snapping, edge::unstable, edge::shared), the
// traces a conforming implementation may give (ref::fragment_choices, admitted()), sorted by
// pixel; a pixel where admitted() gives no list is left out. Empty without fragment counts.
std::vector<AdmittedTraces> admitted_traces(const Case& c, const Expectation& expected,
                                            const CheckOptions& o, int reported_bits);

// One case checked, with the frames a heatmap needs.
struct Checked {
  CaseResult result;
  Expectation expected;
  Frame gl;
  bool streamed = false;  // checked slice by slice: no frames kept
};

// Renders `c` on the reference and on `renderer`, and compares them. A GL error drawing this
// case (gl::RenderError) is the result Error with its message, not an exception, and a feature
// the implementation lacks (gl::FeatureMissing) the result Skip with its reason; seconds
// counts everything. Throws std::invalid_argument for a driver model under ToleranceMode::spec.
// `last`: the previous case's Checked, whose frames' buffers this case's frames reuse where
// they are large enough (Frame::reset), so that a caller checking case after case (a worker)
// does not have the kernel fault in and zero fresh memory for every case; the same result
// and frames, bit for bit, as without. A streamed case frees them first: its slices need none.
Checked check_with_frames(const Case& c, gl::Renderer& renderer, const CheckOptions& o,
                          Checked last = {});
// The same, the verdict only.
CaseResult check(const Case& c, gl::Renderer& renderer, const CheckOptions& o);

}  // namespace glrc::check
