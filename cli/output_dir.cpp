#include "cli/output_dir.hpp"

#include <unistd.h>

#include <fmt/core.h>
#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli/session.hpp"
#include "report/report.hpp"

namespace glrc::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarkerText =
    "glrefcheck output folder: glrefcheck replaces its own files here (results.json, results.csv, "
    "failures.csv, junit.xml, report.html, journal.jsonl, cases/, logs/) and nothing else.\n";

// A results.json (of `run`) or an identify.json (of `identify`) that glrefcheck wrote before
// folders were marked: evidence enough that the folder is glrefcheck's.
bool earlier_glrefcheck_output(const fs::path& dir) {
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
    if (!entries.empty() && !earlier_glrefcheck_output(dir)) {
      std::sort(entries.begin(), entries.end());
      throw InputError(fmt::format(
          "{}: expected a new or empty folder, or one glrefcheck made (it holds a {} file), got "
          "\"{}\", which holds \"{}\"{}: glrefcheck replaces nothing it did not write; name "
          "another folder",
          option, kMarkerFile, shown, printable(entries.front()),
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

bool is_utf8(std::string_view s) {
  size_t k = 0;
  while (k < s.size()) {
    const auto c = static_cast<unsigned char>(s[k]);
    size_t n = 0;
    uint32_t cp = 0;
    if (c < 0x80) {
      ++k;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      n = 1, cp = c & 0x1F;
    } else if (c >= 0xE0 && c <= 0xEF) {
      n = 2, cp = c & 0x0F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      n = 3, cp = c & 0x07;
    } else {
      return false;
    }
    for (size_t j = 1; j <= n; ++j) {
      if (k + j >= s.size()) return false;
      const auto d = static_cast<unsigned char>(s[k + j]);
      if ((d & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (d & 0x3F);
    }
    // Overlong forms, UTF-16 surrogates and code points past U+10FFFF are not UTF-8.
    if ((n == 2 && cp < 0x800) || (n == 3 && (cp < 0x10000 || cp > 0x10FFFF)) ||
        (cp >= 0xD800 && cp <= 0xDFFF))
      return false;
    k += n + 1;
  }
  return true;
}

std::string printable(std::string_view s) {
  std::string out;
  for (size_t k = 0; k < s.size();) {
    const auto c = static_cast<unsigned char>(s[k]);
    // The longest valid UTF-8 sequence starting here, if any, is kept as it is.
    size_t len = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
    if (c >= 0x80 && k + len <= s.size() && is_utf8(s.substr(k, len))) {
      out.append(s.substr(k, len));
      k += len;
      continue;
    }
    if (c < 0x20 || c == 0x7F || c >= 0x80)
      out += fmt::format("\\x{:02x}", c);
    else
      out += char(c);
    ++k;
  }
  return out;
}

}  // namespace glrc::cli
