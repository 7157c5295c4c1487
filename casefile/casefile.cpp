// Case files: JSON in, validated Case out. The format is documented in cases/README.md.
//
// Every error is a CaseError with one line "<file>: <field path>: expected <what>, got <what>",
// so that a typo in a suite of dozens of files points at its place at once. Unknown keys are
// errors everywhere: a misspelt optional field would otherwise silently take its default.
#include "casefile/casefile.hpp"

#include <locale.h>
#include <sys/stat.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <locale>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "casefile/transform.hpp"

namespace glrc::casefile {
namespace {

namespace fs = std::filesystem;

// Memory for one case file's document, released all at once: a large case is millions of small
// containers, and allocating and freeing each one on the heap cost about a tenth of its loading.
class Arena {
 public:
  void* take(size_t n, size_t align) {
    size_t at = (used_ + align - 1) & ~(align - 1);
    if (blocks_.empty() || at + n > size_) {
      size_ = std::max<size_t>(n, size_t(1) << 22);
      blocks_.push_back(std::make_unique<std::byte[]>(size_));
      at = 0;
    }
    used_ = at + n;
    return blocks_.back().get() + at;
  }

 private:
  std::vector<std::unique_ptr<std::byte[]>> blocks_;
  size_t size_ = 0, used_ = 0;
};
thread_local Arena* open_arena = nullptr;

// nlohmann-json makes its allocators by default construction, so the arena is found through a
// thread-local: while one is open (ArenaScope), containers come from it and freeing them is a
// no-op; otherwise from the heap. Every document of this file lives and dies within one scope.
template <typename T>
struct ArenaAllocator {
  using value_type = T;
  ArenaAllocator() = default;
  template <typename U>
  ArenaAllocator(const ArenaAllocator<U>& /*other*/) {}
  T* allocate(size_t n) {
    return open_arena ? static_cast<T*>(open_arena->take(n * sizeof(T), alignof(T)))
                      : std::allocator<T>().allocate(n);
  }
  void deallocate(T* p, size_t n) {
    if (!open_arena) std::allocator<T>().deallocate(p, n);
  }
  template <typename U>
  bool operator==(const ArenaAllocator<U>& /*other*/) const {
    return true;
  }
};

class ArenaScope {
 public:
  ArenaScope() { open_arena = &arena_; }
  ~ArenaScope() { open_arena = nullptr; }
  ArenaScope(const ArenaScope&) = delete;
  ArenaScope& operator=(const ArenaScope&) = delete;

 private:
  Arena arena_;
};

using json = nlohmann::basic_json<std::map, std::vector, std::string, bool, std::int64_t,
                                  std::uint64_t, double, ArenaAllocator>;

constexpr int kMaxSize = 4096;      // framebuffer and viewport extent
constexpr size_t kMaxVaryings = 7;  // 8 color attachments, one holds gl_PrimitiveID

// The length of the UTF-8 sequence starting at s[i], or 0 when none starts there (RFC 3629:
// overlong forms, surrogates and code points beyond U+10FFFF are not UTF-8, as nlohmann-json
// also holds).
size_t utf8_length(std::string_view s, size_t i) {
  const auto at = [&](size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0; };
  const unsigned char c = at(i);
  const auto cont = [&](size_t k, unsigned char lo = 0x80, unsigned char hi = 0xBF) {
    return at(k) >= lo && at(k) <= hi;
  };
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return cont(i + 1) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    const unsigned char lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    return cont(i + 1, lo, hi) && cont(i + 2) ? 3 : 0;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    const unsigned char lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    return cont(i + 1, lo, hi) && cont(i + 2) && cont(i + 3) ? 4 : 0;
  }
  return 0;
}

// `s` fit for one line of a UTF-8 terminal: control characters as \n, \r, \t or \u00XX (a
// NUL would also end a C string, cutting the message), bytes that are not UTF-8 as \xXX; at most
// `max` bytes of output (never half a character or half an escape), then "...". The bound is on
// the output: 100 DEL bytes are 600 characters escaped.
std::string printable(std::string_view s, size_t max = std::string::npos) {
  std::string out;
  size_t i = 0;
  while (i < s.size()) {
    const size_t n = utf8_length(s, i);
    const auto c = static_cast<unsigned char>(s[i]);
    char buf[8];
    std::string_view piece;
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      piece = buf;
    } else if (c == '\n') {
      piece = "\\n";
    } else if (c == '\r') {
      piece = "\\r";
    } else if (c == '\t') {
      piece = "\\t";
    } else if (c < 0x20 || c == 0x7F) {
      std::snprintf(buf, sizeof buf, "\\u%04X", c);
      piece = buf;
    } else {
      piece = s.substr(i, n);
    }
    if (out.size() + piece.size() > max) break;
    out.append(piece);
    i += std::max<size_t>(n, 1);
  }
  if (i < s.size()) out += "...";
  return out;
}

std::string json_quoted(std::string_view s) {
  constexpr size_t kMax = 60;  // keep messages one readable line
  std::string escaped;
  for (const char ch : s.substr(0, 4 * kMax)) {  // enough for kMax characters shown
    if (ch == '"' || ch == '\\') escaped += '\\';
    escaped += ch;
  }
  std::string shown = printable(escaped, kMax);
  if (s.size() > 4 * kMax && !shown.ends_with("...")) shown += "...";
  return "\"" + shown + "\"";
}

// What a JSON value is, for the "got" part of a message.
std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case json::value_t::string:
      return json_quoted(v.get_ref<const std::string&>());
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return v.dump();
    case json::value_t::array:
      return v.empty() ? "an empty array" : "an array of " + std::to_string(v.size());
    case json::value_t::object:
      return "an object";
    default:
      return "a " + std::string(v.type_name());
  }
}

std::string join_list(std::initializer_list<std::string_view> items) {
  std::string out;
  for (std::string_view s : items) {
    if (!out.empty()) out += ", ";
    out += s;
  }
  return out;
}

std::string fmt_double(double d) {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os.precision(9);
  os << d;
  return os.str();
}

