// Stamps: how glrefcheck knows a file a person named for it to write (fuzz --emit, compare
// --json/--markdown/--html, report --out, export --out) is one it wrote and nobody changed since,
// before it replaces it. A stamp is kStampPrefix and the SHA-256 (hex) of the whole file with
// those 64 digits written as zeros; each format holds it where its syntax allows (a JSON field, a
// comment). A file that holds no stamp, or one its text no longer matches (a person edited it,
// or wrote the words by hand), is the person's: refused.
#pragma once

#include <string>
#include <string_view>

namespace glrc::report {

inline constexpr std::string_view kStampPrefix = "glrefcheck-sha256:";

// kStampPrefix followed by 64 zeros: what a writer puts in its text where the stamp goes.
std::string stamp_placeholder();

// `text` with its one placeholder replaced by its stamp. Throws std::logic_error when the text
// holds no placeholder.
std::string stamped(std::string text);

// Whether `text` holds a stamp (the first kStampPrefix in it) that its text still matches.
bool stamp_intact(std::string_view text);

// The command that wrote the stamp: every writer puts "glrefcheck <command> " right before it
// ("fuzz", "compare", "export", "report"), so that one command's file is not replaced by
// another's (a case fuzz emitted by compare's JSON). Empty when the text holds no such word.
std::string stamp_writer(std::string_view text);

// `json_text` (an object as nlohmann's dump(2) writes it: "{\n  ...") with "written_by":
// "glrefcheck <writer> <stamp>" as its first field, stamped: results.json, a campaign's
// results.json, an emitted case, compare's JSON. Throws std::logic_error on other text.
std::string stamped_json(std::string_view writer, const std::string& json_text);

// What a JSON file glrefcheck reads back says of its own stamp: none (it holds no "written_by",
// as files of a glrefcheck before stamps, or made by hand), intact, or edited (its text no
// longer matches it: a person changed a verdict, a name, a field). `has_written_by`: whether
// the parsed document holds the field; `text`: the file's text as read.
enum class JsonStamp { none, intact, edited };
JsonStamp json_stamp(bool has_written_by, std::string_view text);
// The one line for an edited one: "<source>: written_by: expected ..., got ...".
std::string edited_stamp_message(std::string_view source);

// "sha256:" and the SHA-256 (hex) of `text`: a file's content named in results (RunInfo's
// verdict_inputs) and in the run journal, to tell whether two runs read the same file.
std::string content_digest(std::string_view text);

}  // namespace glrc::report
