// A Case as case-file text (write.hpp): hand-written JSON so that the layout is fixed (one
// vertex per line, the triangles packed a few per line) and every number is chosen to read back
// with the same bits through the loader's rules (typed_json::Reader::float32).
#include "casefile/write.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string_view>
#include <system_error>

namespace glrc::casefile {
namespace {

// Appends each part to `out` (no temporaries: GCC 12 at -O3 warns, wrongly, about the memcpy of
// `"literal" + std::string`, which -Werror makes fatal).
template <class... Parts>
void add(std::string& out, const Parts&... parts) {
  (out.append(std::string_view(parts)), ...);
}

// `s` as a JSON string: `"` and `\` escaped, control characters as \n, \r, \t or \u00XX, every
// other byte as it is (a byte that is not UTF-8 is written as is, and the loader refuses it).
std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (ch == '\n') {
      out += "\\n";
    } else if (ch == '\r') {
      out += "\\r";
    } else if (ch == '\t') {
      out += "\\t";
    } else if (u < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(u));
      out += buf;
    } else {
      out += ch;
    }
  }
  out += '"';
  return out;
}

// A non-finite value as the string the loader names in its refusal.
std::string nonfinite(double d) {
  return std::isnan(d) ? "\"nan\"" : d < 0 ? "\"-inf\"" : "\"inf\"";
}

// The shortest decimal that reads back as `f` (std::to_chars: printf's %f or %e form, whichever
// is shorter, so always valid as a JSON number's text too: "0.5", "1e-30", "16777215").
std::string shortest(float f) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  return std::string(buf, r.ptr);
}

// C99 hex, "0x1.8p-3", "-0x1.fffffep+127" (std::to_chars writes no "0x"): exact, always.
std::string hex(float f) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, f, std::chars_format::hex);
  const std::string_view s(buf, size_t(r.ptr - buf));
  std::string out;
  if (s[0] == '-')
    add(out, "-0x", s.substr(1));
  else
    add(out, "0x", s);
  return out;
}

// A float32 as the loader reads it back bit for bit (typed_json::Reader::float32):
//   - a plain JSON number when its shortest decimal is the float exactly as a double: the JSON
//     parser then reads that double exactly (an integer token exactly, a fraction through a
//     correctly rounded strtod), and its one rounding to float32 changes nothing;
//   - otherwise a string holding the shortest decimal, which strtof reads in one rounding: the
//     shortest round-trip decimal rounds to the float it came from (checked here with
//     std::from_chars, correctly rounded like glibc's strtof);
//   - a C99 hex string if that check ever failed; "-0.0" for a negative zero (the JSON number
//     -0 is an integer token and would lose the sign).
std::string number(float f) {
  if (!std::isfinite(f)) return nonfinite(f);
  if (f == 0.0f && std::signbit(f)) return "\"-0.0\"";
  const std::string s = shortest(f);
  double d = 0;
  const auto rd = std::from_chars(s.data(), s.data() + s.size(), d);
  if (rd.ec == std::errc() && rd.ptr == s.data() + s.size() && d == double(f)) return s;
  float back = 0;
  const auto rf = std::from_chars(s.data(), s.data() + s.size(), back);
  if (rf.ec == std::errc() && rf.ptr == s.data() + s.size() &&
      std::bit_cast<uint32_t>(back) == std::bit_cast<uint32_t>(f))
    return quoted(s);
  return quoted(hex(f));
}

// A tolerance value (a double; the loader takes JSON numbers only there): the shortest
// round-trip decimal, which the JSON parser's correctly rounded strtod reads back exactly.
std::string number(double d) {
  if (!std::isfinite(d)) return nonfinite(d);
  if (d == 0.0 && std::signbit(d)) return "-0.0";  // a JSON float token: keeps the sign
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, d);
  return std::string(buf, r.ptr);
}

std::string numbers(const float* v, size_t n) {
  std::string out = "[";
  for (size_t k = 0; k < n; ++k)
    add(out, k ? ", " : "", number(v[k]));
  out += ']';
  return out;
}

template <class E>
std::string name(E e) {
  return quoted(name_of(e));
}

std::string integer(long long i) {
  return std::to_string(i);
}

