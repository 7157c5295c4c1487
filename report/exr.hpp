// Single-channel float EXRs of frame data, for inspecting exact values in an image viewer.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace glrc::report {

// Writes width x height floats (Frame order: row 0 at the bottom) as a one-channel ("Y") float
// EXR, upright: frame row y becomes image row height - 1 - y. `description` goes into the
// file's ImageDescription. Throws std::runtime_error naming the file on failure.
void write_exr(const std::filesystem::path& file, int width, int height,
               const std::vector<float>& values, const std::string& description);

}  // namespace glrc::report
