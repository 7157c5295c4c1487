// glrefcheck export CASE [--format c|shader_test] [--out FILE]: one case as a self-contained C
// reproducer (export/reproducer.hpp) or a piglit shader_test (export/shader_test.hpp) that
// draws it on GL as the harness does and checks the reference's expectation, embedded, without
// glrefcheck.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "core/model.hpp"

namespace glrc::cli {

struct ExportOptions {
  std::string case_path;
  std::string format = "c";
  std::string out;  // default: <case name>.c or <case name>.shader_test in the working folder
  // The model and GL_SUBPIXEL_BITS of one of Mesa's drivers, as `identify` finds them on Mesa
  // 22.3.6 (llvmpipe, softpipe, zink); or the command line's model (as `run --model ideal`).
  std::string driver;
  int subpixel_bits = 8;
  Planes planes = Planes::unsnapped;
  TieBreak tie_break = TieBreak::bottom_left;
  int threads = 0;  // threads drawing the reference; 0: every core
};

// Adds the subcommand "export" with its positional and options; returns it.
CLI::App* add_export_command(CLI::App& app, ExportOptions& o);
// Writes the reproducer and prints one line; 0. InputError (exit 2) for a case that cannot be
// loaded or is too large, an unknown --format or --driver, an --out file glrefcheck did not
// write, or (shader_test) a case whose states shader_runner cannot express.
int cmd_export(const ExportOptions& o, const CLI::App& command);

}  // namespace glrc::cli