// Items packed a few to a line (at most 100 columns), each line indented by `indent`.
std::string packed(const std::vector<std::string>& items, const std::string& indent) {
  std::string out, line;
  for (size_t k = 0; k < items.size(); ++k) {
    std::string item;
    add(item, items[k], k + 1 < items.size() ? "," : "");
    if (!line.empty() && line.size() + 1 + item.size() > 100) {
      add(out, "\n", line);
      line.clear();
    }
    add(line, line.empty() ? indent : " ", item);
  }
  if (!line.empty()) add(out, "\n", line);
  return out;
}

// "triangles": the case's own list, packed a few triples to a line.
void write_triangles(std::string& out, const Case& c) {
  std::vector<std::string> items;
  for (const auto& tri : c.triangles) {
    std::string item;
    add(item, "[", integer(tri[0]), ", ", integer(tri[1]), ", ", integer(tri[2]), "]");
    items.push_back(std::move(item));
  }
  add(out, ",\n  \"triangles\": [", packed(items, "    "), items.empty() ? "" : "\n  ", "]");
}

// One draw of "draws" as an object; its indices packed a few to a line.
std::string draw_text(const Draw& d) {
  std::string out;
  add(out, "{\"mode\": ", name(d.mode));
  if (!d.indexed()) {
    add(out, ", \"first\": ", integer(d.first), ", \"count\": ", integer(d.count), "}");
    return out;
  }
  add(out, ", \"index_type\": ", name(d.index_type));
  if (d.restart != Restart::off) add(out, ", \"restart\": ", name(d.restart));
  if (d.restart == Restart::index) add(out, ", \"restart_index\": ", integer(d.restart_index));
  std::vector<std::string> items;
  for (uint32_t i : d.indices)
    items.push_back(integer(i));
  add(out, ", \"indices\": [", packed(items, "      "), "]}");
  return out;
}

}  // namespace

