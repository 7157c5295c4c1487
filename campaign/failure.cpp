#include "campaign/failure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glrc::campaign {
namespace {

// The channel's kind: "depth" ("depth_offset" in a case with a polygon offset, else
// "depth_clamp" under GL_DEPTH_CLAMP: drivers go wrong in those apart, and a known bug of one
// must not hide the others; gl_FragCoord.z's too), the qualifier of the varying it belongs to,
// or "other" for a built-in's other components.
std::string channel_kind(const Case& c, const std::string& channel) {
  const std::string depth = c.polygon_offset ? "depth_offset"
                            : c.depth_clamp  ? "depth_clamp"
                                             : "depth";
  // gl_FragCoord.z is the fragment's depth, offset included.
  if (channel == "depth" || channel == "gl_FragCoord.z") return depth;
  const std::vector<std::string> names = component_names(c);
  const std::vector<int> varying = component_varying(c);
  // A built-in's ("other"): gl_FragCoord's qualifier is noperspective, and a known bug of
  // noperspective varyings (the clipper's) must not hide a failure of gl_FragCoord.
  for (size_t k = 0; k < names.size(); ++k)
    if (names[k] == channel) {
      const Varying& v = c.varyings[size_t(varying[k])];
      return v.is_builtin() ? "other" : std::string(name_of(v.interpolation));
    }
  return "other";
}

std::string number(float x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(x));
  return text;
}

}  // namespace

std::string Failure::signature() const {
  const std::string name(name_of(kind));
  return detail.empty() ? name : name + "/" + detail;
}

std::vector<Failure> failures_of(const Case& c, const CaseResult& r) {
  switch (r.outcome) {
    case Status::crash:
      return {{FailureClass::crash, ""}};
    case Status::timeout:
      return {{FailureClass::timeout, ""}};
    case Status::error:
      return {{FailureClass::error, ""}};
    case Status::fail:
      break;
    default:
      return {};
  }
  std::vector<Failure> found;
  auto add = [&](FailureClass kind, const std::string& detail) {
    const Failure f{kind, detail};
    for (const Failure& g : found)
      if (g == f) return;
    found.push_back(f);
  };
  for (const ChannelStats& ch : r.channels)
    if (ch.non_finite > 0) add(FailureClass::non_finite, channel_kind(c, ch.name));
  if (r.coverage.gaps > 0) add(FailureClass::gap, "");
  if (r.coverage.double_hits > 0) add(FailureClass::double_hit, "");
  if (r.coverage.fill_rule > 0 && r.coverage.failures > 0) add(FailureClass::fill_rule, "");
  // Under strict coverage the boundary's mismatches fail too: their own class, not value/other.
  if (!r.tolerance.allow_boundary) {
    if (r.coverage.within_snapping > 0) add(FailureClass::boundary, "within_snapping");
    if (r.coverage.exact_tie > 0) add(FailureClass::boundary, "exact_tie");
  }
  for (const ChannelStats& ch : r.channels)
    if (ch.over_tolerance > ch.non_finite) add(FailureClass::value, channel_kind(c, ch.name));
  if (found.empty()) add(FailureClass::value, "other");
  return found;
}

std::optional<std::string> failure_name_problem(std::string_view name) {
  if (name.find('/') != std::string_view::npos) {
    std::string stem(name);
    std::replace(stem.begin(), stem.end(), '/', '_');
    return "a failure's file name (" + stem + "), not its signature";
  }
  // Each class, alone or with the details failures_of gives it.
  static const std::vector<std::string_view> channel_kinds = {
      "depth", "depth_offset", "depth_clamp", "smooth", "flat", "noperspective", "other"};
  for (const auto& [kind, class_name] : Names<FailureClass>::table) {
    if (name == class_name) return std::nullopt;
    if (!name.starts_with(class_name) || name.size() <= class_name.size() ||
        name[class_name.size()] != '_')
      continue;
    const std::string_view detail = name.substr(class_name.size() + 1);
    const bool has_channel = kind == FailureClass::non_finite || kind == FailureClass::value;
    if (has_channel &&
        std::find(channel_kinds.begin(), channel_kinds.end(), detail) != channel_kinds.end())
      return std::nullopt;
    if (kind == FailureClass::boundary && (detail == "within_snapping" || detail == "exact_tie"))
      return std::nullopt;
  }
  return std::string(
      "a campaign failure's name: crash, timeout, error, gap, double_hit, fill_rule, "
      "non_finite_<kind> or value_<kind> (kind: depth, depth_offset, depth_clamp, smooth, flat, "
      "noperspective, other), boundary_within_snapping or boundary_exact_tie");
}

std::string describe(const Failure& f, const CaseResult& r) {
  std::string line = f.signature();
  // A non_finite failure's pixels are GL's NaN and Inf; a value failure's the finite values over
  // the allowance (the NaN and Inf among them are the non_finite failure's), shown by the worst
  // such pixel kept.
  auto worst_of = [&](bool non_finite) -> std::string {
    for (const ChannelStats& ch : r.channels) {
      const uint64_t pixels = non_finite ? ch.non_finite : ch.over_tolerance - ch.non_finite;
      if (pixels == 0 || (!non_finite && ch.over_tolerance < ch.non_finite)) continue;
      const auto p = std::find_if(ch.worst.begin(), ch.worst.end(), [&](const WorstPixel& w) {
        return std::isfinite(w.gl) != non_finite;
      });
      if (p == ch.worst.end()) return ": " + ch.name + ", " + std::to_string(pixels) + " pixels";
      return ": " + ch.name + " at (" + std::to_string(p->x) + ", " + std::to_string(p->y) +
             "): GL " + number(p->gl) + ", reference " + number(p->reference) +
             (non_finite ? "" : ", " + number(float(p->ratio)) + "x the allowance") + ", " +
             std::to_string(pixels) + " pixels";
    }
    return "";
  };
  auto mismatch = [&](CoverageStats::Label label, uint64_t count) -> std::string {
    for (const CoverageStats::Pixel& p : r.coverage.mismatches)
      if (p.label == label)
        return ": (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") reference primitive " +
               std::to_string(p.reference) + ", GL " + std::to_string(p.gl) + ", " +
               std::to_string(count) + " pixels";
    return ": " + std::to_string(count) + " pixels";
  };
  switch (f.kind) {
    case FailureClass::crash:
    case FailureClass::timeout:
    case FailureClass::error:
      return line + ": " + r.message.substr(0, 300);
    case FailureClass::non_finite:
      return line + worst_of(true);
    case FailureClass::gap:
      return line + mismatch(CoverageStats::Label::gap, r.coverage.gaps);
    case FailureClass::double_hit:
      return line + mismatch(CoverageStats::Label::double_hit, r.coverage.double_hits);
    case FailureClass::fill_rule:
      return line + mismatch(CoverageStats::Label::fill_rule, r.coverage.fill_rule);
    case FailureClass::boundary:
      return f.detail == "exact_tie"
                 ? line + mismatch(CoverageStats::Label::exact_tie, r.coverage.exact_tie)
                 : line +
                       mismatch(CoverageStats::Label::within_snapping, r.coverage.within_snapping);
    case FailureClass::value:
      return line + worst_of(false);
  }
  return line;
}

}  // namespace glrc::campaign
