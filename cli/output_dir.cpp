#include "cli/output_dir.hpp"

#include <unistd.h>

#include <fmt/core.h>
#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli/session.hpp"
#include "core/text.hpp"
#include "report/report.hpp"

namespace glrc::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarkerText =
    "glrefcheck output folder: glrefcheck replaces its own files here (results.json, results.csv, "
    "failures.csv, junit.xml, report.html, journal.jsonl, cases/, logs/) and nothing else.\n";

// A results.json (of `run`) or an identify.json (of `identify`) as glrefcheck writes them. Such
// a folder without the marker is still refused (its results.json proves nothing: anyone can
// write one, and cases/ beside it would be deleted), but the message says what to do.
bool looks_like_glrefcheck_output(const fs::path& dir) {
  const auto parse = [&](const char* name) -> nlohmann::json {
    std::error_code ec;
    if (!fs::is_regular_file(dir / name, ec)) return nullptr;
    try {
      std::ifstream in(dir / name);
      return nlohmann::json::parse(in);
    } catch (const std::exception&) {
      return nullptr;
    }
  };
  const auto results = parse("results.json");
  if (results.is_object() && results.contains("run") && results["run"].is_object() &&
      results["run"].contains("gl_renderer") && results.contains("cases") &&
      results["cases"].is_array())
    return true;
  const auto identify = parse("identify.json");
  return identify.is_object() && identify.contains("depth24") && identify.contains("tie_break") &&
         identify.contains("provoking_default");
}

}  // namespace

const std::vector<std::string>& run_output_names() {
  static const std::vector<std::string> names = {"results.json", "results.csv", "failures.csv",
                                                 "junit.xml",    "report.html", kJournalFile,
                                                 "cases",        "logs",        kInputsFolder};
  return names;
}

bool is_marked(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / kMarkerFile, ec)) return false;
  std::ifstream in(dir / kMarkerFile);
  std::string first;
  std::getline(in, first);
  return first.starts_with("glrefcheck output folder");
}

fs::path output_folder(const std::string& out, const std::string& option) {
  if (out.empty()) throw InputError(option + ": expected a folder, got \"\"");
  // Results record their paths in JSON, which holds UTF-8 only: refused here, not mid-run.
  if (!is_utf8(out))
    throw InputError(option + ": expected a path in UTF-8, got \"" + printable(out) + "\"");
  const fs::path dir(out);
  const std::string shown = printable(out);
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st))
      throw InputError(option + ": expected a folder, got \"" + shown + "\" (not a folder)");
    if (access(dir.c_str(), W_OK) != 0)
      throw InputError(option + ": expected a writable folder, got \"" + shown + "\"");
    if (is_marked(dir)) return dir;
    std::vector<std::string> entries;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      entries.push_back(it->path().filename().string());
    if (ec)
      throw InputError(option + ": cannot read the folder \"" + shown + "\" (" + ec.message() +
                       ")");
    if (!entries.empty()) {
      std::sort(entries.begin(), entries.end());
      const std::string expected = fmt::format(
          "{}: expected a new or empty folder, or one glrefcheck made (it holds a {} file), got "
          "\"{}\"",
          option, kMarkerFile, shown);
      if (looks_like_glrefcheck_output(dir))
        throw InputError(expected +
                         ", which holds glrefcheck's results but no marker (an older glrefcheck's, "
                         "or copied): glrefcheck replaces nothing it did not mark; delete the "
                         "folder or name another");
      throw InputError(fmt::format(
          "{}, which holds \"{}\"{}: glrefcheck replaces nothing it did not write; name another "
          "folder",
          expected, printable(entries.front(), 80),
          entries.size() > 1 ? fmt::format(" and {} more", entries.size() - 1) : ""));
    }
  } else {
    // The folders glrefcheck makes are its own: out/ of `--out out/llvmpipe` too, so that a later
    // `run` with the default --out finds it marked.
    std::vector<fs::path> made;
    for (fs::path p = fs::absolute(dir, ec).lexically_normal(); !p.empty() && !fs::exists(p, ec);
         p = p.parent_path()) {
      made.push_back(p);
      if (p == p.parent_path()) break;
    }
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
      throw InputError(option + ": expected a folder that can be created, got \"" + shown + "\"" +
                       (ec ? " (" + ec.message() + ")" : " (not a folder)"));
    if (access(dir.c_str(), W_OK) != 0)
      throw InputError(option + ": expected a writable folder, got \"" + shown + "\"");
    for (const fs::path& p : made)
      if (p.lexically_normal() != fs::absolute(dir, ec).lexically_normal()) try {
          report::write_file_atomically(p / kMarkerFile, kMarkerText);
        } catch (const std::exception&) {
          // The folder asked for is what matters; its parents are a convenience.
        }
  }
  try {
    report::write_file_atomically(dir / kMarkerFile, kMarkerText);
  } catch (const std::exception& e) {
    throw InputError(option + ": " + e.what());
  }
  return dir;
}

void check_replaceable(const fs::path& file, const std::string& option,
                       std::string_view signature) {
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (!fs::exists(st)) return;
  const std::string shown = printable(file.string(), 200);
  const auto refuse = [&](const std::string& what) {
    throw InputError(option + ": expected a new file or one glrefcheck wrote, got \"" + shown +
                     "\", " + what +
                     ": glrefcheck replaces nothing it did not write; name another " + "file");
  };
  if (!fs::is_regular_file(st)) refuse("which is not a regular file");
  std::ifstream in(file, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  if (head.find(signature) == std::string::npos) refuse("which holds something else");
}

void clear_run_outputs(const fs::path& dir) {
  // Only ever inside a folder glrefcheck owns: anything else is the user's.
  if (!is_marked(dir))
    throw std::logic_error("clear_run_outputs: " + dir.string() + " is not a marked folder");
  for (const std::string& name : run_output_names()) {
    std::error_code ec;
    fs::remove_all(dir / name, ec);
    if (ec)
      throw InputError("--out: cannot remove the earlier run's " + (dir / name).string() + " (" +
                       ec.message() + ")");
  }
}

}  // namespace glrc::cli