// Field paths: "vertices[3].clip".
std::string path_key(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}
// A field path as a message shows it: a key of 10,000 characters, or a value 100,000 arrays
// deep, would make the message any length. The start and the end (the field itself) stay.
std::string shown_path(const std::string& raw) {
  constexpr size_t kKeep = 100;
  // Cut as shown, escapes and all: a key of DEL bytes is six times as long on screen.
  const std::string path = printable(raw);
  if (path.size() <= 2 * kKeep) return path;
  size_t head = kKeep, tail = path.size() - kKeep;
  const auto inside_character = [&](size_t i) {
    return (static_cast<unsigned char>(path[i]) & 0xC0) == 0x80;
  };
  while (head > 0 && inside_character(head))
    --head;
  while (tail < path.size() && inside_character(tail))
    ++tail;
  // Nor half an escape (\u007F, \xFF, \n): a backslash close before a cut starts one.
  if (const size_t b = path.rfind('\\', head); b != std::string::npos && head - b < 6) head = b;
  if (const size_t b = path.rfind('\\', tail); b != std::string::npos && tail - b < 6 && b > head)
    tail = b;
  return path.substr(0, head) + "..." + path.substr(tail);
}
std::string path_index(const std::string& parent, size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// Strings holding numbers are parsed in the C locale, whatever the process's locale is.
float parse_float_c_locale(const char* s, char** end) {
  static const locale_t c_locale = newlocale(LC_ALL_MASK, "C", locale_t(0));
  return strtof_l(s, end, c_locale);
}

// Half-way between FLT_MAX and 2^128: a double of this magnitude or more rounds to infinity
// (ties to even), anything below it to a finite float. (static_cast of a double beyond FLT_MAX
// is undefined behaviour, hence the explicit clamp to FLT_MAX below it.)
constexpr double kFloatOverflow = 0x1.ffffffp127;

class Loader {
 public:
  explicit Loader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& expected,
                         const std::string& got) const {
    std::string msg = file_ + ": ";
    if (!path.empty()) msg += shown_path(path) + ": ";
    msg += "expected " + expected + ", got " + got;
    // One line, always, whatever a file name or a key holds.
    throw CaseError(printable(msg));
  }

  const json& require_object(const json& v, const std::string& path) const {
    if (!v.is_object()) fail(path, "an object", describe(v));
    return v;
  }

  // Unknown keys are typos until proven otherwise.
  void check_keys(const json& obj, const std::string& path,
                  std::initializer_list<std::string_view> allowed) const {
    for (const auto& [key, value] : obj.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        fail(path_key(path, key), "one of the keys " + join_list(allowed),
             "unknown key " + json_quoted(key));
    }
  }

  const json* opt(const json& obj, std::string_view key) const {
    auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }

  const json& required(const json& obj, const std::string& path, std::string_view key,
                       const std::string& what) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(path_key(path, key), what, "nothing (the field is required)");
    return *it;
  }

  // A number, rounded to float32 once: a JSON number goes through double (as the JSON parser
  // reads it) and is then rounded to the nearest float, ties to even; a string holding a C99
  // hex float or a decimal is read by strtof directly, for exact bits.
  float number(const json& v, const std::string& path) const {
    double d = 0;
    if (v.is_number()) {
      d = v.get<double>();
      if (!std::isfinite(d)) fail(path, "a finite number", describe(v));
    } else if (v.is_string()) {
      const std::string& s = v.get_ref<const std::string&>();
      const char* begin = s.c_str();
      char* end = nullptr;
      if (s.empty() || std::isspace(static_cast<unsigned char>(s[0])))
        fail(path, "a number or a string holding a C99 hex float or decimal", describe(v));
      errno = 0;
      const float f = parse_float_c_locale(begin, &end);
      if (end != begin + s.size())
        fail(path, "a number or a string holding a C99 hex float or decimal", describe(v));
      // ERANGE also flags an underflow to a subnormal or zero, which is the float it should be.
      if (!std::isfinite(f)) fail(path, "a finite float32 value", describe(v));
      return f;
    } else {
      fail(path, "a number", describe(v));
    }
    if (std::fabs(d) >= kFloatOverflow)
      fail(path, "a number within float32 range", describe(v) + " (overflows float32)");
    if (std::fabs(d) > double(std::numeric_limits<float>::max()))
      return std::signbit(d) ? -std::numeric_limits<float>::max()
                             : std::numeric_limits<float>::max();
    return static_cast<float>(d);
  }

  // A JSON number that number() takes as it is: the hot path of a large case, which must not
  // build a field path per number.
  static std::optional<float> plain_number(const json& v) {
    double d;
    if (v.is_number_float()) {
      d = v.get_ref<const json::number_float_t&>();
    } else if (v.is_number_integer() && !v.is_number_unsigned()) {
      d = double(v.get_ref<const json::number_integer_t&>());
    } else {
      return std::nullopt;
    }
    if (!(std::fabs(d) <= double(std::numeric_limits<float>::max()))) return std::nullopt;
    return static_cast<float>(d);
  }

  // A fixed count of numbers (counts.size() == 1), or one of several counts, appended to `out`.
  // `path` makes the field's path, only for a message.
  template <typename PathFn>
  void numbers_into(const json& v, const PathFn& path, std::initializer_list<size_t> counts,
                    std::vector<float>& out) const {
    const auto what = [&] {
      std::string w;
      for (size_t n : counts)
        w += (w.empty() ? "" : " or ") + std::to_string(n);
      return w + " numbers";
    };
    if (!v.is_array()) fail(path(), what(), describe(v));
    if (std::find(counts.begin(), counts.end(), v.size()) == counts.end())
      fail(path(), what(), std::to_string(v.size()));
    for (size_t i = 0; i < v.size(); ++i) {
      const auto f = plain_number(v[i]);
      out.push_back(f ? *f : number(v[i], path_index(path(), i)));
    }
  }
  std::vector<float> numbers(const json& v, const std::string& path,
                             std::initializer_list<size_t> counts) const {
    std::vector<float> out;
    numbers_into(
        v, [&] { return path; }, counts, out);
    return out;
  }

  std::array<double, 3> vec3(const json& v, const std::string& path) const {
    const auto f = numbers(v, path, {3});
    return {f[0], f[1], f[2]};
  }

  long long integer(const json& v, const std::string& path, const std::string& what) const {
    if (v.is_number_unsigned()) {
      const auto u = v.get<unsigned long long>();
      if (u > static_cast<unsigned long long>(std::numeric_limits<long long>::max()))
        fail(path, what, describe(v));
      return static_cast<long long>(u);
    }
    if (v.is_number_integer()) return v.get<long long>();
    fail(path, what, describe(v));
  }

  int int_in(const json& v, const std::string& path, long long lo, long long hi) const {
    const std::string what = "an integer in " + std::to_string(lo) + ".." + std::to_string(hi);
    const long long i = integer(v, path, what);
    if (i < lo || i > hi) fail(path, what, describe(v));
    return static_cast<int>(i);
  }

  // One of the enum's names (core/names.hpp's table), exactly.
  template <typename E>
  E choice(const json& v, const std::string& path) const {
    if (v.is_string())
      if (const auto value = from_name<E>(v.get_ref<const std::string&>())) return *value;
    std::string names;
    for (const std::string& name : names_of<E>())
      names += (names.empty() ? "" : ", ") + name;
    fail(path, "one of " + names, describe(v));
  }

  double tolerance_value(const json& v, const std::string& path) const {
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0)
      fail(path, "a finite number >= 0", describe(v));
    return v.get<double>();
  }

  Case load(const json& root);

 private:
  void load_geometry(const json& root, Case& c) const;
  void load_state(const json& state, Case& c) const;
  void load_varyings(const json& list, Case& c) const;
  std::optional<Transform> load_transform(const json& t) const;
  std::vector<TransformOp> load_ops(const json& list, const std::string& path) const;
  Projection load_projection(const json& p, const std::string& path) const;
  void load_vertices(const json& list, const std::optional<Transform>& transform, Case& c) const;
  void load_triangles(const json* list, Case& c) const;
  void check_noperspective(const Case& c) const;
  void load_tolerance(const json& t, Case& c) const;

  std::string file_;
};

