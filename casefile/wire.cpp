#include "casefile/wire.hpp"

#include <bit>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace glrc::casefile {
namespace {

using json = nlohmann::json;

// 32-bit words as 8 hex digits each, in one string: a 300,000-vertex case is a few long
// strings, which JSON reads at memcpy speed, instead of millions of numbers.
void put(std::string& s, uint32_t w) {
  constexpr char kHex[] = "0123456789abcdef";
  for (int shift = 28; shift >= 0; shift -= 4)
    s += kHex[(w >> shift) & 0xF];
}
void put(std::string& s, float f) {
  put(s, std::bit_cast<uint32_t>(f));
}

class Words {
 public:
  explicit Words(const std::string& s) : s_(s) {
    if (s_.size() % 8 != 0) throw std::runtime_error("wire: a word string of odd length");
  }
  uint32_t word() {
    if (at_ + 8 > s_.size()) throw std::runtime_error("wire: too few words");
    uint32_t w = 0;
    for (int k = 0; k < 8; ++k) {
      const char c = s_[at_++];
      const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
      if (d < 0) throw std::runtime_error("wire: not a hex digit");
      w = w << 4 | uint32_t(d);
    }
    return w;
  }
  float real() { return std::bit_cast<float>(word()); }
  bool done() const { return at_ == s_.size(); }

 private:
  const std::string& s_;
  size_t at_ = 0;
};

}  // namespace

json to_wire(const Case& c) {
  std::string clip, values, triangles, scalars;
  clip.reserve(c.vertices.size() * 32);
  for (const Vertex& v : c.vertices) {
    for (float f : v.clip)
      put(clip, f);
    for (float f : v.values)
      put(values, f);
  }
  for (const auto& t : c.triangles)
    for (uint32_t i : t)
      put(triangles, i);
  put(scalars, c.depth_near);
  put(scalars, c.depth_far);
  json varyings = json::array();
  for (const Varying& v : c.varyings)
    varyings.push_back({v.name, v.size, int(v.interpolation), int(v.builtin),
                        v.layout.origin_upper_left, v.layout.pixel_center_integer});
  // The draws (only a case that has them): the triangles above are their assembly.
  json draws = json::array();
  for (const Draw& d : c.draws) {
    std::string indices;
    for (uint32_t i : d.indices)
      put(indices, i);
    draws.push_back({int(d.mode), int(d.index_type), d.first, d.count, int(d.restart),
                     d.restart_index, indices});
  }
  json tolerance = json::object();
  if (c.tolerance.varying_ulps) tolerance["varying_ulps"] = *c.tolerance.varying_ulps;
  if (c.tolerance.depth_ulps) tolerance["depth_ulps"] = *c.tolerance.depth_ulps;
  if (c.tolerance.allow_boundary) tolerance["allow_boundary"] = *c.tolerance.allow_boundary;
  json out = {{"name", c.name},
              {"description", c.description},
              {"source_path", c.source_path},
              {"framebuffer", {c.fb_width, c.fb_height}},
              {"viewport", {c.viewport.x, c.viewport.y, c.viewport.width, c.viewport.height}},
              {"depth_range", scalars},
              {"state",
               {int(c.cull), int(c.front_face), int(c.provoking), int(c.depth_func),
                std::bit_cast<uint32_t>(c.depth_clear), c.work_arounds}},
              {"varyings", varyings},
              {"vertices", c.vertices.size()},
              {"clip", clip},
              {"values", values},
              {"triangles", triangles},
              {"tolerance", tolerance}};
  if (!draws.empty()) out["draws"] = draws;
  if (c.scissor) out["scissor"] = {c.scissor->x, c.scissor->y, c.scissor->width, c.scissor->height};
  if (c.distances.any()) {
    std::string distances;
    for (const Vertex& v : c.vertices)
      for (float f : v.distances)
        put(distances, f);
    out["distances"] = {c.distances.clip, c.distances.cull, c.distances.enabled, distances};
  }
  if (c.clip_origin != ClipOrigin::lower_left || c.clip_depth != ClipDepth::negative_one_to_one)
    out["clip_control"] = {int(c.clip_origin), int(c.clip_depth)};
  if (c.depth_clamp) out["depth_clamp"] = true;
  if (const auto& o = c.polygon_offset) {
    // Bits, so that every float (a negative zero too) comes back as it went.
    json offset = {std::bit_cast<uint32_t>(o->factor), std::bit_cast<uint32_t>(o->units)};
    if (o->clamp) offset.push_back(std::bit_cast<uint32_t>(*o->clamp));
    out["polygon_offset"] = offset;
  }
  return out;
}

