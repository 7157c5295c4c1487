// Internal to gl_harness: the framebuffer object every case is drawn into, and reading it back
// into a Frame. Every backend renders to such an FBO (never to a window), with float (or
// integer) attachments, so each value is read back exactly as the fragment shader and the
// depth stage produced it.
//
// Layout of a case's framebuffer (case_colour_formats): colour attachment k (k < n, n the
// number of varyings) is RGBA32F and holds varying k, padded with zeros; attachment n is R32I
// and holds gl_PrimitiveID; depth is DEPTH_COMPONENT32F, or DEPTH_COMPONENT24 for
// DepthFormat::unorm24. The fragment-count pass uses one R32F attachment and the same depth.
// shaders.hpp writes the fragment outputs to match. Rows are read bottom first, as Frame
// stores them: no flip.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/fragment_trace.hpp"
#include "core/frame.hpp"
#include "gl_harness/gl_functions.hpp"
#include "gl_harness/gl_harness.hpp"

namespace glrc::gl {

// One colour attachment per varying plus one for gl_PrimitiveID, within GL 3.3's guaranteed 8
// draw buffers.
inline constexpr int kMaxVaryings = 7;

// The colour formats of a case with `varying_count` varyings: varying_count x GL_RGBA32F, then
// GL_R32I for gl_PrimitiveID.
std::vector<GLenum> case_colour_formats(int varying_count);

// "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT" etc. for glCheckFramebufferStatus's answer, or
// "unknown framebuffer status".
const char* framebuffer_status_name(GLenum status);

// An FBO and its renderbuffers, kept from one case to the next while the size and the formats
// stay the same: allocating them is most of the cost of a case (llvmpipe takes ~50 ms per
// 1024x1024 RGBA32F renderbuffer here), and every case clears all of them first. At most one
// set is alive per Framebuffer, so memory does not pile up either.
//
// Every call needs the renderer's context current. GL objects are freed by release(), not by
// the destructor: the renderer makes its context current and releases them before the context
// goes (a renderer that fails to construct leaves them to the context's teardown).
class Framebuffer {
 public:
  // `gl` must outlive this object; `depth_format` is Target::depth_format.
  Framebuffer(const GlFunctions& gl, DepthFormat depth_format)
      : gl_(gl), depth_format_(depth_format) {}
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  // Binds (GL_FRAMEBUFFER) an FBO of width x height pixels with colour attachment k of
  // colour_formats[k] (all of them draw buffers, in order) and the depth attachment; the one
  // kept from the last call when size and formats are the same, else a new one. Throws
  // RenderError("case '<case_name>': ...") naming the GL error or the incompleteness (the
  // framebuffer is then released).
  void bind(const std::string& case_name, int width, int height,
            const std::vector<GLenum>& colour_formats);

  // Deletes the FBO and its renderbuffers and binds framebuffer 0; a no-op on the objects when
  // there are none.
  void release();

  // --- Readback from the bound framebuffer into `frame` (of the case's width and height) ---

  // Colour attachments 0 .. n-1 of a case's layout into frame.components (varying k's
  // components, in Case order; the padding is dropped), and attachment n into
  // frame.primitive. Sets GL_PACK_ALIGNMENT to 1. GL errors are left for the caller to check.
  // Rows [y0, y0 + frame.height) only, into a frame that high: the same for every read_*.
  void read_varyings(const Case& c, Frame& frame, int y0 = 0);

  // The depth attachment into frame.depth: float z_w for DepthFormat::float32, the stored
  // 24-bit integer (0 .. 2^24 - 1, exact in a float) for unorm24.
  void read_depth(Frame& frame, int y0 = 0);

  // The fragment-count pass's R32F attachment 0 into frame.fragments (resized to the pixel
  // count), each count clamped to 0 .. 65535.
  void read_fragment_counts(Frame& frame, int y0 = 0);
  // The values of colour attachment `attachment` (GL_COLOR_ATTACHMENTk) at `pixels` (window
  // indices x + y·width of the bound framebuffer), `channels` floats each (read as `format`,
  // GL_RED or GL_RG), in the pixels' order; NaN for a pixel outside the framebuffer. One
  // glReadPixels per run of rows asked, of the columns the run's pixels span, each at most
  // 2^17 floats.
  std::vector<float> read_at(const std::vector<size_t>& pixels, GLenum attachment, GLenum format,
                             int channels);
  // Binds (GL_FRAMEBUFFER) the FBO the last bind() made, as it is: to read it again.
  void use() const;

 private:
  const GlFunctions& gl_;
  DepthFormat depth_format_;
  GLuint framebuffer_ = 0;
  std::vector<GLuint> renderbuffers_;  // one per colour attachment, then depth
  int width_ = 0, height_ = 0;
  std::vector<GLenum> colour_formats_;
  // Read back before they are converted into a Frame, a block of rows at a time (about a
  // megabyte: still in cache when converted), kept to spare reallocations: a block of one colour
  // attachment as RGBA, of a 24-bit depth buffer, of the fragment counts.
  std::vector<float> rgba_;
  std::vector<GLuint> z_;
  std::vector<float> counts_;
};

}  // namespace glrc::gl
