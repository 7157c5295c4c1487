// glrefcheck identify: runs identify/'s probes and prints the evidence per choice (subpixel bits,
// attribute planes, tie-break rule, default provoking vertex, 24-bit depth rounding), a one-line
// summary and DIR/identify.json.
#include "cli/identify.hpp"

#include <fmt/core.h>

#include <fstream>
#include <string>
#include <vector>

#include "cli/output_dir.hpp"
#include "identify/identify.hpp"
#include "report/report.hpp"
#include "report/stamp.hpp"

namespace glrc::cli {
namespace {

using namespace glrc::identify;

// One row of a table: the candidate, its columns, and whether it is the one identified.
void print_row(bool best, const std::string& candidate, const std::vector<std::string>& cells,
               const std::vector<int>& widths) {
  std::string line = fmt::format("  {} {:<18}", best ? "*" : " ", candidate);
  for (size_t k = 0; k < cells.size(); ++k)
    line += fmt::format(" {:>{}}", cells[k], widths[k]);
  fmt::print("{}\n", line);
}

void print_header(const std::string& first, const std::vector<std::string>& columns,
                  const std::vector<int>& widths) {
  print_row(false, first, columns, widths);
}

void print_bits(const BitsFinding& f, size_t frames) {
  fmt::print(
      "1. subpixel bits: coverage of {} probe frames ({} triangles: thin ones at random float\n"
      "   positions, and edges that one grid's rounding moves across a pixel centre); pixel\n"
      "   centres exactly on an edge of the candidate are left to the tie rule\n",
      frames, f.triangles);
  const std::vector<int> w{20, 14};
  print_header("candidate", {"coverage mismatches", "ties skipped"}, w);
  for (const BitsCandidate& c : f.candidates)
    print_row(c.bits == f.identified, bits_name(c.bits),
              {std::to_string(c.mismatches), std::to_string(c.ties_skipped)}, w);
  const BitsCandidate& best =
      *std::find_if(f.candidates.begin(), f.candidates.end(),
                    [&](const BitsCandidate& c) { return c.bits == f.identified; });
  std::string verdict =
      f.identified == 0 ? "no snapping" : fmt::format("{} subpixel bits", f.identified);
  if (best.mismatches == 0)
    verdict += ", which explains every probe pixel";
  else
    verdict += fmt::format(", the closest: {} {}", best.mismatches,
                           best.mismatches == 1 ? "mismatch remains" : "mismatches remain");
  if (!f.distinct) verdict += " (other candidates explain the probes as well)";
  fmt::print("   identified: {}\n", verdict);
  if (f.identified == f.reported)
    fmt::print("   GL_SUBPIXEL_BITS reports {}: agrees\n\n", f.reported);
  else if (f.identified == 0)
    fmt::print(
        "   GL_SUBPIXEL_BITS reports {}: the report and the behaviour disagree (the driver does "
        "not snap)\n\n",
        f.reported);
  else
    fmt::print("   GL_SUBPIXEL_BITS reports {}: the report and the behaviour disagree\n\n",
               f.reported);
}

void print_planes(const PlanesFinding& f, int bits, size_t triangles) {
  fmt::print(
      "2. attribute planes: largest varying error in ULPs of the attribute's scale, on {}\n"
      "   perspective triangles at random float positions, with subpixel bits {}\n",
      triangles, bits_name(bits));
  const std::vector<int> w{12, 10, 14, 10};
  print_header("candidate", {"max ulps", "mean ulps", "values compared", "NaN/Inf"}, w);
  for (const PlanesCandidate& c : f.candidates)
    print_row(c.planes == f.identified, planes_name(c.planes),
              {fmt::format("{:.1f}", c.max_ulps), fmt::format("{:.2f}", c.mean_ulps),
               std::to_string(c.compared), std::to_string(c.non_finite)},
              w);
  if (!f.distinguishable)
    fmt::print(
        "   identified: unsnapped (no snapping: snapped and unsnapped planes are the same "
        "model)\n\n");
  else
    fmt::print("   identified: planes from {} positions\n\n", planes_name(f.identified));
}

void print_ties(const TieFinding& f, int bits, size_t triangles) {
  fmt::print(
      "3. tie-break rule: {} pixel centres exactly on one edge of {} triangles (quarter-pixel\n"
      "   vertices, subpixel bits {}); what GL took, by the edge's kind (inward normal)\n",
      f.centres, triangles, bits_name(bits));
  const std::vector<int> kw{8, 8};
  print_header("edge", {"centres", "GL took"}, kw);
  for (int k = 0; k < kKinds; ++k)
    print_row(false, kKindNames[k],
              {std::to_string(f.per_kind[size_t(k)]), std::to_string(f.taken[size_t(k)])}, kw);
  const std::vector<int> w{14, 22};
  print_header("candidate", {"centres wrong", "coverage mismatches"}, w);
  for (const TieCandidate& c : f.candidates)
    print_row(c.rule == f.identified, to_string(c.rule),
              {std::to_string(c.wrong_centres), std::to_string(c.mismatches)}, w);
  const TieCandidate& best =
      *std::find_if(f.candidates.begin(), f.candidates.end(),
                    [&](const TieCandidate& c) { return c.rule == f.identified; });
  if (f.explains_all)
    fmt::print("   identified: {}, which explains every tie\n\n", to_string(f.identified));
  else
    fmt::print(
        "   identified: {} fits best, but no rule explains every tie: {} of {} centres and {} "
        "pixels in all disagree with it\n\n",
        to_string(f.identified), best.wrong_centres, f.centres, best.mismatches);
}

void print_provoking(const ProvokingFinding& f) {
  fmt::print(
      "4. default provoking vertex: a flat varying on {} pixels of 16 triangles, on a context "
      "where\n   glProvokingVertex was never called\n",
      f.pixels);
  const std::vector<int> w{18};
  print_header("candidate", {"pixels matching"}, w);
  print_row(f.identified == ProvokingVertex::last, "last", {std::to_string(f.last)}, w);
  print_row(f.identified == ProvokingVertex::first, "first", {std::to_string(f.first)}, w);
  print_row(false, "(neither)", {std::to_string(f.neither)}, w);
  fmt::print("   identified: {} vertex{}; GL_PROVOKING_VERTEX reports {}{}\n\n",
             provoking_name(f.identified),
             f.identified == ProvokingVertex::last ? " (GL's default)" : " (GL's default is last)",
             provoking_name(f.reported), f.reported == f.identified ? ": agrees" : ": disagrees");
}

void print_depth(const DepthFinding& f) {
  fmt::print(
      "5. 24-bit depth: GL_DEPTH_COMPONENT24 read back as integers, against round and floor of\n"
      "   the exact z·(2^24 - 1) at each pixel centre; informative: the two differ there\n");
  const std::vector<int> w{8, 12, 7, 9, 8};
  print_header("probe", {"pixels", "informative", "round", "truncate", "neither"}, w);
  for (const DepthCategory& c : f.rows())
    print_row(false, c.name,
              {std::to_string(c.pixels), std::to_string(c.informative), std::to_string(c.round),
               std::to_string(c.truncate), std::to_string(c.neither)},
              w);
  const uint64_t chosen = f.identified == "round" ? f.total.round : f.total.truncate;
  fmt::print("   identified: {} ({} of {} informative pixels)\n\n",
             f.identified == "round" ? "round to nearest" : "truncate", chosen,
             f.total.informative);
}

void print_viewport(const ViewportFinding& f) {
  fmt::print(
      "6. viewport precision: triangles in a viewport of quarter-pixel bounds "
      "(glViewportIndexedf),\n"
      "   against the exact rendering of the floats and of the bounds rounded to whole pixels\n");
  if (!f.available) {
    fmt::print("   not probed: no glViewportIndexedf (OpenGL 4.1 or GL_ARB_viewport_array)\n\n");
    return;
  }
  const std::vector<int> w{20};
  print_header("candidate", {"coverage mismatches"}, w);
  for (const ViewportCandidate& c : f.candidates)
    print_row(c.name == f.identified, c.name, {std::to_string(c.mismatches)}, w);
  const bool exact = f.identified == "float";
  fmt::print(
      "   identified: {}; GL_VIEWPORT_SUBPIXEL_BITS reports {}{}\n\n",
      exact ? "the float bounds, exactly" : "bounds rounded to whole pixels (" + f.identified + ")",
      f.reported,
      exact && f.reported == 0
          ? " (it may round to whole pixels; the allowance lets it, ref/viewport.hpp)"
          : "");
}

void print_depth_offset(const DepthOffsetFinding& f) {
  fmt::print(
      "7. polygon offset: triangles on planes as steep along x as along y, depths in [1/2, 3/4],\n"
      "   drawn with glPolygonOffset(1, 0) and (0, 65536) into the 32F depth buffer\n");
  if (!f.available) {
    fmt::print("   not probed\n\n");
    return;
  }
  fmt::print(
      "   slope: the offset is {:.6f} x max(|dz/dx|, |dz/dy|) ({}; the length would be 1.414214)\n",
      f.slope_ratio,
      f.slope == "max"      ? "the larger slope, equation 14.12"
      : f.slope == "length" ? "their length, equation 14.11"
                            : "neither of GL's");
  fmt::print("   units: the offset is {:.6f} x units·2^(e-23) ({})\n\n", f.units_ratio,
             f.units == "r"    ? "GL's r"
             : f.units == "2r" ? "twice GL's r"
                               : "not GL's r");
}

std::unique_ptr<gl::Renderer> open_raw_renderer(const Options& o) {
  gl::Target t;
  t.backend = o.gl.backend;
  t.driver = o.gl.driver;
  t.device_index = o.gl.device;
  t.set_provoking_vertex = false;
  t.depth_format = gl::DepthFormat::unorm24;
  try {
    return gl::create_renderer(t);
  } catch (const gl::Unavailable& e) {
    throw InputError(e.what());
  }
}

}  // namespace

ModelChoice choose_model(const Options& o, gl::Renderer& renderer) {
  return identify::choose_model(model_from_command_line(o), o.model.reference_model(), renderer);
}

int cmd_identify(const Options& o) {
  const auto start = Clock::now();
  const OutputFolder folder = output_folder(o.out);
  // Only an identify.json glrefcheck identify wrote and nobody changed since (its stamp).
  check_replaceable(folder.path / "identify.json", "--out " + o.out, "identify");
  const std::filesystem::path& out = folder.path;
  auto renderer = open_renderer(o);
  auto raw = open_raw_renderer(o);
  const gl::GlInfo& info = renderer->info();
  fmt::print("glrefcheck identify: {} ({}), GL {}\n\n", info.renderer, gl::to_string(o.gl.backend),
             info.version);
  std::fflush(stdout);

  Identification id;
  try {
    id = identify::identify(*renderer, *raw);
  } catch (const ProbeError& e) {
    throw InputError(e.what());
  }
  const ModelFindings& found = id.model;
  print_bits(found.bits, found.coverage_frames);
  print_planes(found.planes, found.bits.identified, found.plane_triangles);
  print_ties(found.ties, found.bits.identified, found.tie_triangles);
  print_provoking(id.provoking);
  print_depth(id.depth);
  print_viewport(id.viewport);
  print_depth_offset(id.offset);
  fmt::print("{}\n", id.summary());

  nlohmann::json j = identification_json(id, info, raw->info().initial_provoking_vertex,
                                         gl::to_string(o.gl.backend), o.gl.driver);
  j["seconds"] = seconds_since(start);
  const std::filesystem::path file = out / "identify.json";
  report::write_file_atomically(file, report::stamped_json("identify", j.dump(2) + "\n"));
  fmt::print("wrote {}/identify.json in {:.2f} s\n", o.out, seconds_since(start));
  return 0;
}

}  // namespace glrc::cli
