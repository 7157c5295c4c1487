#include "cli/export.hpp"

#include <fmt/core.h>
#include <filesystem>

#include "casefile/casefile.hpp"
#include "check/check.hpp"
#include "cli/output_dir.hpp"
#include "cli/session.hpp"
#include "cli/validators.hpp"
#include "core/text.hpp"
#include "export/reproducer.hpp"
#include "export/shader_test.hpp"
#include "gl_harness/first_draw.hpp"
#include "gl_harness/shaders.hpp"
#include "identify/known_models.hpp"
#include "report/report.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {
namespace {

reproducer::ReproducerShaders shaders_of(const Case& c) {
  return {gl::vertex_shader_source(c),
          gl::geometry_shader_source(c),
          gl::fragment_shader_source(c, false),
          gl::fragment_shader_source(c, true),
          gl::count_vertex_shader_source(c.distances),
          gl::count_geometry_shader_source(c.distances)};
}

// The command that wrote the file, for its header: the options given, as given.
std::string command_line(const ExportOptions& o, const CLI::App& command) {
  std::string line = "glrefcheck export " + o.case_path + " --format " + o.format;
  if (!o.driver.empty()) line += " --driver " + o.driver;
  if (command.count("--subpixel-bits"))
    line += " --subpixel-bits " + std::to_string(o.subpixel_bits);
  if (command.count("--planes")) line += std::string(" --planes ") + to_string(o.planes);
  if (command.count("--tie-break")) line += std::string(" --tie-break ") + to_string(o.tie_break);
  return line;
}

std::string model_words(const ExportOptions& o, const check::CheckOptions& options) {
  std::string words = options.model.describe();
  if (!o.driver.empty()) {
    words += " (what `identify` finds for ";
    words += o.driver;
    words += ")";
  }
  return words;
}

// --format shader_test: export/shader_test's file, refused with one line where shader_runner
// cannot express the case.
int export_shader_test(const ExportOptions& o, const CLI::App& command, const Case& c,
                       const check::CheckOptions& options, int reported_bits) {
  std::string out = o.out;
  if (out.empty()) {
    out = c.name;
    out += ".shader_test";
  }
  if (!out.ends_with(".shader_test") || std::filesystem::path(out).filename() == ".shader_test") {
    std::string why = "--out: expected a file name ending in .shader_test, got \"";
    why += printable(out, 200);
    why += "\"";
    throw InputError(why);
  }
  // What the states alone rule out, before the reference is drawn.
  if (const auto why = reproducer::shader_test_state_refusal(c)) {
    std::string message = printable(o.case_path, 200);
    message += ": ";
    message += *why;
    throw InputError(message);
  }
  check_replaceable(out, "--out", "export");
  const Expectation expected = check::expectation_for(c, options, reported_bits);
  const Tolerance tolerance = check::tolerance_for(c, options, reported_bits);
  if (const auto why = reproducer::shader_test_refusal(c, expected, tolerance)) {
    std::string message = printable(o.case_path, 200);
    message += ": ";
    message += *why;
    throw InputError(message);
  }
  reproducer::ShaderTestSetup setup;
  setup.file_name = std::filesystem::path(out).filename().string();
  setup.exported_by = command_line(o, command);
  setup.model = model_words(o, options);
  const reproducer::ShaderTest test = reproducer::shader_test(c, expected, tolerance, setup);
  // Its stamp last (report/stamp.hpp): an export replaces this file only while it is unchanged.
  report::write_file_atomically(out, report::stamped(test.text + "# written by glrefcheck export " +
                                                     report::stamp_placeholder() + "\n"));
  fmt::print(
      "wrote {}: run with {} (values checked against their ranges at {} of {} (pixel, "
      "triangle) pairs, for NaN and Inf everywhere; coverage at {} pixels in {} probes)\n",
      out, reproducer::shader_runner_command(out), test.value_checks, test.value_pairs,
      test.pixels_decided, test.coverage_probes);
  return 0;
}

}  // namespace

