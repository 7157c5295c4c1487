#include "cli/option_groups.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/options_reader.hpp"
#include "cli/validators.hpp"
#include "driver_models/driver_models.hpp"

namespace glrc::cli {

namespace f = option_fields;

void ModelOptions::add_to(CLI::App& app) {
  app.add_option("--model", name,
                 "identified: the exact reference with the subpixel bits, planes and tie rule "
                 "`identify` finds for the implementation, cached (default); ideal: the exact "
                 "reference with the fixed model subpixel_bits=8 planes=unsnapped "
                 "tie=bottom-left, or what --subpixel-bits, --planes, --tie-break say; llvmpipe, "
                 "softpipe: bit-exact models of those drivers, for --tolerance exact")
      ->check(CLI::IsMember(model_choices()));
  app.add_option("--subpixel-bits", subpixel_bits,
                 "reference snapping: 0 (none) to 16; takes the model from the command line")
      ->check(CLI::Range(0, 16));
  add_enum_option(app, "--planes", planes,
                  "attribute planes from snapped or unsnapped positions; takes the model from "
                  "the command line");
  add_enum_option(app, "--tie-break", tie_break,
                  "pixel centres on an edge; takes the model from the command line");
}

bool ModelOptions::given_in(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands())
    for (const char* option : {"--subpixel-bits", "--planes", "--tie-break"})
      try {
        if (sub->count(option) > 0) return true;
      } catch (const CLI::OptionNotFound&) {
      }
  return false;
}

void ModelOptions::write(nlohmann::json& j) const {
  j["model"] = name;
  j["subpixel_bits"] = subpixel_bits;
  j["planes"] = to_string(planes);
  j["tie_break"] = to_string(tie_break);
  j["model_given"] = given;
}

void ModelOptions::read(const typed_json::Reader& r, const nlohmann::json& j,
                        const std::string& path) {
  name = f::text(r, j, path, "model", model_choices());
  subpixel_bits = f::whole(r, j, path, "subpixel_bits", 0, 16);
  planes = f::named<Planes>(r, j, path, "planes");
  tie_break = f::named<TieBreak>(r, j, path, "tie_break");
  given = f::flag(r, j, path, "model_given");
}

std::vector<std::string> model_choices() {
  std::vector<std::string> names = {"identified", "ideal"};
  for (const std::string& d : names_of<driver_models::Driver>())
    names.push_back(d);
  return names;
}

void GlOptions::add_to(CLI::App& app) {
  add_enum_option(app, "--backend", backend, "osmesa, egl (Mesa surfaceless) or egl-device");
  app.add_option(
      "--driver", driver,
      "Mesa gallium driver: llvmpipe, softpipe, zink (egl: GL on lavapipe); \"\" for a GPU");
  app.add_option("--device", device, "egl-device: which EGL device")->check(whole_number(0));
  app.add_option("--mesa", mesa,
                 "a Mesa install tree to run instead of the system's (scripts/mesa-fetch.sh "
                 "VERSION unpacks one into .mesa/VERSION)");
}

void GlOptions::write(nlohmann::json& j) const {
  j["backend"] = gl::to_string(backend);
  j["driver"] = driver;
  j["device"] = device;
}

void GlOptions::read(const typed_json::Reader& r, const nlohmann::json& j,
                     const std::string& path) {
  backend = f::named<gl::Backend>(r, j, path, "backend");
  driver = f::text(r, j, path, "driver");
  device = f::whole(r, j, path, "device", 0);
}

void VerdictOptions::add_to(CLI::App& app) {
  app.add_option("--tolerance-ulps", varying_ulps,
                 "varying tolerance in ULPs of the attribute's scale (overrides case files)")
      ->check(finite_number(0, true));
  app.add_option("--depth-tolerance-ulps", depth_ulps, "depth tolerance in ULPs of 1.0")
      ->check(finite_number(0, true));
  add_enum_option(app, "--tolerance", tolerance,
                  "spec: what the GL specification allows (default); exact: zero differing bits",
                  {"spec", "exact"});
  app.add_option("--spec-subpixel-bits", spec_subpixel_bits,
                 "position freedom of the spec tolerance (default: GL_SUBPIXEL_BITS as reported)")
      ->check(CLI::Range(4, 16));
  app.add_flag("--strict-coverage", strict_coverage,
               "count coverage mismatches at edges (within a subpixel step) as failures");
}

void VerdictOptions::write(nlohmann::json& j) const {
  j["tolerance"] = to_string(tolerance);
  j["strict_coverage"] = strict_coverage;
  if (spec_subpixel_bits) j["spec_subpixel_bits"] = *spec_subpixel_bits;
  if (varying_ulps) j["varying_ulps"] = *varying_ulps;
  if (depth_ulps) j["depth_ulps"] = *depth_ulps;
}

void VerdictOptions::read(const typed_json::Reader& r, const nlohmann::json& j,
                          const std::string& path) {
  tolerance = f::named<ToleranceMode>(r, j, path, "tolerance", {"spec", "exact"});
  strict_coverage = f::flag(r, j, path, "strict_coverage");
  spec_subpixel_bits.reset();
  varying_ulps.reset();
  depth_ulps.reset();
  if (j.contains("spec_subpixel_bits"))
    spec_subpixel_bits = f::whole(r, j, path, "spec_subpixel_bits", 4, 16);
  if (j.contains("varying_ulps")) varying_ulps = f::number(r, j, path, "varying_ulps", 0, 1e300);
  if (j.contains("depth_ulps")) depth_ulps = f::number(r, j, path, "depth_ulps", 0, 1e300);
}

}  // namespace glrc::cli
