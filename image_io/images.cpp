// glrefcheck_images.so: the image functions of glrc_images.h on OpenImageIO. Everything that
// crosses the C interface is caught here: an exception must not unwind into a caller that may
// have been built by another compiler.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <string>

#include "image_io/glrc_images.h"

namespace {

void set_error(char* error, size_t error_size, std::string why) {
  if (!error || error_size == 0) return;
  std::replace(why.begin(), why.end(), '\n', ' ');
  const size_t n = std::min(why.size(), error_size - 1);
  std::memcpy(error, why.data(), n);
  error[n] = '\0';
}

// OIIO keeps an error string per ImageBuf and per thread; one left unread is printed when the
// ImageBuf goes, so every failure reads both.
std::string oiio_error(const OIIO::ImageBuf& buf) {
  std::string why = buf.geterror();
  const std::string global = OIIO::geterror();
  if (why.empty()) why = global;
  return why.empty() ? "unknown OpenImageIO error" : why;
}

template <typename F>
int guarded(char* error, size_t error_size, F&& f) {
  try {
    return f();
  } catch (const std::exception& e) {
    set_error(error, error_size, e.what());
  } catch (...) {
    set_error(error, error_size, "unknown exception in the image plugin");
  }
  return 0;
}

int write_image(const char* path, int width, int height, int channels, const float* pixels,
                int storage, const char* description, const char* compression, char* error,
                size_t error_size) {
  return guarded(error, error_size, [&] {
    if (width <= 0 || height <= 0 || (channels != 1 && channels != 3) || !pixels || !path ||
        (storage != GLRC_IMAGES_UINT8 && storage != GLRC_IMAGES_FLOAT)) {
      set_error(error, error_size, "bad image arguments");
      return 0;
    }
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
    if (channels == 1) spec.channelnames = {"Y"};
    spec.attribute("Software", GLRC_IMAGES_SOFTWARE);
    if (description) spec.attribute("ImageDescription", description);
    if (compression) spec.attribute("compression", compression);
    OIIO::ImageBuf buf(spec);
    const OIIO::TypeDesc stored =
        storage == GLRC_IMAGES_FLOAT ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
    if (!buf.set_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, pixels) || !buf.write(path, stored)) {
      set_error(error, error_size, oiio_error(buf));
      return 0;
    }
    return 1;
  });
}

int text_size(const char* text, int size, const char* font, int* width, int* height, char* error,
              size_t error_size) {
  return guarded(error, error_size, [&] {
    const OIIO::ROI extent = OIIO::ImageBufAlgo::text_size(text, size, font);
    if (!extent.defined()) {
      std::string why = OIIO::geterror();
      set_error(error, error_size, why.empty() ? "cannot measure the text" : why);
      return 0;
    }
    *width = extent.width();
    *height = extent.height();
    return 1;
  });
}

int render_text(float* rgb, int width, int height, int x, int y, const char* text, int size,
                const char* font, const float* colour, int align, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    // Wraps the caller's pixels; render_text draws straight into them.
    OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT), rgb);
    const auto alignx = align == GLRC_IMAGES_LEFT     ? OIIO::ImageBufAlgo::TextAlignX::Left
                        : align == GLRC_IMAGES_CENTRE ? OIIO::ImageBufAlgo::TextAlignX::Center
                                                      : OIIO::ImageBufAlgo::TextAlignX::Right;
    if (!OIIO::ImageBufAlgo::render_text(buf, x, y, text, size, font, {colour, 3}, alignx)) {
      set_error(error, error_size, oiio_error(buf));
      return 0;
    }
    return 1;
  });
}

int font_loads(const char* font) {
  return guarded(nullptr, 0, [&] {
    // text_size loads the face, so it tells whether drawing will work. The lookup failure is
    // not an error of anyone's: drop it.
    const bool ok = OIIO::ImageBufAlgo::text_size("0", 12, font).defined();
    (void)OIIO::geterror();
    return ok ? 1 : 0;
  });
}

constexpr glrc_images_api kApi = {GLRC_IMAGES_ABI_VERSION, write_image, text_size, render_text,
                                  font_loads};

}  // namespace

extern "C" __attribute__((visibility("default"))) const glrc_images_api* glrc_images_entry(void) {
  return &kApi;
}