CLI::App* add_export_command(CLI::App& app, ExportOptions& o) {
  auto* cmd = app.add_subcommand(
      "export",
      "write one case as a self-contained reproducer (a C file, or a piglit shader_test): it "
      "draws the case on GL as glrefcheck does and checks the reference's expectation, embedded, "
      "without glrefcheck");
  cmd->add_option("case", o.case_path, "the case file")->required();
  cmd->add_option("--format", o.format,
                  "c: one C99 file, built with cc alone (default); shader_test: a piglit "
                  "shader_test for shader_runner");
  cmd->add_option("--out", o.out,
                  "the file to write (default: <case name>.c, or <case name>.shader_test, here)");
  cmd->add_option("--driver", o.driver,
                  "judge as for this Mesa driver: llvmpipe, softpipe or zink (the model `identify` "
                  "finds for it and the GL_SUBPIXEL_BITS it reports)")
      // Given as "" (an unset variable) it would judge as no driver, silently.
      ->check(CLI::Validator(
          [](std::string& name) {
            return name.empty() ? std::string("expected llvmpipe, softpipe or zink, got \"\"")
                                : std::string();
          },
          ""));
  cmd->add_option("--subpixel-bits", o.subpixel_bits,
                  "without --driver: the reference's snapping, 0 to 16 (default 8), and the "
                  "GL_SUBPIXEL_BITS the allowance is for (at least 4); must match the driver's "
                  "(llvmpipe 8, softpipe 4)")
      ->check(CLI::Range(0, 16));
  add_enum_option(*cmd, "--planes", o.planes,
                  "without --driver: attribute planes from snapped or unsnapped positions");
  add_enum_option(*cmd, "--tie-break", o.tie_break,
                  "without --driver: pixel centres exactly on an edge");
  cmd->add_option("--threads", o.threads, "threads drawing the reference (default: every core)")
      ->check(whole_number(1))
      ->check(CLI::Range(1, 4096));  // as run's: 100,000 threads hung on their start-up
  return cmd;
}

int cmd_export(const ExportOptions& o, const CLI::App& command) {
  if (o.format != "c" && o.format != "shader_test")
    throw InputError("--format: expected c or shader_test, got \"" + printable(o.format, 80) +
                     "\"");
  check::CheckOptions options;
  int reported_bits = std::max(o.subpixel_bits, 4);
  options.model = Model{o.subpixel_bits, o.planes, o.tie_break};
  if (!o.driver.empty()) {
    const identify::KnownModel* found = identify::known_model(o.driver);
    if (!found)
      throw InputError("--driver: expected llvmpipe, softpipe or zink, got \"" +
                       printable(o.driver, 80) + "\"");
    for (const char* name : {"--subpixel-bits", "--planes", "--tie-break"})
      if (command.count(name))
        throw InputError(std::string(name) + ": expected no model option with --driver " +
                         o.driver + " (the driver names the model)");
    options.model = found->model;
    reported_bits = found->reported_subpixel_bits;
  }
  options.threads = o.threads;

  Case c;
  try {
    c = casefile::load(o.case_path);
  } catch (const std::exception& e) {
    throw InputError(e.what());
  }
  if (o.format == "shader_test") return export_shader_test(o, command, c, options, reported_bits);
  const size_t values = reproducer::reproducer_values(c);
  if (values > reproducer::kMaxReproducerValues) {
    std::string n = std::to_string(values);
    for (int at = int(n.size()) - 3; at > 0; at -= 3)
      n.insert(size_t(at), ",");
    throw InputError(printable(o.case_path, 200) + ": " + n +
                     " pixel values; a reproducer embeds at most 400,000: shrink the case first "
                     "(glrefcheck fuzz --replay ...)");
  }
  const std::string out = o.out.empty() ? c.name + ".c" : o.out;
  if (!out.ends_with(".c") || out.size() < 3 || out.ends_with("/.c"))
    throw InputError("--out: expected a file name ending in .c, got \"" + printable(out, 200) +
                     "\"");
  check_replaceable(out, "--out", "export");

  const Expectation expected = check::expectation_for(c, options, reported_bits);
  const Tolerance tolerance = check::tolerance_for(c, options, reported_bits);
  reproducer::CReproducerSetup setup;
  setup.shaders = shaders_of(c);
  setup.first_draw = gl::first_draw_case();
  setup.first_draw_shaders = shaders_of(setup.first_draw);
  setup.count_fragment = gl::count_fragment_shader_source();
  setup.trace_fragment = gl::trace_fragment_shader_source(several_draws(c));
  setup.admitted = check::admitted_traces(c, expected, options, reported_bits);
  setup.file_name = std::filesystem::path(out).filename().string();
  setup.exported_by = command_line(o, command);
  setup.model = options.model.describe() +
                (o.driver.empty() ? "" : " (what `identify` finds for " + o.driver + ")");
  // Its stamp last (report/stamp.hpp): an export replaces this file only while it is unchanged.
  report::write_file_atomically(
      out,
      report::stamped(reproducer::c_reproducer(c, expected, tolerance, setup) +
                      "/* written by glrefcheck export " + report::stamp_placeholder() + " */\n"));
  fmt::print("wrote {}: compile with {}, run with {} [egl|osmesa]\n", out,
             reproducer::c_compile_command(out), reproducer::c_run_command(out));
  return 0;
}

}  // namespace glrc::cli