std::string to_case_file(const Case& c) {
  std::string out = "{\n";
  add(out, "  \"description\": ", quoted(c.description), ",\n");
  add(out, "  \"framebuffer\": {\"width\": ", integer(c.fb_width),
      ", \"height\": ", integer(c.fb_height), "},\n");
  add(out, "  \"viewport\": {\"x\": ", number(c.viewport.x), ", \"y\": ", number(c.viewport.y),
      ", \"width\": ", number(c.viewport.width), ", \"height\": ", number(c.viewport.height),
      "},\n");
  if (c.scissor)
    add(out, "  \"scissor\": {\"x\": ", integer(c.scissor->x), ", \"y\": ", integer(c.scissor->y),
        ", \"width\": ", integer(c.scissor->width), ", \"height\": ", integer(c.scissor->height),
        "},\n");

  const Case defaults;
  if (std::bit_cast<uint32_t>(c.depth_near) != std::bit_cast<uint32_t>(defaults.depth_near) ||
      std::bit_cast<uint32_t>(c.depth_far) != std::bit_cast<uint32_t>(defaults.depth_far))
    add(out, "  \"depth_range\": {\"near\": ", number(c.depth_near),
        ", \"far\": ", number(c.depth_far), "},\n");
  const bool clear_set =
      std::bit_cast<uint32_t>(c.depth_clear) != std::bit_cast<uint32_t>(defaults.depth_clear);
  const bool clip_control_set =
      c.clip_origin != defaults.clip_origin || c.clip_depth != defaults.clip_depth;
  if (c.cull != defaults.cull || c.front_face != defaults.front_face ||
      c.provoking != defaults.provoking || c.depth_func != defaults.depth_func || clear_set ||
      clip_control_set || c.depth_clamp)
    add(out, "  \"state\": {\"cull\": ", name(c.cull), ", \"front_face\": ", name(c.front_face),
        ", \"provoking_vertex\": ", name(c.provoking), ", \"depth_func\": ", name(c.depth_func),
        clear_set ? ", \"depth_clear\": " + number(c.depth_clear) : "",
        clip_control_set ? ", \"clip_origin\": " + name(c.clip_origin) +
                               ", \"clip_depth\": " + name(c.clip_depth)
                         : "",
        c.depth_clamp ? ", \"depth_clamp\": true" : "", "},\n");
  if (const auto& o = c.polygon_offset)
    add(out, "  \"polygon_offset\": {\"factor\": ", number(o->factor),
        ", \"units\": ", number(o->units), o->clamp ? ", \"clamp\": " + number(*o->clamp) : "",
        "},\n");
  if (c.work_arounds != defaults.work_arounds)
    add(out, "  \"work_arounds\": ", c.work_arounds ? "true" : "false", ",\n");

  if (!c.varyings.empty()) {
    out += "  \"varyings\": [\n";
    for (size_t i = 0; i < c.varyings.size(); ++i) {
      const Varying& v = c.varyings[i];
      if (v.is_builtin())
        add(out, "    {\"builtin\": ", name(v.builtin),
            v.layout.origin_upper_left ? ", \"origin_upper_left\": true" : "",
            v.layout.pixel_center_integer ? ", \"pixel_center_integer\": true" : "", "}",
            i + 1 < c.varyings.size() ? ",\n" : "\n");
      else
        add(out, "    {\"name\": ", quoted(v.name), ", \"size\": ", integer(v.size),
            ", \"interpolation\": ", name(v.interpolation), "}",
            i + 1 < c.varyings.size() ? ",\n" : "\n");
    }
    out += "  ],\n";
  }

  // One vertex per line: clip, then each varying's components in declaration order (a size-1
  // varying as a bare number). Values that do not match the varyings' sizes are written as far
  // as they go, for the loader to refuse.
  // Every written distance enabled is the default; otherwise the planes that are.
  const uint32_t all = c.distances.clip <= 0 ? 0u : (1u << std::min(c.distances.clip, 31)) - 1u;
  if (c.distances.enabled != all) {
    std::string planes;
    for (int k = 0; k < 32; ++k)
      if (c.distances.enabled >> k & 1u) add(planes, planes.empty() ? "" : ", ", integer(k));
    add(out, "  \"enabled_clip_distances\": [", planes, "],\n");
  }
  out += "  \"vertices\": [\n";
  for (size_t i = 0; i < c.vertices.size(); ++i) {
    const Vertex& v = c.vertices[i];
    add(out, "    {\"clip\": ", numbers(v.clip.data(), 4));
    size_t at = 0;
    for (const Varying& var : c.varyings) {
      const size_t want = var.size > 0 ? size_t(var.size) : 0;
      const size_t n = std::min(want, v.values.size() - std::min(at, v.values.size()));
      if (!var.is_builtin())  // no value per vertex
        add(out, ", ", quoted(var.name), ": ",
            var.size == 1 && n == 1 ? number(v.values[at]) : numbers(v.values.data() + at, n));
      at += n;
    }
    // Only as many as the case says (a hostile case may hold fewer: written as is).
    const size_t clip = std::min(size_t(std::max(c.distances.clip, 0)), v.distances.size());
    const size_t cull = std::min(size_t(std::max(c.distances.cull, 0)), v.distances.size() - clip);
    if (clip) add(out, ", \"clip_distance\": ", numbers(v.distances.data(), clip));
    if (cull) add(out, ", \"cull_distance\": ", numbers(v.distances.data() + clip, cull));
    add(out, "}", i + 1 < c.vertices.size() ? ",\n" : "\n");
  }
  out += "  ]";

  if (c.draws.empty()) {
    write_triangles(out, c);
  } else {
    out += ",\n  \"draws\": [";
    for (size_t d = 0; d < c.draws.size(); ++d)
      add(out, "\n    ", draw_text(c.draws[d]), d + 1 < c.draws.size() ? "," : "\n  ");
    out += "]";
  }

  const ToleranceOverride& t = c.tolerance;
  if (t.varying_ulps || t.depth_ulps || t.allow_boundary) {
    std::string fields;
    const auto field = [&](std::string_view key, const std::string& value) {
      add(fields, fields.empty() ? "" : ", ", "\"", key, "\": ", value);
    };
    if (t.varying_ulps) field("varying_ulps", number(*t.varying_ulps));
    if (t.depth_ulps) field("depth_ulps", number(*t.depth_ulps));
    if (t.allow_boundary) field("allow_boundary", *t.allow_boundary ? "true" : "false");
    add(out, ",\n  \"tolerance\": {", fields, "}");
  }
  out += "\n}\n";
  return out;
}

}  // namespace glrc::casefile
