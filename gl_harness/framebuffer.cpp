// The FBO every case is drawn into, and its readback into a Frame (framebuffer.hpp).
#include "gl_harness/framebuffer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace glrc::gl {

std::vector<GLenum> case_colour_formats(int varying_count) {
  std::vector<GLenum> formats(size_t(varying_count), GL_RGBA32F);
  formats.push_back(GL_R32I);
  return formats;
}

const char* framebuffer_status_name(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_COMPLETE:
      return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED:
      return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER:
      return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER:
      return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED:
      return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
      return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS:
      return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
  }
  return "unknown framebuffer status";
}

void Framebuffer::bind(const std::string& case_name, int width, int height,
                       const std::vector<GLenum>& colour_formats) {
  if (framebuffer_ && width_ == width && height_ == height && colour_formats_ == colour_formats) {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);  // draw buffers are FBO state
    return;
  }
  release();
  gl_.GenFramebuffers(1, &framebuffer_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  renderbuffers_.assign(colour_formats.size() + 1, 0);
  gl_.GenRenderbuffers(GLsizei(renderbuffers_.size()), renderbuffers_.data());
  auto attach = [&](GLuint rb, GLenum format, GLenum attachment) {
    gl_.BindRenderbuffer(GL_RENDERBUFFER, rb);
    gl_.RenderbufferStorage(GL_RENDERBUFFER, format, width, height);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, rb);
  };
  std::vector<GLenum> draw_buffers;
  for (size_t k = 0; k < colour_formats.size(); ++k) {
    attach(renderbuffers_[k], colour_formats[k], GLenum(GL_COLOR_ATTACHMENT0 + k));
    draw_buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + k));
  }
  attach(renderbuffers_.back(),
         depth_format_ == DepthFormat::unorm24 ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32F,
         GL_DEPTH_ATTACHMENT);
  gl_.DrawBuffers(GLsizei(draw_buffers.size()), draw_buffers.data());
  GLenum error = gl_.GetError();
  GLenum status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
  if (error != GL_NO_ERROR || status != GL_FRAMEBUFFER_COMPLETE) {
    release();
    throw RenderError(
        "case '" + case_name + "': " +
        (error != GL_NO_ERROR
             ? std::string(gl_error_name(error)) + " while creating the framebuffer"
             : std::string("framebuffer incomplete: ") + framebuffer_status_name(status)));
  }
  width_ = width;
  height_ = height;
  colour_formats_ = colour_formats;
}

void Framebuffer::release() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (framebuffer_) gl_.DeleteFramebuffers(1, &framebuffer_);
  if (!renderbuffers_.empty())
    gl_.DeleteRenderbuffers(GLsizei(renderbuffers_.size()), renderbuffers_.data());
  framebuffer_ = 0;
  renderbuffers_.clear();
  width_ = height_ = 0;
  colour_formats_.clear();
}

void Framebuffer::use() const {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
}

namespace {

// out[i][p] = rgba[4·p + i] for the first `size` (1 to 4) of each pixel's four values: a loop
// for each size, over every pixel at once, which the compiler vectorizes.
template <int size>
void deinterleave_first(const float* rgba, size_t pixels, float* const* out) {
  float* o[size];
  for (int i = 0; i < size; ++i)
    o[i] = out[i];
  for (size_t p = 0; p < pixels; ++p)
    for (int i = 0; i < size; ++i)
      o[i][p] = rgba[4 * p + size_t(i)];
}

void deinterleave(const float* rgba, size_t pixels, int size, float* const* out) {
  switch (size) {
    case 1:
      return deinterleave_first<1>(rgba, pixels, out);
    case 2:
      return deinterleave_first<2>(rgba, pixels, out);
    case 3:
      return deinterleave_first<3>(rgba, pixels, out);
    default:
      return deinterleave_first<4>(rgba, pixels, out);
  }
}

// The rows of a staging block: about kStagingBytes of `bytes_per_pixel` pixels `width` wide, at
// least one row, at most `height`. A readback converted on the CPU (de-interleaved, shifted,
// clamped) goes through one block at a time: the block GL has just written is still in the
// core's cache when it is converted, where a whole frame's staging buffer (16 MB for one RGBA32F
// attachment of 1024x1024) is read back from memory. Measured on the 1024x1024 quad of four vec4
// (bench/, gl/: llvmpipe's draw and readback): 36-40 ms with the whole frame staged, 32.5-34 ms
// with 32 or 64 rows; 2048x2048 with seven vec4: 271 -> 235 ms. A block is one glReadPixels
// per attachment: far fewer than a row each (8 rows a block measured the same as 64).
constexpr size_t kStagingBytes = size_t(1) << 20;

int staging_rows(int width, int height, size_t bytes_per_pixel) {
  const size_t row = std::max<size_t>(size_t(std::max(width, 1)) * bytes_per_pixel, 1);
  return int(std::clamp<size_t>(kStagingBytes / row, 1, size_t(std::max(height, 1))));
}

// Rows [0, height) of a readback `width` wide, `per_pixel` values of T a pixel, through
// `staging`, one block of staging_rows at a time: block(b, rows, data) for rows [b, b + rows) in
// turn, which reads them into data (every value, before any is used) and converts them.
template <class T, class Block>
void through_staging(std::vector<T>& staging, int width, int height, size_t per_pixel,
                     Block block) {
  const int step = staging_rows(width, height, per_pixel * sizeof(T));
  resize_large(staging, size_t(std::max(width, 0)) * size_t(step) * per_pixel);
  for (int b = 0; b < height; b += step)
    block(b, std::min(step, height - b), staging.data());
}

}  // namespace

