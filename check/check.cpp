#include "check/check.hpp"

#include <algorithm>
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "compare/compare.hpp"
#include "ref/mesh.hpp"
#include "ref/reference.hpp"

namespace glrc::check {

int freedom_bits(const Judging& o, int reported_bits) {
  return std::max(o.spec_subpixel_bits.value_or(reported_bits), 4);
}

std::optional<ToleranceMode> mode_override(const Judging& o) {
  if (o.tolerance == ToleranceMode::exact) return ToleranceMode::exact;
  if (o.tolerance == ToleranceMode::ulps || o.varying_ulps || o.depth_ulps)
    return ToleranceMode::ulps;
  return std::nullopt;
}

std::optional<std::string> judging_problem(const Judging& o) {
  const bool thresholds = o.varying_ulps || o.depth_ulps;
  if (o.driver_model && !mode_override(o))
    return "a driver model is judged bit for bit (exact) or by fixed ULPs, not by the "
           "specification's allowance";
  if (o.tolerance == ToleranceMode::exact && thresholds)
    return "exact judges bit for bit: no ULP thresholds with it";
  return std::nullopt;
}

Tolerance tolerance_for(const Case& c, const Judging& o, int reported_bits) {
  Tolerance t = c.tolerance.applied_to(Tolerance{});
  t.subpixel_bits = freedom_bits(o, reported_bits);
  if (o.varying_ulps) t.varying_ulps = *o.varying_ulps;
  if (o.depth_ulps) t.depth_ulps = *o.depth_ulps;
  if (const auto mode = mode_override(o)) t.mode = *mode;
  if (o.strict_coverage) t.allow_boundary = false;
  return t;
}

bool deferral_pays(const Case& c) {
  const double pixels = double(std::max(c.fb_width, 0)) * double(std::max(c.fb_height, 0));
  return c.component_count() > 0 && pixels >= 4096.0 * double(c.triangles.size());
}

namespace {

// expectation_for(), its triangles' set-up handed back in `setup` (none with a driver model).
Expectation expectation_and_setup(const Case& c, const CheckOptions& o, int reported_bits,
                                  Expectation storage,
                                  std::shared_ptr<const ref::CaseSetup>& setup) {
  const int bits = freedom_bits(o, reported_bits);
  if (o.driver_model) {
    Expectation r = ref::render(c, o.model, bits, o.threads, std::move(storage));
    // The driver model replaces the frame only: the edge bits still name ties and bands.
    r.frame = driver_models::render(c, *o.driver_model);
    return r;
  }
  if (o.deferred_allowance && deferral_pays(c))
    return ref::render_deferred(c, o.model, bits, o.threads, std::move(storage), setup);
  return ref::render(c, o.model, bits, o.threads, std::move(storage), setup);
}

}  // namespace

Expectation expectation_for(const Case& c, const CheckOptions& o, int reported_bits,
                            Expectation storage) {
  std::shared_ptr<const ref::CaseSetup> setup;
  return expectation_and_setup(c, o, reported_bits, std::move(storage), setup);
}

// What judges the counts the edge bits excuse (compare::TraceSource): GL's traces from the
// renderer's counting pass of the case it drew last, the reference's choices from its set-up.
// None against a driver model, whose frame is matched bit for bit or by fixed ULPs.
std::optional<compare::TraceSource> trace_source(const Case& c, gl::Renderer& renderer,
                                                 const CheckOptions& o, int reported,
                                                 std::shared_ptr<const ref::CaseSetup> setup) {
  if (o.driver_model) return std::nullopt;
  return compare::TraceSource{
      [&c, &renderer](const std::vector<size_t>& pixels) {
        return renderer.fragment_traces(c, pixels);
      },
      [&c, &o, reported, setup = std::move(setup)](const std::vector<size_t>& pixels) {
        const int bits = freedom_bits(o, reported);
        return setup ? ref::fragment_choices(c, o.model, bits, pixels, o.threads, *setup)
                     : ref::fragment_choices(c, o.model, bits, pixels, o.threads);
      }};
}

std::vector<AdmittedTraces> admitted_traces(const Case& c, const Expectation& expected,
                                            const CheckOptions& o, int reported_bits) {
  const Frame& f = expected.frame;
  if (f.fragments.size() != f.pixel_count() || expected.edges.size() != f.pixel_count()) return {};
  std::vector<size_t> pixels;
  for (size_t i = 0; i < f.pixel_count(); ++i)
    if (expected.edges[i] & (edge::snapping | edge::unstable | edge::shared)) pixels.push_back(i);
  const std::vector<FragmentChoices> choices =
      ref::fragment_choices(c, o.model, freedom_bits(o, reported_bits), pixels, o.threads);
  std::vector<AdmittedTraces> out;
  for (size_t k = 0; k < pixels.size(); ++k)
    if (auto traces = admitted(choices[k])) out.push_back({pixels[k], std::move(*traces)});
  return out;
}

std::string tolerance_text(const Judging& o, int reported_bits) {
  if (const auto mode = mode_override(o)) return to_string(*mode);
  return "spec (subpixel bits " + std::to_string(freedom_bits(o, reported_bits)) + ")";
}

std::string model_text(const Judging& o) {
  if (o.driver_model)
    return std::string(driver_models::to_string(*o.driver_model)) +
           " (bit-exact model of Mesa 22.3.6's driver)";
  return o.model.describe();
}

size_t frame_bytes(const Case& c) {
  return size_t(std::max(c.fb_width, 0)) * size_t(std::max(c.fb_height, 0)) *
         (3 + size_t(std::max(c.component_count(), 0))) * 4;
}

int slice_rows(const Case& c, const Execution& o) {
  const size_t row_bytes = std::max<size_t>(frame_bytes(c) / size_t(std::max(c.fb_height, 1)), 1);
  return int(std::clamp<size_t>(o.slice_bytes / row_bytes, 1, size_t(std::max(c.fb_height, 1))));
}

Expectation expectation_rows(const Case& c, const CheckOptions& o, int reported_bits, int y0,
                             int rows) {
  return ref::render_rows(c, o.model, freedom_bits(o, reported_bits), o.threads, y0, rows);
}

namespace {

// Slices of rows [y0, y0 + rows) spread evenly over a streamed frame, from which its floors
// are guessed (compare::Comparator::add_floor_sample): kSampleSlices of them, about twice the
// fewest runs of compare::RunGrid::kRun pixels a guess is made from, none where that is more than
// an eighth of the frame. Sixty-four places, not thirty-two: the 4096x4096 scene's guess from 32
// slices of four rows did not hold (its stream compared twice), from 64 of two it did.
std::vector<std::pair<int, int>> floor_sample_slices(const Case& c) {
  constexpr int kSampleSlices = 64;
  constexpr size_t kRuns = 2 * compare::kFewestFloorSamples;
  const int runs_per_row = compare::RunGrid{c.fb_width, c.fb_height}.whole_runs_per_row();
  if (runs_per_row <= 0 || c.fb_height <= 0) return {};
  const int rows = int((kRuns + size_t(runs_per_row) - 1) / size_t(runs_per_row));
  if (int64_t(rows) * 8 > c.fb_height) return {};
  const int slices = std::min(kSampleSlices, rows);
  const int height = (rows + slices - 1) / slices;
  std::vector<std::pair<int, int>> out;
  for (int b = 0; b < slices; ++b) {
    const int middle = int((2 * int64_t(b) + 1) * c.fb_height / (2 * slices));
    out.emplace_back(std::clamp(middle - height / 2, 0, c.fb_height - height), height);
  }
  return out;
}

// Slice by slice: GL draws once, then for each slice the reference renders its rows (with its
// allowances deferred where CheckOptions::deferred_allowance asks and that pays), GL's are read
// back (glReadPixels of the slice) and both are compared; GL's slice is then digested on a thread
// of its own while the next slice is drawn, read and compared (the digest is one SHA-256 stream
// in row order, which nothing else of a slice needs). At most three slices of GL's frame (one read,
// one hashed, one spare) and two of the reference's (one compared, one drawn) are alive at a
// time. The comparator's floors are guessed first from slices spread over the frame
// (floor_sample_slices), as a frame compared whole guesses them from a sample of itself: without
// them, a channel keeps every value until it has a percent of the frame's, and its allowances
// are computed at every pixel until then (a sixth of the 2048x2048 scene's check). Should the
// stream not bear them out, its slices are compared again without (GL's frame stays drawn).
void check_streamed(const Case& c, gl::Renderer& renderer, const CheckOptions& o, int reported,
                    Checked& out) {
  const int rows = slice_rows(c, o);
  const bool deferred = o.deferred_allowance && deferral_pays(c);
  const Tolerance tolerance = tolerance_for(c, o, reported);
  renderer.draw(c);
  // The reference's rows [y0, y0 + n), in the buffers of `storage` where it can.
  const auto draw_rows = [&](int y0, int n, Expectation&& storage) {
    return deferred ? ref::render_rows_deferred(c, o.model, freedom_bits(o, reported), o.threads,
                                                y0, n, std::move(storage))
                    : expectation_rows(c, o, reported, y0, n);
  };
  ref::FrameDigest digest(c.fb_width, c.fb_height);
  // Declared before the digest's future, whose destructor waits for it: the slice it hashes
  // outlives it, whatever throws. GL's slice is read into the buffers of the slice before the
  // last (`spare`), hashed by then: a fresh slice's pages are faulted in and zeroed by the kernel
  // (perf: a twentieth of the 2048x2048 scene's check).
  Frame hashing, spare;
  std::future<void> hashed;
  // Every slice compared by `comparator`, and hashed when `hash`. The reference's next slice is
  // drawn while this one is read back and compared, in the buffers of the slice before
  // (`drawn`): a slice's drawing has parts on one thread (each triangle set up and prepared),
  // as its reading back has, which the other's work fills.
  const auto compare_slices = [&](compare::Comparator& comparator, bool hash) {
    Expectation drawn;
    std::future<Expectation> next;  // after `drawn`: its destructor waits for the drawing
    const auto draw_next = [&](int y0) {
      if (y0 >= c.fb_height) return;
      next = std::async(std::launch::async, [&, y0, storage = std::move(drawn)]() mutable {
        return draw_rows(y0, std::min(rows, c.fb_height - y0), std::move(storage));
      });
    };
    draw_next(0);
    for (int y0 = 0; y0 < c.fb_height; y0 += rows) {
      const int n = std::min(rows, c.fb_height - y0);
      Expectation expected = next.get();
      draw_next(y0 + rows);
      Frame gl = renderer.read_rows_reusing(c, y0, n, std::move(spare));
      comparator.add_rows(expected, gl, y0);
      if (hashed.valid()) hashed.get();
      spare = std::exchange(hashing, std::move(gl));
      if (hash) hashed = std::async(std::launch::async, [&] { digest.add_rows(hashing); });
      drawn = std::move(expected);
    }
    if (hashed.valid()) hashed.get();
  };
  std::optional<compare::Comparator> comparator;
  comparator.emplace(c, tolerance, c.fb_width, c.fb_height, o.threads);
  // One slice of the whole frame guesses its floors from itself, and may compare a channel
  // again (compare::Comparator::add_rows).
  const std::vector<std::pair<int, int>> samples =
      rows < c.fb_height ? floor_sample_slices(c) : std::vector<std::pair<int, int>>{};
  Expectation sample;
  for (const auto& [y0, n] : samples) {
    sample = draw_rows(y0, n, std::move(sample));
    spare = renderer.read_rows_reusing(c, y0, n, std::move(spare));
    comparator->add_floor_sample(sample, spare);
  }
  sample = {};
  comparator->guess_floors();
  compare_slices(*comparator, true);
  if (!comparator->floors_held()) {
    comparator.emplace(c, tolerance, c.fb_width, c.fb_height, o.threads);
    compare_slices(*comparator, false);
  }
  const std::optional<compare::TraceSource> traces = trace_source(c, renderer, o, reported);
  out.result = comparator->finish(traces ? &*traces : nullptr);
  out.result.gl_digest = digest.hex();
  out.streamed = true;
}

}  // namespace

Checked check_with_frames(const Case& c, gl::Renderer& renderer, const CheckOptions& o,
                          Checked last) {
  if (const auto problem = judging_problem(o)) throw std::invalid_argument(*problem);
  const auto start = std::chrono::steady_clock::now();
  Checked out;
  const int reported = renderer.info().subpixel_bits;
  const bool streamed = !o.driver_model && frame_bytes(c) > o.whole_frame_bytes;
  // The reference is drawn while GL draws: it needs no GL, and a driver's first draw of a case
  // spends most of its time compiling shaders on one core (llvmpipe's LLVM), not drawing.
  std::future<Expectation> expected;
  // The reference's set-up of the triangles, kept for the traces' choices (trace_source).
  std::shared_ptr<const ref::CaseSetup> setup;
  if (streamed)
    last = {};
  else
    expected = std::async(std::launch::async, [&, storage = std::move(last.expected)]() mutable {
      return expectation_and_setup(c, o, reported, std::move(storage), setup);
    });
  try {
    if (streamed) {
      check_streamed(c, renderer, o, reported, out);
      out.result.seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return out;
    }
    out.gl = renderer.render_reusing(c, std::move(last.gl));
    // GL's digest is hashed while the reference is finished and the channels are compared:
    // none needs another.
    std::future<std::string> gl_digest =
        std::async(std::launch::async, [&] { return ref::digest(out.gl); });
    out.expected = expected.get();
    const std::optional<compare::TraceSource> traces =
        trace_source(c, renderer, o, reported, std::move(setup));
    out.result = compare::compare(c, out.expected, out.gl, tolerance_for(c, o, reported), o.threads,
                                  traces ? &*traces : nullptr);
    out.result.gl_digest = gl_digest.get();
  } catch (const gl::RenderError& e) {
    // The reference's own error comes first, as when it was drawn before GL.
    if (expected.valid()) out.expected = expected.get();
    out.result.name = c.name;
    out.result.description = c.description;
    // A feature the implementation lacks skips the case: nothing was judged.
    const bool missing = dynamic_cast<const gl::FeatureMissing*>(&e) != nullptr;
    out.result.status = out.result.outcome = missing ? Status::skip : Status::error;
    out.result.message = e.what();
  }
  out.result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

CaseResult check(const Case& c, gl::Renderer& renderer, const CheckOptions& o) {
  return check_with_frames(c, renderer, o).result;
}

}  // namespace glrc::check