void Loader::load_geometry(const json& root, Case& c) const {
  const json* fb = opt(root, "framebuffer");
  const json* vp = opt(root, "viewport");
  if (fb) {
    require_object(*fb, "framebuffer");
    check_keys(*fb, "framebuffer", {"width", "height"});
    c.fb_width = int_in(required(*fb, "framebuffer", "width", "an integer in 1..4096"),
                        "framebuffer.width", 1, kMaxSize);
    c.fb_height = int_in(required(*fb, "framebuffer", "height", "an integer in 1..4096"),
                         "framebuffer.height", 1, kMaxSize);
  }
  if (vp) {
    require_object(*vp, "viewport");
    check_keys(*vp, "viewport", {"x", "y", "width", "height"});
    Viewport v;
    v.x = int_in(required(*vp, "viewport", "x", "an integer in 0..4095"), "viewport.x", 0,
                 kMaxSize - 1);
    v.y = int_in(required(*vp, "viewport", "y", "an integer in 0..4095"), "viewport.y", 0,
                 kMaxSize - 1);
    v.width = int_in(required(*vp, "viewport", "width", "an integer in 1..4096"), "viewport.width",
                     1, kMaxSize);
    v.height = int_in(required(*vp, "viewport", "height", "an integer in 1..4096"),
                      "viewport.height", 1, kMaxSize);
    if (fb) {
      if (v.x + v.width > c.fb_width)
        fail("viewport", "x + width <= framebuffer.width (" + std::to_string(c.fb_width) + ")",
             std::to_string(v.x + v.width));
      if (v.y + v.height > c.fb_height)
        fail("viewport", "y + height <= framebuffer.height (" + std::to_string(c.fb_height) + ")",
             std::to_string(v.y + v.height));
    } else {
      // The framebuffer defaults to the viewport's extent, which must itself be a legal size.
      if (v.x + v.width > kMaxSize)
        fail("viewport", "x + width <= 4096 (the default framebuffer width)",
             std::to_string(v.x + v.width));
      if (v.y + v.height > kMaxSize)
        fail("viewport", "y + height <= 4096 (the default framebuffer height)",
             std::to_string(v.y + v.height));
      c.fb_width = v.x + v.width;
      c.fb_height = v.y + v.height;
    }
    c.viewport = v;
  } else {
    c.viewport = Viewport{0, 0, c.fb_width, c.fb_height};
  }

  if (const json* dr = opt(root, "depth_range")) {
    require_object(*dr, "depth_range");
    check_keys(*dr, "depth_range", {"near", "far"});
    auto read = [&](std::string_view key, float def) {
      const json* v = opt(*dr, key);
      if (!v) return def;
      const std::string path = path_key("depth_range", key);
      const float f = number(*v, path);
      if (!(f >= 0.0f && f <= 1.0f)) fail(path, "a number in [0, 1]", describe(*v));
      return f;
    };
    c.depth_near = read("near", 0.0f);
    c.depth_far = read("far", 1.0f);
  }
}

void Loader::load_state(const json& state, Case& c) const {
  require_object(state, "state");
  check_keys(state, "state", {"cull", "front_face", "provoking_vertex", "depth_func"});
  if (const json* v = opt(state, "cull")) c.cull = choice<CullFace>(*v, "state.cull");
  if (const json* v = opt(state, "front_face"))
    c.front_face = choice<FrontFace>(*v, "state.front_face");
  if (const json* v = opt(state, "provoking_vertex"))
    c.provoking = choice<ProvokingVertex>(*v, "state.provoking_vertex");
  if (const json* v = opt(state, "depth_func"))
    c.depth_func = choice<DepthFunc>(*v, "state.depth_func");
}