void Framebuffer::read_varyings(const Case& c, Frame& frame, int y0) {
  const int n = int(c.varyings.size());
  const int w = frame.width, h = frame.height;
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  int component = 0;
  for (int k = 0; k < n; ++k) {
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0 + k);
    const int size = c.varyings[k].size;
    through_staging(rgba_, w, h, 4, [&](int b, int rows, float* rgba) {
      gl_.ReadPixels(0, y0 + b, w, rows, GL_RGBA, GL_FLOAT, rgba);
      // Rows come bottom first, as Frame wants: no flip. The varying's components in one pass
      // over the band's pixels (one per component read the RGBA band as many times).
      float* out[4] = {};
      for (int i = 0; i < size; ++i)
        out[i] = frame.components[size_t(component + i)].data() + frame.index(0, b);
      deinterleave(rgba, size_t(rows) * size_t(w), size, out);
    });
    component += size;
  }
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0 + n);
  gl_.ReadPixels(0, y0, w, h, GL_RED_INTEGER, GL_INT, frame.primitive.data());
}

// Mesa replicates the top bits below when widening a 24-bit depth to 32, so >> 8 gives the
// stored integer back.
void Framebuffer::read_depth(Frame& frame, int y0) {
  const int w = frame.width, h = frame.height;
  if (depth_format_ == DepthFormat::float32) {
    gl_.ReadPixels(0, y0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, frame.depth.data());
    return;
  }
  through_staging(z_, w, h, 1, [&](int b, int rows, GLuint* z) {
    gl_.ReadPixels(0, y0 + b, w, rows, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, z);
    float* depth = frame.depth.data() + frame.index(0, b);
    for (size_t i = 0, count = size_t(rows) * size_t(w); i < count; ++i)
      depth[i] = float(z[i] >> 8);
  });
}

void Framebuffer::read_fragment_counts(Frame& frame, int y0) {
  const int w = frame.width, h = frame.height;
  resize_large(frame.fragments, frame.pixel_count());  // every value written below
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  through_staging(counts_, w, h, 1, [&](int b, int rows, float* counts) {
    gl_.ReadPixels(0, y0 + b, w, rows, GL_RED, GL_FLOAT, counts);
    uint16_t* fragments = frame.fragments.data() + frame.index(0, b);
    for (size_t i = 0, count = size_t(rows) * size_t(w); i < count; ++i)
      fragments[i] = uint16_t(std::clamp(counts[i], 0.0f, 65535.0f));
  });
}

std::vector<float> Framebuffer::read_at(const std::vector<size_t>& pixels, GLenum attachment,
                                        GLenum format, int channels) {
  std::vector<float> out(pixels.size() * size_t(channels), NAN);
  if (width_ <= 0 || height_ <= 0 || pixels.empty()) return out;
  const size_t w = size_t(width_), total = w * size_t(height_), n = size_t(channels);
  std::vector<size_t> order;
  for (size_t k = 0; k < pixels.size(); ++k)
    if (pixels[k] < total) order.push_back(k);
  if (order.empty()) return out;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return pixels[a] < pixels[b]; });
  // The pixels in runs of rows, each run read as one block of the columns it needs: a
  // glReadPixels is a round trip through the driver (a thousand rows one by one took longer than
  // one block), but a block of every row asked, zero-filled and page-faulted afresh, took the
  // longest (8 MB for a 1000x1000 RG32F frame: 40% of a check tracing 1,030 pixels). A run is
  // at most kBlockFloats floats, so a dense set costs height / rows-per-block round trips.
  constexpr size_t kBlockFloats = size_t(1) << 17;
  const size_t run_rows = std::max<size_t>(1, kBlockFloats / (w * n));
  std::vector<float> block;
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.ReadBuffer(attachment);
  for (size_t first = 0; first < order.size();) {
    const size_t y0 = pixels[order[first]] / w;
    size_t end = first, x0 = w, x1 = 0;
    for (; end < order.size() && pixels[order[end]] / w < y0 + run_rows; ++end) {
      x0 = std::min(x0, pixels[order[end]] % w);
      x1 = std::max(x1, pixels[order[end]] % w);
    }
    const size_t y1 = pixels[order[end - 1]] / w, width = x1 - x0 + 1;
    block.resize(width * (y1 - y0 + 1) * n);
    gl_.ReadPixels(GLint(x0), GLint(y0), GLsizei(width), GLsizei(y1 - y0 + 1), format, GL_FLOAT,
                   block.data());
    for (size_t k = first; k < end; ++k) {
      const size_t i = pixels[order[k]];
      const size_t j = (i / w - y0) * width + (i % w - x0);
      for (size_t c = 0; c < n; ++c)
        out[order[k] * n + c] = block[j * n + c];
    }
    first = end;
  }
  return out;
}

}  // namespace glrc::gl
