// Reading cases/*.json into Case values, with validation: every error names the file, the
// field and what was expected.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/case.hpp"

namespace glrc::casefile {

// what() is one line: "<file>: <field>: expected <what>, got <what>".
struct CaseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Case load(const std::filesystem::path& file);

// Case files named by the arguments: files as given, directories searched recursively for
// *.json; sorted by path, duplicates removed. Throws CaseError for a path that does not exist.
std::vector<std::filesystem::path> collect(const std::vector<std::string>& files_or_dirs);

}  // namespace glrc::casefile
