// Case files: JSON in, validated Case out. The format is documented in cases/README.md.
//
// This file reads files and folders (load, collect); parsing is typed_json's document parser
// (typed_json/document.hpp) and the fields are read by the case schema (case_schema.hpp). Every
// error is a CaseError with one line "<file>: <field path>: expected <what>, got <what>", so that
// a typo in a suite of dozens of files points at its place at once.
#include "casefile/casefile.hpp"

#include "core/text.hpp"

#include <sys/stat.h>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "casefile/case_schema.hpp"
#include "typed_json/document.hpp"
#include "typed_json/text.hpp"

namespace glrc::casefile {
namespace {

namespace fs = std::filesystem;
using typed_json::json_quoted;
using typed_json::printable;
using typed_json::utf8_length;

}  // namespace

Case load(const fs::path& file) {
  const std::string name = file.string();
  const typed_json::Reader reader(name, typed_json::Wording::full,
                                  &typed_json::raise_as<CaseError>);
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (ec || !fs::exists(st)) reader.fail("", "a readable case file", "none at this path");
  // Opening a FIFO would wait for a writer, forever.
  if (!fs::is_regular_file(st)) reader.fail("", "a regular case file", file_kind(st));
  std::ifstream in(file, std::ios::binary);
  if (!in) reader.fail("", "a readable case file", "one that cannot be opened");
  std::string text;
  text.resize(size_t(fs::file_size(file, ec)));
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  if (in.bad() || ec) reader.fail("", "a readable case file", "a read error");
  // A file that grew since its size was taken: read the rest.
  if (in) text.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return parse(std::move(text), name, file.stem().string());
}

Case parse(std::string text, const std::string& source, const std::string& name) {
  const typed_json::Reader reader(source, typed_json::Wording::full,
                                  &typed_json::raise_as<CaseError>);
  const typed_json::ArenaScope arena;  // before the document: outlives it
  CaseJson root;
  typed_json::parse(reader, text, root, expected_number_at);
  text = std::string();  // the document holds it all now
  Case c = Loader(reader).load(root);
  c.name = name;
  return c;
}

namespace {

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
      // A link that leads nowhere, or back to itself, is there: say what it is.
      throw CaseError(
          printable(arg) + ": expected a case file or a directory of them, got " +
          (fs::is_symlink(fs::symlink_status(p))
               ? "a symbolic link that leads to no file (" + (ec ? ec.message() : "dangling") + ")"
               : std::string("no such path")));
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
            // glrefcheck's own output (a run's results.json, a campaign's failures/) is no case:
            // `run cases --out cases/out` and the next `run cases` would read it as one.
            if (std::error_code mec; fs::is_regular_file(e / kOutputFolderMarker, mec))
              say("glrefcheck: ignored " + printable(e.string()) +
                  ": an output folder of glrefcheck's (it holds " + kOutputFolderMarker + ")");
            else
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
