// Shared by the casefile tests: case files written to a private temporary directory (never into
// the repository), and a check that a load fails with a one-line message naming the file, the
// field and what was expected.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "casefile/casefile.hpp"
#include "tests/support/temp_dir_test.hpp"

namespace glrc::casefile::test {

class CaseFileTest : public glrc::test::TempDirTest {
 protected:
  // Writes `text` to <tmp>/<name> (sub-directories created) and returns the path.
  std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto path = dir_ / name;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  Case load_text(const std::string& text, const std::string& name = "case.json") {
    return load(write(name, text));
  }

  // The message of the CaseError that loading `text` throws ("" if it loads).
  std::string error_of(const std::string& text, const std::string& name = "case.json") {
    const auto path = write(name, text);
    try {
      load(path);
    } catch (const CaseError& e) {
      return e.what();
    }
    return "";
  }
};

inline uint32_t bits(float f) {
  return std::bit_cast<uint32_t>(f);
}

// A case's polygon offset as bits: none, or {factor, units[, clamp]}, every float exactly.
inline std::vector<uint32_t> offset_bits(const std::optional<PolygonOffset>& o) {
  if (!o) return {};
  std::vector<uint32_t> out{bits(o->factor), bits(o->units)};
  if (o->clamp) out.push_back(bits(*o->clamp));
  return out;
}

// Every validation message: one line, "<file>: <field path>: expected ..., got ...".
#define EXPECT_CASE_ERROR(text, field_path)                                              \
  do {                                                                                   \
    const std::string msg_ = error_of(text);                                             \
    const std::string file_ = (dir_ / "case.json").string();                             \
    EXPECT_EQ(msg_.rfind(file_ + ": " + std::string(field_path) + ": expected ", 0), 0u) \
        << "message: " << msg_;                                                          \
    EXPECT_NE(msg_.find(", got "), std::string::npos) << msg_;                           \
    EXPECT_EQ(msg_.find('\n'), std::string::npos) << msg_;                               \
  } while (0)

}  // namespace glrc::casefile::test
