// Text with holes, filled: the shader_test's GLSL is kept as real files (export/glsl/), embedded
// at build time, whose per-case parts are marked in lines of their own or in place:
//   @NAME@          replaced by values' NAME. A line that holds only the hole takes the value's
//                   lines (each ending in a newline; none when it is empty) instead of itself.
//   //@if FLAG      the lines up to the matching //@else or //@end are kept where FLAG is set
//   //@if !FLAG     ... where it is not; //@if blocks nest
//   //@ text        a comment of the file's own, never in the output
// Every hole and flag the file names must be given, in the blocks kept or not, and every one
// given must be named: the files are the program's, not the user's, and a hole or flag not
// given, one given but never named, an unbalanced marker or an '@' without its pair throws
// std::logic_error naming it.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace glrc::reproducer {

std::string fill_template(std::string_view text, const std::map<std::string, std::string>& values,
                          const std::map<std::string, bool>& flags);

}  // namespace glrc::reproducer