// GLSL keywords and reserved words (GLSL 4.60 section 3.6, plus a few type names): a varying
// named after one would not compile in the harness's shaders.
bool glsl_reserved(const std::string& name) {
  static const std::set<std::string, std::less<>> kWords = {
      "active",     "asm",       "atomic_uint", "attribute",   "bool",       "break",
      "buffer",     "bvec2",     "bvec3",       "bvec4",       "case",       "cast",
      "centroid",   "class",     "coherent",    "common",      "const",      "continue",
      "default",    "discard",   "dmat2",       "dmat2x2",     "dmat2x3",    "dmat2x4",
      "dmat3",      "dmat3x2",   "dmat3x3",     "dmat3x4",     "dmat4",      "dmat4x2",
      "dmat4x3",    "dmat4x4",   "do",          "double",      "dvec2",      "dvec3",
      "dvec4",      "else",      "enum",        "extern",      "external",   "false",
      "filter",     "fixed",     "flat",        "float",       "for",        "fvec2",
      "fvec3",      "fvec4",     "goto",        "half",        "highp",      "hvec2",
      "hvec3",      "hvec4",     "if",          "iimage1D",    "iimage2D",   "iimage3D",
      "image1D",    "image2D",   "image3D",     "in",          "inline",     "inout",
      "input",      "int",       "interface",   "invariant",   "isampler1D", "isampler2D",
      "isampler3D", "ivec2",     "ivec3",       "ivec4",       "layout",     "long",
      "lowp",       "main",      "mat2",        "mat2x2",      "mat2x3",     "mat2x4",
      "mat3",       "mat3x2",    "mat3x3",      "mat3x4",      "mat4",       "mat4x2",
      "mat4x3",     "mat4x4",    "mediump",     "namespace",   "noinline",   "noperspective",
      "out",        "output",    "partition",   "patch",       "precise",    "precision",
      "public",     "readonly",  "resource",    "restrict",    "return",     "sample",
      "sampler1D",  "sampler2D", "sampler3D",   "samplerCube", "short",      "sizeof",
      "smooth",     "static",    "struct",      "subroutine",  "superp",     "switch",
      "template",   "this",      "true",        "typedef",     "uimage1D",   "uimage2D",
      "uimage3D",   "uint",      "union",       "unsigned",    "usampler1D", "usampler2D",
      "usampler3D", "using",     "uvec2",       "uvec3",       "uvec4",      "varying",
      "vec2",       "vec3",      "vec4",        "void",        "volatile",   "while",
      "writeonly"};
  return kWords.count(name) > 0;
}

void Loader::load_varyings(const json& list, Case& c) const {
  if (!list.is_array()) fail("varyings", "an array of 0 to 7 varyings", describe(list));
  if (list.size() > kMaxVaryings)
    fail("varyings", "at most 7 varyings", std::to_string(list.size()));
  std::set<std::string> seen;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = path_index("varyings", i);
    const json& v = require_object(list[i], path);
    check_keys(v, path, {"name", "size", "interpolation"});
    Varying var;
    const json& name = required(v, path, "name", "a GLSL identifier");
    if (!name.is_string()) fail(path_key(path, "name"), "a GLSL identifier", describe(name));
    var.name = name.get<std::string>();
    const std::string& n = var.name;
    const bool identifier = !n.empty() &&
                            (std::isalpha(static_cast<unsigned char>(n[0])) || n[0] == '_') &&
                            std::all_of(n.begin(), n.end(), [](char ch) {
                              return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
                            });
    if (!identifier || n.size() > 64)
      fail(path_key(path, "name"), "a GLSL identifier ([A-Za-z_][A-Za-z0-9_]*, at most 64 chars)",
           describe(name));
    if (n.rfind("gl_", 0) == 0)
      fail(path_key(path, "name"), "a name not starting with \"gl_\" (reserved by GLSL)",
           describe(name));
    if (n.find("__") != std::string::npos)
      fail(path_key(path, "name"), "a name without \"__\" (reserved by GLSL)", describe(name));
    if (glsl_reserved(n))
      fail(path_key(path, "name"), "a name that is not a GLSL keyword", describe(name));
    // A vertex object holds "clip"/"position" beside the varyings' names.
    if (n == "clip" || n == "position")
      fail(path_key(path, "name"), "a name other than clip and position (vertex keys)",
           describe(name));
    if (!seen.insert(n).second)
      fail(path_key(path, "name"), "a name not used by another varying", describe(name));
    if (const json* size = opt(v, "size")) var.size = int_in(*size, path_key(path, "size"), 1, 4);
    if (const json* interp = opt(v, "interpolation"))
      var.interpolation = choice<Interpolation>(*interp, path_key(path, "interpolation"));
    c.varyings.push_back(var);
  }
}

std::vector<TransformOp> Loader::load_ops(const json& list, const std::string& path) const {
  if (!list.is_array()) fail(path, "an array of operations", describe(list));
  std::vector<TransformOp> ops;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = path_index(path, i);
    const json& op = require_object(list[i], p);
    if (op.size() != 1)
      fail(p, "an object with exactly one of the keys translate, rotate, scale, look_at",
           std::to_string(op.size()) + " keys");
    check_keys(op, p, {"translate", "rotate", "scale", "look_at"});
    const std::string& key = op.begin().key();
    const json& value = op.begin().value();
    const std::string vp = path_key(p, key);
    TransformOp o;
    if (key == "translate") {
      o.kind = TransformOp::Kind::translate;
      o.v = vec3(value, vp);
    } else if (key == "scale") {
      o.kind = TransformOp::Kind::scale;
      o.v = vec3(value, vp);
    } else if (key == "rotate") {
      o.kind = TransformOp::Kind::rotate;
      require_object(value, vp);
      check_keys(value, vp, {"degrees", "axis"});
      o.degrees = number(required(value, vp, "degrees", "a number"), path_key(vp, "degrees"));
      o.v = vec3(required(value, vp, "axis", "3 numbers"), path_key(vp, "axis"));
      if (o.v[0] == 0 && o.v[1] == 0 && o.v[2] == 0)
        fail(path_key(vp, "axis"), "a non-zero axis", "[0, 0, 0]");
    } else {
      o.kind = TransformOp::Kind::look_at;
      require_object(value, vp);
      check_keys(value, vp, {"eye", "center", "up"});
      o.v = vec3(required(value, vp, "eye", "3 numbers"), path_key(vp, "eye"));
      o.center = vec3(required(value, vp, "center", "3 numbers"), path_key(vp, "center"));
      o.up = vec3(required(value, vp, "up", "3 numbers"), path_key(vp, "up"));
      const double f[3] = {o.center[0] - o.v[0], o.center[1] - o.v[1], o.center[2] - o.v[2]};
      if (f[0] == 0 && f[1] == 0 && f[2] == 0)
        fail(path_key(vp, "center"), "a point other than eye", "the eye's position");
      const double s[3] = {f[1] * o.up[2] - f[2] * o.up[1], f[2] * o.up[0] - f[0] * o.up[2],
                           f[0] * o.up[1] - f[1] * o.up[0]};
      if (s[0] == 0 && s[1] == 0 && s[2] == 0)
        fail(path_key(vp, "up"), "a direction not parallel to center - eye", "a parallel one");
    }
    ops.push_back(o);
  }
  return ops;
}

