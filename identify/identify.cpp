#include "identify/identify.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <utility>

#include "identify/model_cache.hpp"

namespace glrc::identify {
namespace {

using json = nlohmann::json;

constexpr uint64_t kSeed = 0x5eed1de47;

// Findings 1 to 3. `rnd` draws the probes; findings 4 and 5 draw theirs after these, so the
// probes are the same in every use.
ModelFindings find_model(gl::Renderer& renderer, Random& rnd) {
  ModelFindings f;
  const std::vector<Probe> coverage = render_all(renderer, subpixel_probes(rnd));
  f.bits = identify_bits(coverage, renderer.info().subpixel_bits);
  f.coverage_frames = coverage.size();

  const std::vector<Probe> planes_probes =
      render_all(renderer, {plane_triangles(rnd, 0), plane_triangles(rnd, 1)});
  f.planes = identify_planes(planes_probes, f.bits.identified);
  f.plane_triangles = triangle_count(planes_probes);

  std::vector<TieCentre> centres;
  std::vector<Case> tie_cases;
  for (int k = 0; k < 2; ++k)
    tie_cases.push_back(tie_triangles(rnd, k, size_t(k), centres));
  const std::vector<Probe> tie_probes = render_all(renderer, std::move(tie_cases));
  f.ties = identify_ties(tie_probes, centres, f.bits.identified);
  f.tie_triangles = triangle_count(tie_probes);
  return f;
}

}  // namespace

Model ModelFindings::model() const {
  Model m;
  m.subpixel_bits = bits.identified;
  m.planes = planes.identified;
  m.tie_break = ties.identified;
  return m;
}

std::string Identification::summary() const {
  return fmt::format("identify: subpixel_bits={} planes={} tie={} provoking_default={} depth24={}",
                     model.bits.identified, planes_name(model.planes.identified),
                     to_string(model.ties.identified), provoking_name(provoking.identified),
                     depth.identified);
}

ModelFindings find_model(gl::Renderer& renderer) {
  Random rnd(kSeed);
  return find_model(renderer, rnd);
}

Model identify_model(gl::Renderer& renderer) {
  return find_model(renderer).model();
}

Identification identify(gl::Renderer& renderer, gl::Renderer& raw) {
  Random rnd(kSeed);
  Identification id;
  id.model = find_model(renderer, rnd);
  // What identify found is what run, diff and selftest would identify: keep it for them.
  const gl::GlInfo& info = renderer.info();
  model_cache_slot(info.renderer, info.version, driver_files(info)).save(id.model.model());

  const Case provoking_case = provoking_triangles(rnd);
  const Probe provoking_probe{provoking_case, render_gl(raw, provoking_case)};
  id.provoking = identify_provoking(provoking_probe, raw.info().initial_provoking_vertex);

  std::vector<std::vector<DepthTriangle>> exact(3);
  std::vector<Case> depth_cases;
  for (int k = 0; k < 3; ++k)
    depth_cases.push_back(depth_triangles(rnd, k, exact[size_t(k)]));
  id.depth = identify_depth(render_all(raw, std::move(depth_cases)), exact);

  // Drawn last: the earlier probes' random draws stay as they were.
  const Case viewport_case = viewport_triangles(rnd);
  if (info.viewport_subpixel_bits >= 0)
    id.viewport = identify_viewport({viewport_case, render_gl(renderer, viewport_case)},
                                    id.model.model(), info.viewport_subpixel_bits);
  // On the harness's 32F depth buffer, whose r the offset's units count.
  id.offset = identify_depth_offset(render_all(renderer, depth_offset_cases(rnd)));
  return id;
}

nlohmann::json identification_json(const Identification& id, const gl::GlInfo& info,
                                   ProvokingVertex raw_provoking, const std::string& backend,
                                   const std::string& driver) {
  const BitsFinding& bits = id.model.bits;
  const PlanesFinding& planes = id.model.planes;
  const TieFinding& ties = id.model.ties;
  const ProvokingFinding& provoking = id.provoking;
  const DepthFinding& depth = id.depth;
  json j;
  j["backend"] = backend;
  j["driver"] = driver;
  j["gl"] = {{"vendor", info.vendor},
             {"renderer", info.renderer},
             {"version", info.version},
             {"platform", info.platform},
             {"subpixel_bits", info.subpixel_bits},
             {"initial_provoking_vertex", provoking_name(raw_provoking)}};
  json bit_rows = json::array();
  for (const BitsCandidate& c : bits.candidates)
    bit_rows.push_back(
        {{"bits", c.bits}, {"mismatches", c.mismatches}, {"ties_skipped", c.ties_skipped}});
  j["subpixel_bits"] = {
      {"identified", bits.identified}, {"snapping", bits.identified != 0},
      {"reported", bits.reported},     {"agrees_with_reported", bits.identified == bits.reported},
      {"distinct", bits.distinct},     {"triangles", bits.triangles},
      {"candidates", bit_rows}};
  json plane_rows = json::array();
  for (const PlanesCandidate& c : planes.candidates)
    plane_rows.push_back({{"planes", planes_name(c.planes)},
                          {"max_ulps", c.max_ulps},
                          {"mean_ulps", c.mean_ulps},
                          {"compared", c.compared},
                          {"non_finite", c.non_finite}});
  j["planes"] = {{"identified", planes_name(planes.identified)},
                 {"distinguishable", planes.distinguishable},
                 {"candidates", plane_rows}};
  json tie_rows = json::array(), kinds = json::array();
  for (const TieCandidate& c : ties.candidates)
    tie_rows.push_back({{"rule", to_string(c.rule)},
                        {"centres_wrong", c.wrong_centres},
                        {"coverage_mismatches", c.mismatches}});
  for (int k = 0; k < kKinds; ++k)
    kinds.push_back({{"edge", kKindNames[k]},
                     {"centres", ties.per_kind[size_t(k)]},
                     {"taken", ties.taken[size_t(k)]}});
  j["tie_break"] = {{"identified", to_string(ties.identified)},
                    {"explains_all", ties.explains_all},
                    {"centres", ties.centres},
                    {"edges", kinds},
                    {"candidates", tie_rows}};
  j["provoking_default"] = {{"identified", provoking_name(provoking.identified)},
                            {"reported", provoking_name(provoking.reported)},
                            {"pixels", provoking.pixels},
                            {"first", provoking.first},
                            {"last", provoking.last},
                            {"neither", provoking.neither}};
  json depth_rows = json::array();
  for (const DepthCategory& c : depth.rows())
    depth_rows.push_back({{"probe", c.name},
                          {"pixels", c.pixels},
                          {"informative", c.informative},
                          {"round", c.round},
                          {"truncate", c.truncate},
                          {"neither", c.neither}});
  j["depth24"] = {{"identified", depth.identified}, {"probes", depth_rows}};
  const ViewportFinding& viewport = id.viewport;
  json viewport_rows = json::array();
  for (const ViewportCandidate& c : viewport.candidates)
    viewport_rows.push_back({{"viewport", c.name}, {"coverage_mismatches", c.mismatches}});
  j["viewport_precision"] = {{"available", viewport.available},
                             {"reported_subpixel_bits", viewport.reported},
                             {"identified", viewport.identified},
                             {"pixels", viewport.pixels},
                             {"candidates", viewport_rows}};
  const DepthOffsetFinding& offset = id.offset;
  j["depth_offset"] = {{"available", offset.available}, {"pixels", offset.pixels},
                       {"slope", offset.slope},         {"slope_ratio", offset.slope_ratio},
                       {"units", offset.units},         {"units_ratio", offset.units_ratio}};
  j["summary"] = id.summary();
  return j;
}

std::string bits_name(int bits) {
  return bits == 0 ? "none" : std::to_string(bits);
}

const char* planes_name(Planes p) {
  return to_string(p);
}

const char* provoking_name(ProvokingVertex p) {
  return name_of(p).data();  // the table's names are string literals, NUL-terminated
}

ModelChoice fallback_model(const Model& fallback, const std::string& why) {
  std::string reason = why;
  std::replace(reason.begin(), reason.end(), '\n', ' ');
  if (reason.size() > 200) reason = reason.substr(0, 197) + "...";
  return {fallback, "default (identify failed: " + reason + ")"};
}

ModelChoice choose_model(const std::optional<ModelChoice>& given, const Model& fallback,
                         gl::Renderer& renderer) {
  if (given) return *given;
  const gl::GlInfo& info = renderer.info();
  const ModelCacheSlot cache = model_cache_slot(info.renderer, info.version, driver_files(info));
  if (const auto cached = cache.load()) return {*cached, "identify (cached)"};
  Model m;
  try {
    m = identify_model(renderer);
  } catch (const std::exception& e) {
    return fallback_model(fallback, e.what());
  }
  cache.save(m);
  return {m, "identify"};
}

}  // namespace glrc::identify
