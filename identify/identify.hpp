// identify: which Model explains a GL implementation best, with the evidence. Five findings, one
// file each: subpixel bits (subpixel_bits.hpp), attribute planes (planes.hpp), tie-break rule
// (tie_rule.hpp), default provoking vertex (provoking_vertex.hpp) and 24-bit depth rounding
// (depth_rounding.hpp). The first three are the choices the reference takes as a Model, and
// judge `run`, `diff` and `selftest` unless the command line names a model.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/model.hpp"
#include "gl_harness/gl_harness.hpp"
#include "identify/depth_offset.hpp"
#include "identify/depth_rounding.hpp"
#include "identify/planes.hpp"
#include "identify/provoking_vertex.hpp"
#include "identify/subpixel_bits.hpp"
#include "identify/tie_rule.hpp"
#include "identify/viewport_precision.hpp"

namespace glrc::identify {

// Findings 1 to 3: the choices the reference takes as a Model.
struct ModelFindings {
  BitsFinding bits;
  PlanesFinding planes;
  TieFinding ties;
  size_t coverage_frames = 0, plane_triangles = 0, tie_triangles = 0;
  Model model() const;
};

// All five findings. `renderer` is a harness renderer; `raw` one opened with
// set_provoking_vertex = false and a 24-bit depth buffer (gl::Target), for findings 4 and 5.
struct Identification {
  ModelFindings model;
  ProvokingFinding provoking;
  DepthFinding depth;
  ViewportFinding viewport;
  DepthOffsetFinding offset;
  std::string summary() const;  // "identify: subpixel_bits=8 planes=unsnapped tie=... depth24=..."
};

// The subpixel bits, attribute planes and tie-break rule on `renderer`: about 0.5 s on
// llvmpipe. The probes come from a fixed seed, so they are the same in every use. Throws
// ProbeError when GL cannot draw a probe.
ModelFindings find_model(gl::Renderer& renderer);
Model identify_model(gl::Renderer& renderer);

// Findings 1 to 3 on `renderer` (the same probes as find_model), then 4 and 5 on `raw`.
Identification identify(gl::Renderer& renderer, gl::Renderer& raw);

// identify.json's contents (the evidence of every finding), for `gl`, the raw renderer's
// GL_PROVOKING_VERTEX `raw_provoking`, and the run's backend and driver names.
nlohmann::json identification_json(const Identification& id, const gl::GlInfo& gl,
                                   ProvokingVertex raw_provoking, const std::string& backend,
                                   const std::string& driver);

// "none" for 0 bits, else the number; "snapped"/"unsnapped"; "first"/"last".
std::string bits_name(int bits);
const char* planes_name(Planes p);
const char* provoking_name(ProvokingVertex p);

// The model that judges a run and where it came from.
struct ModelChoice {
  Model model;
  // "identify" (found now), "identify (cached)", "command line" (--subpixel-bits, --planes,
  // --tie-break, or a driver model), "default" (--model ideal: the fixed default model); after a
  // failed identification "default (identify failed: why)".
  std::string source;
};

// `fallback` as the choice after a failed identification: its source says why, on one line of
// at most about 200 characters.
ModelChoice fallback_model(const Model& fallback, const std::string& why);

// The model that judges cases on `renderer`: `given` when the caller has one (the command
// line's), else the identified one, from the model cache when it holds this implementation,
// else identified now and cached. A failed identification gives `fallback`, its source saying
// why. Never throws for GL's sake.
ModelChoice choose_model(const std::optional<ModelChoice>& given, const Model& fallback,
                         gl::Renderer& renderer);

}  // namespace glrc::identify
