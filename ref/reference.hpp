// The exact CPU reference of GL's triangle pipeline: clip -> divide -> viewport -> snap ->
// rasterize -> v/w and 1/w interpolated per pixel -> depth. Every value is the float32 nearest
// (ties to even) to the exact rational value the Model defines; no result depends on compiler,
// flags or CPU.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"
#include "core/fragment_trace.hpp"
#include "core/model.hpp"

namespace glrc::ref {

// render()'s result is the Expectation (core/expectation.hpp): the frame, its edge bits and,
// when asked for, the allowance. Its old name here, kept for the CMake package's users:
using Reference [[deprecated("ref::Reference is glrc::Expectation")]] = Expectation;

// Renders the case under model m. With `freedom_bits` (the GL_SUBPIXEL_BITS an implementation
// reports, at least 4 taken), also the specification's allowance per pixel and channel
// (allowance.hpp), and edge bands as wide as that position freedom; without, no allowance and
// bands one model subpixel step wide. Neither is part of the digest.
// `threads`: how many threads draw it (ref/tiles.hpp), 0 for every core this process may use;
// every bit of the result is the same for any number.
Expectation render(const Case& c, const Model& m, std::optional<int> freedom_bits = std::nullopt,
                   int threads = 1);
// The same bits, drawn in the buffers of `storage` (an Expectation the caller is done with, of
// any case; left empty), where they are large enough: a caller checking case after case
// reuses the memory of the last one (Frame::reset).
Expectation render(const Case& c, const Model& m, std::optional<int> freedom_bits, int threads,
                   Expectation&& storage);

// render(c, m, freedom_bits, threads, storage) with the components' allowances deferred
// (Expectation::deferred), and the depth's too in a case without a depth test
// (DepthFunc::always: no fragment may win it instead of another, so drawing needs no depth
// allowance): computed where a comparison asks for them, bit for bit render()'s, not at every
// pixel drawn; the result's allowed frame holds the depth's only, or nothing (and the
// candidates their own, as render()'s), until complete_allowance (core/frame.hpp). Most pixels
// of a frame compared need only a bound of their allowances over a run of pixels.
Expectation render_deferred(const Case& c, const Model& m, int freedom_bits, int threads,
                            Expectation&& storage = {});

// A case's triangles as render() sets them up (ref/mesh.hpp).
struct CaseSetup;
// render() and render_deferred() that hand their set-up of c's triangles under m back in
// `setup` (instead of freeing it), for fragment_choices() to reuse: the same bits.
Expectation render(const Case& c, const Model& m, std::optional<int> freedom_bits, int threads,
                   Expectation&& storage, std::shared_ptr<const CaseSetup>& setup);
Expectation render_deferred(const Case& c, const Model& m, int freedom_bits, int threads,
                            Expectation&& storage, std::shared_ptr<const CaseSetup>& setup);

// render(c, m, std::nullopt, threads).frame, bit for bit, without the edge bits (which `digest`
// does not hash): neither the edges triangles share nor the bands along them are looked for.
Frame render_frame(const Case& c, const Model& m, int threads = 1);

// Rows [y0, y0 + rows) of render()'s result, for a frame too large to hold whole (check.hpp's
// streamed comparison): the same bits, in frames `rows` high whose row 0 is window row y0, the
// edge bits and candidates' pixels indexed within them. Every triangle is set up and prepared
// again for each call (per-triangle work times the number of slices). Throws
// std::invalid_argument for rows outside the framebuffer.
Expectation render_rows(const Case& c, const Model& m, std::optional<int> freedom_bits, int threads,
                        int y0, int rows);

// render_rows() with the components' allowances deferred, as render_deferred() defers them
// (and the depth's in a case without a depth test): bit for bit render_rows()' allowances where
// a comparison of the slice asks for them (its DeferredAllowance knows the slice's first row), in
// the buffers of `storage` where given. Throws as render_rows().
Expectation render_rows_deferred(const Case& c, const Model& m, int freedom_bits, int threads,
                                 int y0, int rows, Expectation&& storage = {});

// What a conforming implementation may rasterize at each of `pixels` (window indices
// x + y·fb_width, each inside the framebuffer), for judging a fragment trace
// (core/fragment_trace.hpp): the triangles that surely cover the centre, those that may (free,
// or as a shared edge gives the centre to their side), from the position freedom of an
// implementation of `freedom_bits` subpixel bits (at least 4), as render() finds its edge bits.
// The reference's own count is sure.count plus the members it draws. Sets up again the
// triangles that may reach a pixel asked (render()'s set-up and position freedom, not its
// planes or allowances): for the few pixels whose count differs, not for a frame. `threads` as
// render()'s.
std::vector<FragmentChoices> fragment_choices(const Case& c, const Model& m, int freedom_bits,
                                              const std::vector<size_t>& pixels, int threads = 1);
// The same from `setup`, render()'s set-up of c's triangles under m (render(..., setup)),
// instead of setting them up again.
std::vector<FragmentChoices> fragment_choices(const Case& c, const Model& m, int freedom_bits,
                                              const std::vector<size_t>& pixels, int threads,
                                              const CaseSetup& setup);

// SHA-256 (hex) of the frame's bits: width, height, then per pixel primitive, depth and every
// component, little-endian. Identical bits give identical digests on any machine.
std::string digest(const Frame& f);
// digest() of a frame fed slice of rows by slice of rows, in order: the same hex, without the
// frame held whole.
class FrameDigest {
 public:
  FrameDigest(int width, int height);
  ~FrameDigest();
  FrameDigest(const FrameDigest&) = delete;
  FrameDigest& operator=(const FrameDigest&) = delete;
  void add_rows(const Frame& slice);  // slice.width must be the frame's
  std::string hex();                  // once, after the last row
 private:
  struct Context;
  std::unique_ptr<Context> context_;
  int width_;
};
// SHA-256 (hex) of everything render() gives: the frame's digest, then per pixel the edge bits
// and the allowance's primitive, depth and components (when computed), then every candidate
// (pixel, primitive, depth, allowed depth, values, allowed values). A faster reference must keep
// it (tests/expectation_digests.txt), not only the frame's.
std::string expectation_digest(const Expectation& r);

}  // namespace glrc::ref
