#include "cli/session.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "casefile/casefile.hpp"
#include "cli/options_reader.hpp"
#include "core/text.hpp"
#include "driver_models/driver_models.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {

std::optional<ModelChoice> model_from_command_line(const Options& o) {
  // Any of the model's own options names the model outright: a developer testing a hypothesis
  // ("is it top-left?") gets exactly the model typed, the rest at the fixed defaults.
  if (o.model.given) return ModelChoice{o.model.reference_model(), "command line"};
  if (o.model.name == "identified") return std::nullopt;
  if (o.model.name == "ideal") return ModelChoice{o.model.reference_model(), "default"};
  return ModelChoice{o.model.reference_model(), "command line"};  // a driver model
}

ModelChoice fallback_model(const Options& o, const std::string& why) {
  return identify::fallback_model(o.model.reference_model(), why);
}

check::Judging judging(const Options& o) {
  check::Judging judged;
  judged.model = o.model.reference_model();
  judged.driver_model = driver_models::driver_from_string(o.model.name);
  // With the thresholds, check::mode_override decides the mode.
  judged.tolerance = o.verdict.tolerance;
  judged.varying_ulps = o.verdict.varying_ulps;
  judged.depth_ulps = o.verdict.depth_ulps;
  judged.spec_subpixel_bits = o.verdict.spec_subpixel_bits;
  judged.strict_coverage = o.verdict.strict_coverage;
  if (const auto problem = check::judging_problem(judged))
    throw InputError(judged.driver_model && !check::mode_override(judged)
                         ? "--model " + o.model.name + ": " + *problem +
                               " (--tolerance exact, or --tolerance-ulps)"
                         : "--tolerance exact: " + *problem +
                               " (--tolerance-ulps/--depth-tolerance-ulps given)");
  return judged;
}

check::CheckOptions check_options(const Options& o) {
  check::CheckOptions c{judging(o), {}};
  c.threads = o.threads;
  return c;
}

std::vector<Case> load_cases(const Options& o) {
  // Every command loads its cases first: options that cannot go together stop it here, before
  // any work.
  judging(o);
  std::vector<std::string> paths = o.paths;
  if (paths.empty()) {
    if (!std::filesystem::is_directory("cases"))
      throw InputError("no cases/ folder here: name case files or folders on the command line");
    paths = {"cases"};
  }
  std::optional<Regex> filter;
  if (!o.filter.empty()) {
    try {
      filter.emplace(o.filter);
    } catch (const std::runtime_error& e) {
      throw InputError(std::string("--filter: ") + e.what());
    }
  }
  std::vector<Case> cases;
  // Notes on what a folder search passed over wait until the cases have loaded: an error stays
  // the one line it should be, and "no case matches" can say what was passed over.
  std::vector<std::string> notes;
  size_t files = 0;
  try {
    for (const auto& file :
         casefile::collect(paths, [&](const std::string& n) { notes.push_back(n); })) {
      ++files;
      // A case's name is its file's stem: a case the filter leaves out is not even read.
      if (filter && !filter->search(file.stem().string())) continue;
      cases.push_back(casefile::load(file));
    }
  } catch (const casefile::CaseError& e) {
    throw InputError(e.what());
  }
  if (cases.empty()) {
    std::string where;
    for (size_t k = 0; k < paths.size() && k < 3; ++k)
      where += (k ? ", " : "") + printable(paths[k]);
    if (paths.size() > 3) where += " and " + std::to_string(paths.size() - 3) + " more";
    std::string why = files > 0 ? std::to_string(files) + " case file" + (files > 1 ? "s" : "") +
                                      ", none matching --filter " + printable(o.filter, 80)
                                : "no *.json case file found";
    if (!notes.empty())
      why += "; " + std::to_string(notes.size()) + " passed over, the first " +
             notes.front().substr(notes.front().find("ignored ") + 8);
    throw InputError("no case matches in " + where + ": " + why);
  }
  for (const std::string& n : notes)
    std::fprintf(stderr, "%s\n", n.c_str());
  return cases;
}

gl::Target target_of(const Options& o) {
  gl::Target t;
  t.backend = o.gl.backend;
  t.driver = o.gl.driver;
  t.device_index = o.gl.device;
  return t;
}

std::unique_ptr<gl::Renderer> open_renderer(const Options& o) {
  try {
    return gl::create_renderer(target_of(o));
  } catch (const gl::Unavailable& e) {
    throw InputError(e.what());
  }
}

RunInfo run_info(const Options& o, const gl::GlInfo& gl, const ModelChoice& model) {
  RunInfo info;
  info.backend = gl::to_string(o.gl.backend);
  info.driver = o.gl.driver;
  check::CheckOptions judged = check_options(o);
  judged.model = model.model;
  info.model = check::model_text(judged);
  info.model_source = model.source;
  info.subpixel_bits = gl.subpixel_bits;
  info.tolerance = check::tolerance_text(judged, gl.subpixel_bits);
  info.gl_vendor = gl.vendor;
  info.gl_renderer = gl.renderer;
  info.gl_version = gl.version;
  info.gl_library = gl.library;
  info.gl_warnings = gl.warnings;
  info.gl_primitive_id_from_geometry_shader = gl.primitive_id_from_geometry_shader;
  info.mesa_prefix = o.gl.mesa;
  return info;
}

std::map<std::string, std::string> verdict_inputs(const Options& o) {
  const auto number = [](const std::optional<double>& v) {
    return v ? fmt::format("{}", *v) : std::string();
  };
  std::map<std::string, std::string> inputs = {
      {"strict_coverage", o.verdict.strict_coverage ? "true" : "false"},
      {"varying_ulps", number(o.verdict.varying_ulps)},
      {"depth_ulps", number(o.verdict.depth_ulps)}};
  for (const auto& [name, file] :
       {std::pair{"baseline", &o.baseline}, {"flakes", &o.flakes}, {"skips", &o.skips}})
    if (!file->empty()) {
      std::ifstream in(*file, std::ios::binary);
      std::string text((std::istreambuf_iterator<char>(in)), {});
      if (!in && !in.eof())
        throw InputError(std::string("--") + name + ": cannot read \"" + printable(*file, 200) +
                         "\"");
      inputs[name] = report::content_digest(text);
    } else {
      inputs[name] = "";
    }
  return inputs;
}

Baseline load_baseline(const Options& o) {
  if (o.baseline.empty()) return {};
  Baseline b;
  try {
    b = report::read_baseline(o.baseline);
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  if (const std::string note = report::ignored_note(b); !note.empty()) fmt::print("{}\n", note);
  return b;
}

void to_json(nlohmann::json& j, const Options& o) {
  j = nlohmann::json::object();
  o.model.write(j);
  o.gl.write(j);
  o.verdict.write(j);
  j["out"] = o.out;
  j["threads"] = o.threads;
}

void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          Options& o) {
  namespace f = option_fields;
  f::object(r, j, path);
  o.model.read(r, j, path);
  o.gl.read(r, j, path);
  o.verdict.read(r, j, path);
  o.out = f::text(r, j, path, "out");
  // Absent from the journals of runs before --threads.
  o.threads = j.contains("threads") ? f::whole(r, j, path, "threads", 0, 4096) : 0;
}

void from_json(const nlohmann::json& j, Options& o) {
  read(option_fields::reader(""), j, "options", o);
}

std::string options_json(const Options& o) {
  return nlohmann::json(o).dump();
}

Options options_from_json(const std::string& text) {
  Options o;
  read(option_fields::reader("the worker's options"), nlohmann::json::parse(text), "options", o);
  return o;
}

}  // namespace glrc::cli
