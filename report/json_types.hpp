// The results' types as JSON: one serialization for results.json, the worker protocol (a case's
// result on one line) and the run journal. nlohmann's to_json/from_json (in namespace glrc, so
// found by ADL: `json j = result;`, `j.get<CaseResult>()`) and, for readers that name their
// source, read() overloads that carry the source and the field path into every message.
//
// Every field is written; numbers that JSON cannot hold (NaN, infinities) as the strings "nan",
// "inf", "-inf" (json_number, report/format.hpp), which every reader takes back. Fields added
// after the first results.json are optional when read, with the value an old run meant (see
// each read()). Object keys come out sorted (nlohmann::json's objects are std::maps), so the
// bytes of a results.json depend on the values alone.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/result.hpp"
#include "typed_json/reader.hpp"

namespace glrc {

void to_json(nlohmann::json& j, const WorstPixel& w);
void to_json(nlohmann::json& j, const ChannelStats& c);
void to_json(nlohmann::json& j, const CoverageStats::Pixel& p);
void to_json(nlohmann::json& j, const CoverageStats& c);
// results.json's "tolerance" of a case: mode, subpixel_bits, varying_ulps, depth_ulps,
// allow_boundary.
void to_json(nlohmann::json& j, const Tolerance& t);
void to_json(nlohmann::json& j, const CaseResult& r);
void to_json(nlohmann::json& j, const RunInfo& r);

// report::read() with no source and the value at the top of the path ("channels[0].worst[1].x:
// expected an integer"): throws typed_json::Error.
void from_json(const nlohmann::json& j, WorstPixel& w);
void from_json(const nlohmann::json& j, ChannelStats& c);
void from_json(const nlohmann::json& j, CoverageStats::Pixel& p);
void from_json(const nlohmann::json& j, CoverageStats& c);
void from_json(const nlohmann::json& j, Tolerance& t);
void from_json(const nlohmann::json& j, CaseResult& r);
void from_json(const nlohmann::json& j, RunInfo& r);

}  // namespace glrc

namespace glrc::report {

// Reads the value `j` at `path` (e.g. "cases[3]") into `out`, each field checked; a field that
// is missing, of the wrong type or out of range fails through `r` (Wording::brief is
// results.json's wording: "<source>: cases[3].seconds: expected a number or "nan", "inf",
// "-inf""). Integers are checked against their ranges (a forged file must not reach the code
// that indexes by them, nor read 2^32 + 1 as 1).
void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          WorstPixel& out);
void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          ChannelStats& out);
void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          CoverageStats::Pixel& out);
void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          CoverageStats& out);
// subpixel_bits is optional (default 4).
void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          Tolerance& out);
// outcome, when absent (written before outcomes were recorded), is derived from status
// (ExpectedFail was a Fail, UnexpectedPass a Pass); gl_digest is optional ("").
void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          CaseResult& out);
// Optional, added later: model_source, mesa_prefix, gl_library (""), gl_warnings (none),
// gl_primitive_id_from_geometry_shader and interrupted (false), gl_subpixel_bits (0), jobs (1,
// >= 0: a merged run of no shards says 0), fraction (1, >= 1), fraction_start (1, in
// 1..fraction), total_cases (0).
void read(const typed_json::Reader& r, const nlohmann::json& j, const std::string& path,
          RunInfo& out);

}  // namespace glrc::report
