#include "export/text_template.hpp"

#include <set>
#include <stdexcept>
#include <vector>

namespace glrc::reproducer {
namespace {

[[noreturn]] void fail(const std::string& why) {
  throw std::logic_error("fill_template: " + why);
}

// Whether `line`, a marker, names a flag that is set (a leading '!' inverts it).
bool flag_set(std::string_view name, const std::map<std::string, bool>& flags,
              std::set<std::string>& used) {
  const bool inverted = name.starts_with('!');
  if (inverted) name.remove_prefix(1);
  const auto it = flags.find(std::string(name));
  if (it == flags.end()) fail("no flag " + std::string(name));
  used.insert(it->first);
  return it->second != inverted;
}

// `line` with every @NAME@ replaced by its value.
std::string fill_holes(std::string_view line, const std::map<std::string, std::string>& values,
                       std::set<std::string>& used) {
  std::string out;
  for (size_t at = 0;;) {
    const size_t open = line.find('@', at);
    if (open == std::string_view::npos) return out.append(line.substr(at));
    const size_t close = line.find('@', open + 1);
    if (close == std::string_view::npos) fail("an '@' without its pair in: " + std::string(line));
    const std::string name(line.substr(open + 1, close - open - 1));
    const auto it = values.find(name);
    if (it == values.end()) fail("no value " + name);
    used.insert(name);
    out.append(line.substr(at, open - at)).append(it->second);
    at = close + 1;
  }
}

}  // namespace

std::string fill_template(std::string_view text, const std::map<std::string, std::string>& values,
                          const std::map<std::string, bool>& flags) {
  std::string out;
  std::set<std::string> used_values, used_flags;
  // Per open //@if: whether its lines are kept, and whether the block around it keeps its own.
  struct Block {
    bool kept, outer;
  };
  std::vector<Block> blocks;
  const auto kept = [&] { return blocks.empty() || blocks.back().kept; };
  while (!text.empty()) {
    const size_t end = text.find('\n');
    if (end == std::string_view::npos) fail("a last line without its newline");
    const std::string_view line = text.substr(0, end);
    text.remove_prefix(end + 1);
    if (line.starts_with("//@if ")) {
      const bool outer = kept(), set = flag_set(line.substr(6), flags, used_flags);
      blocks.push_back({outer && set, outer});
    } else if (line == "//@else") {
      if (blocks.empty()) fail("//@else without //@if");
      Block& b = blocks.back();
      b.kept = b.outer && !b.kept;
    } else if (line == "//@end") {
      if (blocks.empty()) fail("//@end without //@if");
      blocks.pop_back();
    } else if (line.starts_with("//@")) {
      continue;  // the file's own comment
    } else {
      // Every hole is filled, kept or not: each must be given wherever the file uses it.
      const std::string filled = fill_holes(line, values, used_values);
      const bool whole = line.size() > 2 && line.front() == '@' && line.back() == '@' &&
                         line.find('@', 1) == line.size() - 1;
      if (!kept()) continue;
      out += filled;
      if (!whole) out += '\n';
    }
  }
  if (!blocks.empty()) fail("//@if without //@end");
  for (const auto& [name, value] : values)
    if (!used_values.count(name)) fail("value " + name + " given but never used");
  for (const auto& [name, value] : flags)
    if (!used_flags.count(name)) fail("flag " + name + " given but never used");
  return out;
}

}  // namespace glrc::reproducer