Projection Loader::load_projection(const json& p, const std::string& path) const {
  require_object(p, path);
  if (p.size() != 1)
    fail(path, "an object with exactly one of the keys perspective, frustum, ortho",
         std::to_string(p.size()) + " keys");
  check_keys(p, path, {"perspective", "frustum", "ortho"});
  const std::string& key = p.begin().key();
  const json& value = p.begin().value();
  const std::string vp = path_key(path, key);
  require_object(value, vp);
  Projection out;
  auto get = [&](std::string_view k) -> double {
    return number(required(value, vp, k, "a number"), path_key(vp, k));
  };
  if (key == "perspective") {
    check_keys(value, vp, {"fovy_degrees", "aspect", "near", "far"});
    out.kind = Projection::Kind::perspective;
    out.p = {get("fovy_degrees"), get("aspect"), get("near"), get("far"), 0, 0};
    if (!(out.p[0] > 0 && out.p[0] < 180))
      fail(path_key(vp, "fovy_degrees"), "a number in (0, 180)", fmt_double(out.p[0]));
    if (!(out.p[1] > 0)) fail(path_key(vp, "aspect"), "a number > 0", fmt_double(out.p[1]));
  } else {
    check_keys(value, vp, {"left", "right", "bottom", "top", "near", "far"});
    out.kind = key == "frustum" ? Projection::Kind::frustum : Projection::Kind::ortho;
    out.p = {get("left"), get("right"), get("bottom"), get("top"), get("near"), get("far")};
    if (out.p[0] == out.p[1])
      fail(path_key(vp, "right"), "a value other than left", fmt_double(out.p[1]));
    if (out.p[2] == out.p[3])
      fail(path_key(vp, "top"), "a value other than bottom", fmt_double(out.p[3]));
  }
  const double n = key == "perspective" ? out.p[2] : out.p[4];
  const double f = key == "perspective" ? out.p[3] : out.p[5];
  if (key != "ortho") {
    // A perspective divide by the eye distance needs both planes in front of the eye.
    if (!(n > 0)) fail(path_key(vp, "near"), "a number > 0", fmt_double(n));
    if (!(f > 0)) fail(path_key(vp, "far"), "a number > 0", fmt_double(f));
  }
  if (n == f) fail(path_key(vp, "far"), "a value other than near", fmt_double(f));
  return out;
}

std::optional<Transform> Loader::load_transform(const json& t) const {
  require_object(t, "transform");
  check_keys(t, "transform", {"model", "view", "projection"});
  Transform out;
  if (const json* m = opt(t, "model")) out.model = load_ops(*m, "transform.model");
  if (const json* v = opt(t, "view")) out.view = load_ops(*v, "transform.view");
  if (const json* p = opt(t, "projection"))
    out.projection = load_projection(*p, "transform.projection");
  return out;
}

void Loader::load_vertices(const json& list, const std::optional<Transform>& transform,
                           Case& c) const {
  if (!list.is_array() || list.empty())
    fail("vertices", "a non-empty array of vertex objects", describe(list));
  // Positions are transformed together once all are read, so that one matrix set serves all.
  std::vector<size_t> from_position;
  std::vector<std::array<double, 4>> positions;
  c.vertices.reserve(list.size());
  const size_t components = size_t(c.component_count());
  for (size_t i = 0; i < list.size(); ++i) {
    // Field paths are made only for a message: a large case has millions of fields.
    const auto path = [&] { return path_index("vertices", i); };
    const json& v = list[i];
    if (!v.is_object()) require_object(v, path());
    // Allowed keys: clip, position, and the varyings' names.
    for (const auto& [key, value] : v.items()) {
      if (key == "clip" || key == "position") continue;
      // A named reference: Clang before 16 cannot capture a structured binding.
      const std::string& name = key;
      const bool varying = std::any_of(c.varyings.begin(), c.varyings.end(),
                                       [&](const Varying& var) { return var.name == name; });
      if (!varying) {
        std::string keys = "clip, position";
        for (const auto& var : c.varyings)
          keys += ", " + var.name;
        fail(path_key(path(), key), "one of the keys " + keys + " (varyings must be declared)",
             "unknown key " + json_quoted(key));
      }
    }
    Vertex vertex;
    const json* clip = opt(v, "clip");
    const json* pos = opt(v, "position");
    if (clip && pos) fail(path(), "exactly one of clip, position", "both");
    if (!clip && !pos) fail(path(), "exactly one of clip, position", "neither");
    std::vector<float> f;
    if (clip) {
      numbers_into(
          *clip, [&] { return path_key(path(), "clip"); }, {4}, f);
      vertex.clip = {f[0], f[1], f[2], f[3]};
    } else {
      if (!transform)
        fail(path_key(path(), "position"),
             "clip coordinates, or a \"transform\" in the case to use position", "no transform");
      numbers_into(
          *pos, [&] { return path_key(path(), "position"); }, {3, 4}, f);
      positions.push_back({f[0], f[1], f[2], f.size() == 4 ? double(f[3]) : 1.0});
      from_position.push_back(i);
    }
    vertex.values.reserve(components);
    for (const auto& var : c.varyings) {
      const auto vp = [&] { return path_key(path(), var.name); };
      const auto what = [&] {
        return var.size == 1 ? "a number (varying " + var.name + ")"
                             : std::to_string(var.size) + " numbers (varying " + var.name + ")";
      };
      const json* value = opt(v, var.name);
      if (!value) fail(vp(), what(), "nothing (every vertex needs every varying)");
      if (var.size == 1 && !value->is_array()) {
        const auto x = plain_number(*value);
        vertex.values.push_back(x ? *x : number(*value, vp()));
      } else {
        if (!value->is_array()) fail(vp(), what(), describe(*value));
        if (value->size() != size_t(var.size)) fail(vp(), what(), std::to_string(value->size()));
        for (size_t k = 0; k < value->size(); ++k) {
          const auto x = plain_number((*value)[k]);
          vertex.values.push_back(x ? *x : number((*value)[k], path_index(vp(), k)));
        }
      }
    }
    c.vertices.push_back(std::move(vertex));
  }
  if (!positions.empty()) {
    const auto clips = to_clip(*transform, positions);
    for (size_t k = 0; k < clips.size(); ++k) {
      const std::string path = path_key(path_index("vertices", from_position[k]), "position");
      std::array<float, 4>& out = c.vertices[from_position[k]].clip;
      for (int j = 0; j < 4; ++j) {
        const double d = clips[k][j];
        if (!(std::fabs(d) < kFloatOverflow))
          fail(path, "clip coordinates finite in float32 after the transform",
               "clip[" + std::to_string(j) + "] = " + fmt_double(d));
        // The one rounding from the double transform to the float32 gl_Position.
        out[j] =
            std::fabs(d) > double(std::numeric_limits<float>::max())
                ? (d < 0 ? -std::numeric_limits<float>::max() : std::numeric_limits<float>::max())
                : static_cast<float>(d);
      }
    }
  }
}

