#include "cli/workers/protocol.hpp"

#include <stdexcept>

#include "casefile/wire.hpp"
#include "identify/model_cache.hpp"

namespace glrc::gl {

void to_json(nlohmann::json& j, const GlInfo& info) {
  j = {{"vendor", info.vendor},
       {"renderer", info.renderer},
       {"version", info.version},
       {"platform", info.platform},
       {"library", info.library},
       {"subpixel_bits", info.subpixel_bits},
       {"initial_provoking_vertex", std::string(name_of(info.initial_provoking_vertex))},
       {"primitive_id_from_geometry_shader", info.primitive_id_from_geometry_shader},
       {"warnings", info.warnings}};
}

void from_json(const nlohmann::json& j, GlInfo& info) {
  info.vendor = j.at("vendor"), info.renderer = j.at("renderer"), info.version = j.at("version");
  info.platform = j.at("platform"), info.library = j.at("library");
  info.subpixel_bits = j.at("subpixel_bits");
  const auto provoking =
      from_name<ProvokingVertex>(j.at("initial_provoking_vertex").get<std::string>());
  if (!provoking) throw std::runtime_error("initial_provoking_vertex: expected first or last");
  info.initial_provoking_vertex = *provoking;
  info.primitive_id_from_geometry_shader = j.at("primitive_id_from_geometry_shader");
  info.warnings = j.at("warnings").get<std::vector<std::string>>();
}

}  // namespace glrc::gl

namespace glrc::cli {

nlohmann::json hello_message(const gl::GlInfo& info, const std::vector<std::string>& driver_files) {
  nlohmann::json hello = info;
  hello["driver_files"] = driver_files;
  return {{"hello", hello}};
}

std::string job_line(size_t index, const Case& c, bool images, const Model& model) {
  const nlohmann::json job = {
      {"index", index}, {"file", c.source_path}, {"case", casefile::to_wire(c)},
      {"name", c.name}, {"images", images},      {"model", identify::model_json(model)}};
  return job.dump() + "\n";
}

CaseResult unfinished_result(const Case& c, Status status, const std::string& message,
                             double seconds) {
  CaseResult r;
  r.name = c.name;
  r.description = c.description;
  r.status = r.outcome = status;
  r.message = message;
  r.seconds = seconds;
  return r;
}

std::string result_line(size_t index, const std::string& result_json, bool images) {
  return "{\"index\":" + std::to_string(index) + (images ? ",\"images\":true" : "") +
         ",\"result\":" + result_json + "}";
}

std::optional<ResultLine> read_result_line(std::string_view line) {
  constexpr std::string_view head = "{\"index\":", images = ",\"images\":true",
                             result = ",\"result\":";
  if (!line.starts_with(head) || !line.ends_with('}')) return std::nullopt;
  size_t at = head.size(), digits = 0;
  ResultLine r;
  for (; at < line.size() && line[at] >= '0' && line[at] <= '9' && digits < 18; ++at, ++digits)
    r.index = r.index * 10 + size_t(line[at] - '0');
  if (digits == 0) return std::nullopt;
  line.remove_prefix(at);
  if (line.starts_with(images)) r.images = true, line.remove_prefix(images.size());
  if (!line.starts_with(result)) return std::nullopt;
  line.remove_prefix(result.size());
  line.remove_suffix(1);  // the line's closing brace
  r.result = line;
  return r;
}

}  // namespace glrc::cli