Case from_wire(const json& j) {
  try {
    Case c;
    c.name = j.at("name").get<std::string>();
    c.description = j.at("description").get<std::string>();
    c.source_path = j.at("source_path").get<std::string>();
    c.fb_width = j.at("framebuffer").at(0).get<int>();
    c.fb_height = j.at("framebuffer").at(1).get<int>();
    const json& vp = j.at("viewport");
    c.viewport = {vp.at(0).get<float>(), vp.at(1).get<float>(), vp.at(2).get<float>(),
                  vp.at(3).get<float>()};
    Words depth(j.at("depth_range").get_ref<const std::string&>());
    c.depth_near = depth.real(), c.depth_far = depth.real();
    const json& st = j.at("state");
    c.cull = CullFace(st.at(0).get<int>());
    c.front_face = FrontFace(st.at(1).get<int>());
    c.provoking = ProvokingVertex(st.at(2).get<int>());
    c.depth_func = DepthFunc(st.at(3).get<int>());
    c.depth_clear = std::bit_cast<float>(st.at(4).get<uint32_t>());
    c.work_arounds = st.at(5).get<bool>();
    for (const json& v : j.at("varyings"))
      c.varyings.push_back({v.at(0).get<std::string>(),
                            v.at(1).get<int>(),
                            Interpolation(v.at(2).get<int>()),
                            Builtin(v.at(3).get<int>()),
                            {v.at(4).get<bool>(), v.at(5).get<bool>()}});
    const size_t n = j.at("vertices").get<size_t>(), components = size_t(c.component_count());
    Words clip(j.at("clip").get_ref<const std::string&>());
    Words values(j.at("values").get_ref<const std::string&>());
    c.vertices.resize(n);
    for (Vertex& v : c.vertices) {
      for (float& f : v.clip)
        f = clip.real();
      v.values.resize(components);
      for (float& f : v.values)
        f = values.real();
    }
    Words triangles(j.at("triangles").get_ref<const std::string&>());
    while (!triangles.done())
      c.triangles.push_back({triangles.word(), triangles.word(), triangles.word()});
    if (!clip.done() || !values.done()) throw std::runtime_error("wire: words left over");
    if (j.contains("scissor")) {
      const json& b = j.at("scissor");
      c.scissor =
          Scissor{b.at(0).get<int>(), b.at(1).get<int>(), b.at(2).get<int>(), b.at(3).get<int>()};
    }
    if (j.contains("distances")) {
      const json& d = j.at("distances");
      c.distances.clip = d.at(0).get<int>(), c.distances.cull = d.at(1).get<int>();
      c.distances.enabled = d.at(2).get<uint32_t>();
      if (c.distances.clip < 0 || c.distances.cull < 0 ||
          c.distances.clip + c.distances.cull > kMaxDistances)
        throw std::runtime_error("wire: distances out of range");
      Words words(d.at(3).get_ref<const std::string&>());
      for (Vertex& v : c.vertices) {
        v.distances.resize(size_t(c.distances.clip + c.distances.cull));
        for (float& f : v.distances)
          f = words.real();
      }
      if (!words.done()) throw std::runtime_error("wire: distance words left over");
    }
    if (j.contains("clip_control")) {
      const json& cc = j.at("clip_control");
      const int origin = cc.at(0).get<int>(), mode = cc.at(1).get<int>();
      if (origin < 0 || origin > 1 || mode < 0 || mode > 1)
        throw std::runtime_error("wire: clip_control out of range");
      c.clip_origin = ClipOrigin(origin), c.clip_depth = ClipDepth(mode);
    }
    c.depth_clamp = j.contains("depth_clamp") && j.at("depth_clamp").get<bool>();
    if (j.contains("polygon_offset")) {
      const json& o = j.at("polygon_offset");
      PolygonOffset& p = c.polygon_offset.emplace();
      p.factor = std::bit_cast<float>(o.at(0).get<uint32_t>());
      p.units = std::bit_cast<float>(o.at(1).get<uint32_t>());
      if (o.size() > 2) p.clamp = std::bit_cast<float>(o.at(2).get<uint32_t>());
    }
    if (j.contains("draws")) {
      for (const json& d : j.at("draws")) {
        Draw draw;
        draw.mode = PrimitiveMode(d.at(0).get<int>());
        draw.index_type = IndexType(d.at(1).get<int>());
        draw.first = d.at(2).get<uint32_t>();
        draw.count = d.at(3).get<uint32_t>();
        draw.restart = Restart(d.at(4).get<int>());
        draw.restart_index = d.at(5).get<uint32_t>();
        Words indices(d.at(6).get_ref<const std::string&>());
        while (!indices.done())
          draw.indices.push_back(indices.word());
        c.draws.push_back(std::move(draw));
      }
    }
    const json& t = j.at("tolerance");
    if (t.contains("varying_ulps")) c.tolerance.varying_ulps = t["varying_ulps"].get<double>();
    if (t.contains("depth_ulps")) c.tolerance.depth_ulps = t["depth_ulps"].get<double>();
    if (t.contains("allow_boundary")) c.tolerance.allow_boundary = t["allow_boundary"].get<bool>();
    return c;
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("wire: ") + e.what());
  }
}

}  // namespace glrc::casefile
