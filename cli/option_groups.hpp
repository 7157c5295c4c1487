// The option groups that run, diff, digest, selftest, identify and fuzz share: each group holds
// its fields, registers its options with CLI11 and writes and reads its part of the options'
// JSON (a worker's options on its stdin, a run's in its journal), in one place. The JSON is one
// flat object of every group's fields, as it always was.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/model.hpp"
#include "core/result.hpp"
#include "gl_harness/gl_harness.hpp"

namespace CLI {
class App;
}

namespace glrc::typed_json {
class Reader;
}

namespace glrc::cli {

// What judges the cases: --model and the exact reference's choices.
struct ModelOptions {
  // "identified" (what `identify` finds for the implementation), "ideal" (the exact reference
  // with the choices below), or a bit-exact model of one driver ("llvmpipe", "softpipe").
  std::string name = "identified";
  int subpixel_bits = 8;
  Planes planes = Planes::unsnapped;
  TieBreak tie_break = TieBreak::bottom_left;
  // Whether --subpixel-bits, --planes or --tie-break was on the command line: then the
  // reference's model is the command line's, whatever --model says.
  bool given = false;

  // The exact reference's model from subpixel_bits, planes and tie_break.
  Model reference_model() const { return {subpixel_bits, planes, tie_break}; }
  // Sets subpixel_bits, planes and tie_break to m (reference_model() is then m).
  void set_reference_model(const Model& m) {
    subpixel_bits = m.subpixel_bits, planes = m.planes, tie_break = m.tie_break;
  }
  // --model, --subpixel-bits, --planes, --tie-break.
  void add_to(CLI::App& app);
  // Whether the subcommand that ran was given --subpixel-bits, --planes or --tie-break.
  static bool given_in(const CLI::App& app);
  // Its fields in `j` (model, subpixel_bits, planes, tie_break, model_given), and back, each
  // checked as the command line checks it (InputError naming "<path>.<field>").
  void write(nlohmann::json& j) const;
  void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path);
};

// --model's choices: identified, ideal, and the driver models' names.
std::vector<std::string> model_choices();

// Which GL: the backend, Mesa's driver, the EGL device, and a Mesa install tree.
struct GlOptions {
  gl::Backend backend = gl::Backend::osmesa;
  std::string driver = "llvmpipe";
  int device = 0;
  // A Mesa install tree to run instead of the system's (scripts/mesa-fetch.sh makes one). Not in
  // the JSON: the process re-executes itself under it before anything reads the options.
  std::string mesa;

  // --backend, --driver, --device, --mesa.
  void add_to(CLI::App& app);
  // backend, driver, device.
  void write(nlohmann::json& j) const;
  void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path);
};

// How the verdict is reached: the tolerance and what changes it.
struct VerdictOptions {
  ToleranceMode tolerance = ToleranceMode::spec;  // spec or exact (ulps: the numbers below)
  std::optional<int> spec_subpixel_bits;          // overrides GL_SUBPIXEL_BITS as reported
  std::optional<double> varying_ulps, depth_ulps;
  bool strict_coverage = false;

  // --tolerance-ulps, --depth-tolerance-ulps, --tolerance, --spec-subpixel-bits,
  // --strict-coverage.
  void add_to(CLI::App& app);
  // tolerance, strict_coverage, and spec_subpixel_bits, varying_ulps, depth_ulps where set.
  void write(nlohmann::json& j) const;
  void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path);
};

}  // namespace glrc::cli