void Loader::load_triangles(const json* list, Case& c) const {
  const size_t n = c.vertices.size();
  if (!list) {
    if (n % 3 != 0)
      fail("vertices", "a multiple of 3 vertices (consecutive triples, as \"triangles\" is absent)",
           std::to_string(n));
    for (uint32_t i = 0; i + 2 < n; i += 3)
      c.triangles.push_back({i, i + 1, i + 2});
    return;
  }
  if (!list->is_array() || list->empty())
    fail("triangles", "a non-empty array of [i, j, k] index triples", describe(*list));
  const std::string what = "an index in 0.." + std::to_string(n - 1);
  for (size_t t = 0; t < list->size(); ++t) {
    const std::string path = path_index("triangles", t);
    const json& tri = (*list)[t];
    if (!tri.is_array()) fail(path, "3 vertex indices", describe(tri));
    if (tri.size() != 3) fail(path, "3 vertex indices", std::to_string(tri.size()));
    std::array<uint32_t, 3> idx{};
    for (size_t k = 0; k < 3; ++k) {
      const long long i = integer(tri[k], path_index(path, k), what);
      if (i < 0 || static_cast<unsigned long long>(i) >= n)
        fail(path_index(path, k), what, describe(tri[k]));
      idx[k] = static_cast<uint32_t>(i);
    }
    c.triangles.push_back(idx);
  }
}

// GL specifies noperspective interpolation in window coordinates, which a triangle reaching
// behind the eye (w_c <= 0 at a vertex) does not have: the projected triangle is not the visible
// region, and the spec leaves the result undefined. Such a case could not have a reference.
void Loader::check_noperspective(const Case& c) const {
  auto np = std::find_if(c.varyings.begin(), c.varyings.end(), [](const Varying& v) {
    return v.interpolation == Interpolation::noperspective;
  });
  if (np == c.varyings.end()) return;
  for (size_t t = 0; t < c.triangles.size(); ++t) {
    for (uint32_t i : c.triangles[t]) {
      const float w = c.vertices[i].clip[3];
      if (w <= 0.0f)
        fail(path_index("triangles", t),
             "w_c > 0 at every vertex, because varying " + json_quoted(np->name) +
                 " is noperspective and GL leaves screen-linear interpolation undefined for "
                 "triangles reaching behind the eye",
             "w_c = " + fmt_double(w) + " at vertex " + std::to_string(i));
    }
  }
}

void Loader::load_tolerance(const json& t, Case& c) const {
  require_object(t, "tolerance");
  check_keys(t, "tolerance", {"varying_ulps", "depth_ulps", "allow_boundary"});
  if (const json* v = opt(t, "varying_ulps"))
    c.tolerance.varying_ulps = tolerance_value(*v, "tolerance.varying_ulps");
  if (const json* v = opt(t, "depth_ulps"))
    c.tolerance.depth_ulps = tolerance_value(*v, "tolerance.depth_ulps");
  if (const json* v = opt(t, "allow_boundary")) {
    if (!v->is_boolean()) fail("tolerance.allow_boundary", "true or false", describe(*v));
    c.tolerance.allow_boundary = v->get<bool>();
  }
}

Case Loader::load(const json& root) {
  Case c;
  c.source_path = file_;
  if (!root.is_object()) fail("", "a JSON object at the top level", describe(root));
  check_keys(root, "",
             {"description", "framebuffer", "viewport", "depth_range", "state", "varyings",
              "transform", "vertices", "triangles", "tolerance"});

  const json& desc = required(root, "", "description", "a one-line string");
  // Printed on terminals by list, diff and run: a control character (a line break, an escape
  // sequence, a NUL) would break the line or drive the terminal.
  if (!desc.is_string() || desc.get_ref<const std::string&>().empty() ||
      std::any_of(desc.get_ref<const std::string&>().begin(),
                  desc.get_ref<const std::string&>().end(),
                  [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; }))
    fail("description", "a non-empty one-line string without control characters", describe(desc));
  c.description = desc.get<std::string>();

  load_geometry(root, c);
  if (const json* s = opt(root, "state")) load_state(*s, c);
  if (const json* v = opt(root, "varyings")) load_varyings(*v, c);
  std::optional<Transform> transform;
  if (const json* t = opt(root, "transform")) transform = load_transform(*t);
  load_vertices(required(root, "", "vertices", "an array of vertices"), transform, c);
  load_triangles(opt(root, "triangles"), c);
  check_noperspective(c);
  if (const json* t = opt(root, "tolerance")) load_tolerance(*t, c);
  return c;
}

// Builds the document as nlohmann-json's own SAX DOM parser does, and stops at a key written
// twice in one object (nlohmann-json would keep the last one without a word): an object is a
// std::map, so the check is one lookup. The parser callback used before rescans the parent
// array at the end of every object, which made loading quadratic in the number of vertices.
// The open containers give the path of the value being read, for errors found while parsing.
class DomBuilder final : public json::json_sax_t {
 public:
  explicit DomBuilder(json& root) : root_(root) {}

