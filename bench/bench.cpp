// Google Benchmark timings of one case's parts, on the same machine in the same run, so that
// their ratios mean something (scripts/bench.sh prints them against issue 13's targets):
//   gl/<case>         llvmpipe (OSMesa) drawing the case and reading the frame back, through
//                     gl_harness as `run` does it (program, FBO, draw, glReadPixels), warm;
//   frame/<case>      the exact reference's frame alone, as `glrefcheck digest` renders it
//                     (ref::render_frame): coverage, every varying and depth, no allowance and
//                     no edge bits (what llvmpipe computes), on every core, as llvmpipe draws on
//                     every core;
//   reference/<case>  the exact reference with the specification's allowance, as `run` renders
//                     it (check::expectation_for with llvmpipe's subpixel bits and default model),
//                     on every core;
//   compare/<case>    the comparison of llvmpipe's frame with it, its channels on every core;
//   check/<case>      all three, as one case of `run` in a worker;
//   digest/<case>     SHA-256 of llvmpipe's frame (results.json's gl_digest), which check/
//                     computes beside the reference (not in bench.sh's table: a part of check/).
// Usage: glrc_bench [--benchmark_* flags] CASE.json... (bench/scenes.py writes the scenes).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "compare/compare.hpp"
#include "core/large_buffer.hpp"
#include "gl_harness/gl_harness.hpp"
#include "ref/reference.hpp"

namespace {

using namespace glrc;

gl::Renderer& llvmpipe() {
  static const std::unique_ptr<gl::Renderer> renderer = gl::create_renderer(gl::Target{});
  return *renderer;
}

void register_case(const Case& c) {
  // Every core for the reference, as llvmpipe uses every core for its draw.
  check::CheckOptions options;
  options.threads = 0;
  const auto ms = [](benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
  };
  // gl/, reference/ and check/ draw and read back into the last iteration's frames, as a worker
  // does from case to case (check::check_with_frames), each warm from one untimed pass before
  // its loop: Google Benchmark calls a benchmark's function afresh for each repetition, and
  // bench.py's repetitions of a case as large as the quad are one iteration each, which began
  // with no frames to reuse (measured on the quad: check 196-200 ms a repetition, 187 ms when
  // 23 iterations share one warm start).
  ms(benchmark::RegisterBenchmark(("gl/" + c.name).c_str(), [c](benchmark::State& state) {
    Frame gl = llvmpipe().render(c);  // warm: the first draw compiles shaders
    for (auto _ : state) {
      gl = llvmpipe().render_reusing(c, std::move(gl));
      benchmark::DoNotOptimize(gl);
    }
  }));
  ms(benchmark::RegisterBenchmark(
      ("frame/" + c.name).c_str(), [c, options](benchmark::State& state) {
        for (auto _ : state)
          benchmark::DoNotOptimize(ref::render_frame(c, options.model, options.threads));
      }));
  // The reference under `o`, each iteration in the last one's buffers: reference/ with the
  // allowance at every pixel, deferred/ as `run`'s workers draw it (below).
  const auto expectation = [&](const std::string& part, const check::CheckOptions& o) {
    ms(benchmark::RegisterBenchmark((part + "/" + c.name).c_str(), [c, o](benchmark::State& state) {
      const int bits = llvmpipe().info().subpixel_bits;
      Expectation last = check::expectation_for(c, o, bits);
      for (auto _ : state) {
        last = check::expectation_for(c, o, bits, std::move(last));
        benchmark::DoNotOptimize(last);
      }
    }));
  };
  expectation("reference", options);
  ms(benchmark::RegisterBenchmark(
      ("compare/" + c.name).c_str(), [c, options](benchmark::State& state) {
        const int bits = llvmpipe().info().subpixel_bits;
        const Expectation e = check::expectation_for(c, options, bits);
        const Frame gl = llvmpipe().render(c);
        const Tolerance t = check::tolerance_for(c, options, bits);
        for (auto _ : state)
          benchmark::DoNotOptimize(compare::compare(c, e, gl, t, options.threads));
      }));
  // As `run`'s workers check a case: the component allowances computed where the comparison
  // needs them (CheckOptions::deferred_allowance), where that pays (check::deferral_pays).
  check::CheckOptions as_run = options;
  as_run.deferred_allowance = true;
  expectation("deferred", as_run);
  ms(benchmark::RegisterBenchmark(
      ("check/" + c.name).c_str(), [c, as_run](benchmark::State& state) {
        check::Checked last = check::check_with_frames(c, llvmpipe(), as_run);
        for (auto _ : state) {
          last = check::check_with_frames(c, llvmpipe(), as_run, std::move(last));
          benchmark::DoNotOptimize(last.result);
        }
      }));
  ms(benchmark::RegisterBenchmark(("digest/" + c.name).c_str(), [c](benchmark::State& state) {
    const Frame gl = llvmpipe().render(c);
    for (auto _ : state)
      benchmark::DoNotOptimize(ref::digest(gl));
  }));
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_buffers();  // as glrefcheck's workers do: check/ times a case as one of them
  benchmark::Initialize(&argc, argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: glrc_bench [--benchmark_* flags] CASE.json...\n");
    return 2;
  }
  try {
    for (int k = 1; k < argc; ++k)
      register_case(casefile::load(argv[k]));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glrc_bench: %s\n", e.what());
    return 2;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
