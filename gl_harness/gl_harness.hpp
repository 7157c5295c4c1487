// gl_harness: the same Case rendered by a real GL implementation. The GL context is the only
// global state in glrefcheck and it lives behind this interface.
#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/case.hpp"
#include "core/fragment_trace.hpp"
#include "core/frame.hpp"
#include "core/names.hpp"

namespace glrc::gl {

enum class Backend { osmesa, egl, egl_device };
}  // namespace glrc::gl
namespace glrc {
template <>
struct Names<gl::Backend> {
  static constexpr std::array<std::pair<gl::Backend, std::string_view>, 3> table{{
      {gl::Backend::osmesa, "osmesa"},
      {gl::Backend::egl, "egl"},
      {gl::Backend::egl_device, "egl-device"},
  }};
};
}  // namespace glrc
namespace glrc::gl {
const char* to_string(Backend b);                                // "osmesa", "egl", "egl-device"
std::optional<Backend> backend_from_string(std::string_view s);  // inverse of to_string

// The depth attachment every render draws into.
//   float32: GL_DEPTH_COMPONENT32F; Frame::depth holds z_w as the depth stage produced it.
//   unorm24: GL_DEPTH_COMPONENT24; Frame::depth holds the stored integer (0 .. 2^24 - 1, exact
//            in a float), read back as GL_UNSIGNED_INT >> 8, and 2^24 - 1 (the clear value)
//            where nothing was drawn. For finding how a driver rounds to 24 bits; the
//            comparator does not understand such frames.
enum class DepthFormat { float32, unorm24 };

struct Target {
  Backend backend = Backend::osmesa;
  // Mesa's gallium driver (llvmpipe, softpipe; zink on EGL); "" = whatever the platform gives
  std::string driver = "llvmpipe";
  int device_index = 0;  // egl-device: which EGLDevice
  // What glrefcheck identify changes; the defaults are what every other command uses.
  // false: glProvokingVertex is never called on this renderer's context, so flat varyings come
  // from the context's default provoking vertex (GL's default is the last) and
  // Case::provoking is ignored.
  bool set_provoking_vertex = true;
  DepthFormat depth_format = DepthFormat::float32;
};

struct GlInfo {
  std::string vendor, renderer, version;
  // How the context was made, e.g. "EGL surfaceless platform (EGL 1.5, Mesa Project)".
  std::string platform;
  // The driver library the context came from, as the dynamic loader found it (libOSMesa,
  // libEGL_mesa, libEGL_nvidia...): which Mesa ran, whatever GL_VERSION claims.
  std::string library;
  int subpixel_bits = 0;  // GL_SUBPIXEL_BITS as reported
  // GL_VIEWPORT_SUBPIXEL_BITS as reported (GL 4.1 or GL_ARB_viewport_array: the precision of a
  // fractional viewport's bounds); -1 where the context has no fractional viewports.
  int viewport_subpixel_bits = -1;
  // GL_PROVOKING_VERTEX as reported by the fresh context, before anything set it (GL: last).
  ProvokingVertex initial_provoking_vertex = ProvokingVertex::last;
  // A pass-through geometry shader supplies gl_PrimitiveID, because without one this driver
  // drew nothing when the fragment shader read gl_PrimitiveID (softpipe, Mesa 22.3.6). Only
  // then: on llvmpipe a geometry shader changes the bits of varyings and depth.
  bool primitive_id_from_geometry_shader = false;
  // What the implementation got wrong while the renderer set up, one line each: today a wrong
  // first draw (which pixel, what was expected, what came). The renderer works all the same;
  // every case passes or fails on its own, so a run reports these and goes on.
  std::vector<std::string> warnings;
};

// A library, platform, driver or GL feature this machine lacks. what() is one line saying what
// is missing and how to get it; the CLI prints it and exits 2.
struct Unavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A failure while rendering one case (GL error, incomplete FBO): that case is an error, the
// run goes on.
struct RenderError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A GL feature one case asks for that this implementation lacks (glClipControl without GL 4.5
// or GL_ARB_clip_control): that case is skipped with what() as the reason, the run goes on.
struct FeatureMissing : RenderError {
  using RenderError::RenderError;
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual const GlInfo& info() const = 0;
  // Renders one case into a fresh FBO of the case's framebuffer size and reads it back.
  virtual Frame render(const Case& c) = 0;
  // The same in two steps, for a frame too large to hold whole: draw() renders the case and
  // keeps it; read_rows() then reads rows [y0, y0 + rows) of it into a Frame that many rows
  // high (row 0 = window row y0), glReadPixels of that region only, as often as asked, until
  // the next draw() or render(). render(c) is draw(c), then read_rows(c, 0, c.fb_height).
  // Throws as render() does, and RenderError for rows outside the framebuffer. These defaults
  // (for renderers that are no GL: tests) keep render()'s whole frame and cut it.
  virtual void draw(const Case& c) { drawn_ = render(c); }
  virtual Frame read_rows(const Case& c, int y0, int rows);
  // render(c), read back into the buffers of `storage` (a frame the caller is done with, of
  // any case) where they are large enough: a caller checking case after case reuses the last
  // one's memory (Frame::reset). Throws as render() does. This default (renderers that are no
  // GL: tests) is render(c).
  virtual Frame render_reusing(const Case& c, Frame&& storage) {
    storage = Frame();
    return render(c);
  }
  // read_rows(), read back into the buffers of `storage` where they are large enough: a
  // streamed check reuses a slice's memory for the slice after next. Throws as read_rows(). This
  // default (renderers that are no GL: tests) is read_rows().
  virtual Frame read_rows_reusing(const Case& c, int y0, int rows, Frame&& storage) {
    storage = Frame();
    return read_rows(c, y0, rows);
  }
  // The fragment traces (core/fragment_trace.hpp) of the case last drawn (render() or draw()),
  // at `pixels` (window indices x + y·fb_width), in their order: its fragment counts, and the
  // sums of p + 1 and the hash of p over its fragments (the count pass's second attachment, or
  // where gl_PrimitiveID needs the geometry shader a trace pass drawn the first time a case is
  // asked: the count pass again); nothing for a pixel whose sums were not exact in
  // float32, or from a renderer that keeps no traces. Throws RenderError before a draw. This
  // default (renderers that are no GL: tests) keeps none.
  virtual std::vector<std::optional<FragmentTrace>> fragment_traces(
      const Case& c, const std::vector<size_t>& pixels) {
    (void)c;
    return std::vector<std::optional<FragmentTrace>>(pixels.size());
  }

 private:
  Frame drawn_;
};

// Creates a context on the target and checks that the driver asked for is the one running.
// Throws Unavailable. Mesa picks its driver once per process: every call in one process must
// name the same Target::driver (a different one throws Unavailable); run one process per
// driver. Several renderers with the same driver may coexist; each makes its own context
// current in render().
// Environment: a non-empty driver sets GALLIUM_DRIVER=driver; for the EGL backends and
// llvmpipe/softpipe/zink also LIBGL_ALWAYS_SOFTWARE=1 (zink then runs on lavapipe).
std::unique_ptr<Renderer> create_renderer(const Target& t);

}  // namespace glrc::gl