  bool null() override { return add(nullptr); }
  bool boolean(bool b) override { return add(b); }
  bool number_integer(json::number_integer_t v) override { return add(v); }
  bool number_unsigned(json::number_unsigned_t v) override { return add(v); }
  bool number_float(json::number_float_t v, const std::string& /*text*/) override { return add(v); }
  bool string(std::string& s) override { return add(std::move(s)); }
  bool binary(json::binary_t& b) override { return add(std::move(b)); }
  bool start_object(size_t /*size*/) override { return open(json::object()); }
  bool start_array(size_t /*size*/) override {
    // Most arrays of a case hold 3 or 4 numbers: one allocation instead of three.
    json array = json::array();
    array.get_ref<json::array_t&>().reserve(4);
    return open(std::move(array));
  }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(std::string& k) override {
    Level& top = stack_.back();
    auto [it, inserted] = top.node->get_ref<json::object_t&>().emplace(std::move(k), nullptr);
    if (!inserted) {
      top.slot = nullptr;  // the path of the object, not of its previous key
      duplicate_ = path_key(path(), it->first);
      return false;
    }
    top.key = &it->first;
    top.slot = &it->second;
    return true;
  }
  bool parse_error(size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& ex) override {
    error_ = Error{position, last_token, ex.id, ex.what(), path()};
    return false;
  }

  struct Error {
    size_t position;         // bytes read
    std::string last_token;  // as the message quotes it
    int id;                  // nlohmann-json's exception id: 101 syntax, 406 number overflow
    std::string message;
    std::string path;  // of the value being read
  };
  const std::optional<Error>& error() const { return error_; }
  const std::optional<std::string>& duplicate() const { return duplicate_; }

 private:
  struct Level {
    json* node;
    const std::string* key = nullptr;  // objects: the key being read (a node of the map)
    json* slot = nullptr;              // objects: where its value goes
  };

  json* place(json&& v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Level& top = stack_.back();
    if (top.node->is_array()) {
      // Only the last element is ever open, so a reallocation moves no pointer held here.
      top.node->push_back(std::move(v));
      return &top.node->back();
    }
    *top.slot = std::move(v);
    return top.slot;
  }
  bool add(json&& v) {
    place(std::move(v));
    return true;
  }
  bool open(json&& container) {
    stack_.push_back({place(std::move(container))});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }
  // An open array's element being read is its last one if that is itself open, else the next.
  std::string path() const {
    std::string p;
    for (size_t k = 0; k < stack_.size(); ++k) {
      const Level& l = stack_[k];
      // Appended in place: a path 100,000 levels deep must not be copied at every level.
      if (l.node->is_array()) {
        const size_t n = l.node->size();
        // Three appends, not "[" + ...: GCC 12 at -O3 reports a false -Wrestrict in operator+.
        p += '[';
        p += std::to_string(k + 1 < stack_.size() ? n - 1 : n);
        p += ']';
      } else if (l.slot) {
        if (!p.empty()) p += '.';
        p += *l.key;
      } else {
        break;
      }
    }
    return p;
  }

  json& root_;
  std::vector<Level> stack_;
  std::optional<Error> error_;
  std::optional<std::string> duplicate_;
};

// What a field holds, for a number that overflows a double, which the parser meets before the
// loader sees the field.
std::string expected_number_at(const std::string& path) {
  const auto ends_with = [&](std::string_view tail) {
    return path.size() >= tail.size() &&
           path.compare(path.size() - tail.size(), tail.size(), tail) == 0;
  };
  if (path == "framebuffer.width" || path == "framebuffer.height" || path == "viewport.width" ||
      path == "viewport.height")
    return "an integer in 1.." + std::to_string(kMaxSize);
  if (path == "viewport.x" || path == "viewport.y")
    return "an integer in 0.." + std::to_string(kMaxSize - 1);
  if (path.rfind("varyings[", 0) == 0 && ends_with(".size")) return "an integer in 1..4";
  if (path.rfind("triangles[", 0) == 0) return "a vertex index (an integer)";
  if (path.rfind("tolerance.", 0) == 0) return "a finite number >= 0";
  return "a number within float32 range";
}

std::string file_kind(const fs::file_status& st);

// Where byte `offset` of `text` is, as JSON parsers say it: "line L, column C" (1-based).
std::string line_and_column(std::string_view text, size_t offset) {
  const std::string_view before = text.substr(0, offset);
  const size_t line = size_t(std::count(before.begin(), before.end(), '\n')) + 1;
  const size_t start = before.rfind('\n');
  const size_t column = offset - (start == std::string_view::npos ? 0 : start + 1) + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// Bytes no JSON text may hold, found before parsing so that the message says what and where:
// nlohmann-json takes a NUL for the end of the input (silently ignoring what follows), and its
// message for a byte that is not UTF-8 gives no offset.
void check_bytes(const Loader& loader, std::string_view text) {
  for (size_t i = 0; i < text.size();) {
    // Eight ASCII bytes without a NUL at a time: a 50 MB case is mostly that.
    if (i + 8 <= text.size()) {
      uint64_t w;
      std::memcpy(&w, text.data() + i, 8);
      constexpr uint64_t kHigh = 0x8080808080808080ull, kLow = 0x0101010101010101ull;
      if ((w & kHigh) == 0 && ((w - kLow) & ~w & kHigh) == 0) {
        i += 8;
        continue;
      }
    }
    if (text[i] == '\0')
      loader.fail(line_and_column(text, i), "a JSON text without NUL bytes",
                  "a NUL byte at offset " + std::to_string(i));
    if (static_cast<unsigned char>(text[i]) < 0x80) {
      ++i;
      continue;
    }
    const size_t n = utf8_length(text, i);
    if (n == 0) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[i]));
      loader.fail(
          line_and_column(text, i), "UTF-8 text",
          std::string("the byte ") + byte + ", which is not UTF-8, at offset " + std::to_string(i));
    }
    i += n;
  }
}

// nlohmann-json's message, without its "[json.exception...] parse error at line L, column C: "
// prefix (the line and column become the field) and with the text it quotes cut short: a
// malformed 50 MB line would otherwise be quoted whole.
std::pair<std::string, std::string> parse_message(const DomBuilder::Error& e) {
  std::string msg = e.message;
  std::string where;
  const size_t at = msg.find("at line ");
  if (at != std::string::npos) {
    const size_t colon = msg.find(": ", at);
    where = msg.substr(at + 3, colon == std::string::npos ? std::string::npos : colon - at - 3);
    msg = colon == std::string::npos ? "" : msg.substr(colon + 2);
  } else if (const size_t close = msg.find("] "); close != std::string::npos) {
    msg = msg.substr(close + 2);
  }
  constexpr size_t kQuoted = 80;
  if (e.last_token.size() > kQuoted) {
    const std::string quoted = "'" + e.last_token + "'";
    if (const size_t q = msg.find(quoted); q != std::string::npos)
      msg.replace(q, quoted.size(), "'" + printable(e.last_token, kQuoted) + "'");
  }
  return {where, msg};
}

}  // namespace

