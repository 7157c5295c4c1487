// Draw: one GL draw command of a case (glDrawArrays or glDrawElements), with its primitive type
// and primitive restart. What the harness issues to GL; core/primitive_assembly.hpp turns a
// case's draws into the triangles the reference rasterizes.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "core/names.hpp"

namespace glrc {

// The triangle primitive types (OpenGL 4.6 section 10.1.8, 10.1.9, 10.1.10).
enum class PrimitiveMode { triangles, triangle_strip, triangle_fan };
template <>
struct Names<PrimitiveMode> {
  static constexpr std::array<std::pair<PrimitiveMode, std::string_view>, 3> table{{
      {PrimitiveMode::triangles, "triangles"},
      {PrimitiveMode::triangle_strip, "triangle_strip"},
      {PrimitiveMode::triangle_fan, "triangle_fan"},
  }};
};

// glDrawArrays (none) or glDrawElements with GL_UNSIGNED_BYTE, _SHORT or _INT indices.
enum class IndexType { none, unsigned_byte, unsigned_short, unsigned_int };
template <>
struct Names<IndexType> {
  static constexpr std::array<std::pair<IndexType, std::string_view>, 4> table{{
      {IndexType::none, "none"},
      {IndexType::unsigned_byte, "unsigned_byte"},
      {IndexType::unsigned_short, "unsigned_short"},
      {IndexType::unsigned_int, "unsigned_int"},
  }};
};
// Bytes an index of the type takes (0 for none).
constexpr int index_bytes(IndexType t) {
  return t == IndexType::unsigned_byte    ? 1
         : t == IndexType::unsigned_short ? 2
         : t == IndexType::unsigned_int   ? 4
                                          : 0;
}
// The largest index the type holds: 2^(8·bytes) − 1.
constexpr uint32_t max_index(IndexType t) {
  return t == IndexType::unsigned_byte    ? 0xffu
         : t == IndexType::unsigned_short ? 0xffffu
                                          : 0xffffffffu;
}

// Primitive restart (OpenGL 4.6 section 10.3.6): off; GL_PRIMITIVE_RESTART_FIXED_INDEX (the
// restart index is the type's largest, max_index); or GL_PRIMITIVE_RESTART with
// glPrimitiveRestartIndex(Draw::restart_index).
enum class Restart { off, fixed_index, index };
template <>
struct Names<Restart> {
  static constexpr std::array<std::pair<Restart, std::string_view>, 3> table{{
      {Restart::off, "off"},
      {Restart::fixed_index, "fixed_index"},
      {Restart::index, "index"},
  }};
};

struct Draw {
  PrimitiveMode mode = PrimitiveMode::triangles;
  IndexType index_type = IndexType::none;
  // glDrawArrays(mode, first, count): vertices first .. first + count − 1 (index_type none).
  uint32_t first = 0, count = 0;
  // glDrawElements(mode, indices.size(), index_type, ...): each fits index_type; an index equal
  // to restart_value() (with restart on) restarts the primitive instead of naming a vertex.
  std::vector<uint32_t> indices;
  Restart restart = Restart::off;
  uint32_t restart_index = 0;  // Restart::index: glPrimitiveRestartIndex's value

  bool indexed() const { return index_type != IndexType::none; }
  // The index value that restarts the primitive, when restart is on.
  uint32_t restart_value() const {
    return restart == Restart::fixed_index ? max_index(index_type) : restart_index;
  }
  bool restarts_at(uint32_t index) const {
    return restart != Restart::off && index == restart_value();
  }
  // The vertex indices the draw transfers, in order (array draws: first, first + 1, ...),
  // restart indices kept where they stand.
  std::vector<uint32_t> elements() const;
  friend bool operator==(const Draw&, const Draw&) = default;
};

}  // namespace glrc