Case load(const fs::path& file) {
  const std::string name = file.string();
  Loader loader(name);
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (ec || !fs::exists(st)) loader.fail("", "a readable case file", "none at this path");
  // Opening a FIFO would wait for a writer, forever.
  if (!fs::is_regular_file(st)) loader.fail("", "a regular case file", file_kind(st));
  std::ifstream in(file, std::ios::binary);
  if (!in) loader.fail("", "a readable case file", "one that cannot be opened");
  std::string text;
  text.resize(size_t(fs::file_size(file, ec)));
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  if (in.bad() || ec) loader.fail("", "a readable case file", "a read error");
  // A file that grew since its size was taken: read the rest.
  if (in) text.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  check_bytes(loader, text);

  const ArenaScope arena;  // before the document: outlives it
  json root;
  DomBuilder builder(root);
  json::sax_parse(text, &builder, json::input_format_t::json, /*strict=*/true);
  if (const auto& e = builder.error()) {
    if (e->id == 406) {
      // "number overflow parsing '1e400'": a number beyond double range, in the field the
      // builder's path names.
      loader.fail(e->path, expected_number_at(e->path),
                  printable(e->last_token, 80) + " (beyond the range of a double)");
    }
    const auto [where, msg] = parse_message(*e);
    loader.fail(where, "valid JSON", msg);
  }
  if (builder.duplicate())
    loader.fail(*builder.duplicate(), "each key once in its object", "it twice");
  text = std::string();  // the document holds it all now
  Case c = loader.load(root);
  c.name = file.stem().string();
  return c;
}

namespace {

// What a path that is not a regular file is, for messages.
std::string file_kind(const fs::file_status& st) {
  switch (st.type()) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::not_found:
      return "a broken symbolic link";
    default:
      return "something other than a regular file";
  }
}

// Case names become JSON strings in results.json and reports, which must be UTF-8: a path that
// is not is refused here, before any work, rather than by the JSON library mid-run.
void require_utf8(const fs::path& p) {
  const std::string& s = p.native();
  for (size_t i = 0; i < s.size();) {
    const size_t n = utf8_length(s, i);
    if (n == 0) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(s[i]));
      throw CaseError(printable(s) + ": expected a path in UTF-8 (case names go into JSON), got " +
                      "the byte " + byte + " at offset " + std::to_string(i));
    }
    i += n;
  }
}

}  // namespace

std::vector<fs::path> collect(const std::vector<std::string>& files_or_dirs,
                              const std::function<void(const std::string&)>& note) {
  const auto say = [&](const std::string& line) {
    if (note) {
      note(line);
    } else {
      std::fprintf(stderr, "%s\n", line.c_str());
    }
  };
  std::vector<fs::path> out;
  // Folders searched, by device and inode: a symbolic link back to a folder already searched
  // (a loop, or two links to one folder) is not searched again, which would otherwise never end
  // or grow exponentially.
  std::set<std::pair<dev_t, ino_t>> searched;
  for (const std::string& arg : files_or_dirs) {
    const fs::path p(arg);
    require_utf8(p);
    std::error_code ec;
    const fs::file_status st = fs::status(p, ec);
    if (ec || !fs::exists(st))
      throw CaseError(printable(arg) +
                      ": expected a case file or a directory of them, got no such path");
    if (fs::is_regular_file(st)) {
      out.push_back(p.lexically_normal());  // a file named explicitly is taken as it is
      continue;
    }
    if (!fs::is_directory(st))
      // Reading a FIFO would wait for a writer; a device is no case either. Named outright, it is
      // a mistake to say so (found in a folder, it is only passed over).
      throw CaseError(printable(arg) + ": expected a case file or a directory of them, got " +
                      file_kind(st) + " (not read)");
    std::vector<fs::path> pending = {p};
    while (!pending.empty()) {
      const fs::path dir = pending.back();
      pending.pop_back();
      struct stat sb {};
      if (stat(dir.c_str(), &sb) != 0 || !searched.insert({sb.st_dev, sb.st_ino}).second) {
        if (dir != p)
          say("glrefcheck: ignored " + printable(dir.string()) +
              ": a symbolic link to a folder searched already");
        continue;
      }
      try {
        for (const auto& entry : fs::directory_iterator(dir)) {
          const fs::path& e = entry.path();
          require_utf8(e);
          std::error_code sec;
          const fs::file_status est = entry.status(sec);  // follows symbolic links
          if (fs::is_directory(est)) {
            pending.push_back(e);
          } else if (e.extension() == ".json") {
            if (fs::is_regular_file(est)) {
              out.push_back(e.lexically_normal());
            } else if (sec && sec != std::errc::no_such_file_or_directory) {
              // A link to itself, or through too many links: following it fails (ELOOP).
              say("glrefcheck: ignored " + printable(e.string()) +
                  ": a symbolic link that cannot be followed (" + sec.message() + ")");
            } else {
              say("glrefcheck: ignored " + printable(e.string()) + ": " + file_kind(est) +
                  ", not a regular file");
            }
          }
        }
      } catch (const fs::filesystem_error& e) {
        throw CaseError(printable(dir.string()) + ": expected a readable directory, got " +
                        e.code().message());
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  // A case's name is its file's stem, and names key results and reports.
  std::map<std::string, fs::path> names;
  for (const fs::path& p : out) {
    // A tab or line break in a name would split the lines that list, digest and diff print.
    for (const char ch : p.stem().string())
      if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f)
        throw CaseError(printable(p.string()) +
                        ": name: expected a case name without control characters, got " +
                        json_quoted(p.stem().string()) + ": rename the file");
    auto [it, inserted] = names.emplace(p.stem().string(), p);
    if (!inserted)
      throw CaseError(printable(p.string()) + ": name: expected a case name used once, got " +
                      json_quoted(p.stem().string()) + ", also the name of " +
                      printable(it->second.string()));
  }
  return out;
}

}  // namespace glrc::casefile
