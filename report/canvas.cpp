#include "report/canvas.hpp"

#include <algorithm>
#include <stdexcept>

#if GLRC_IMAGES
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#endif

namespace glrc::report {
namespace {

#if GLRC_IMAGES
OIIO::ImageSpec rgb_spec(const Canvas& canvas) {
  return OIIO::ImageSpec(canvas.width, canvas.height, 3, OIIO::TypeDesc::FLOAT);
}
#endif

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

}  // namespace

Rgb mix(Rgb a, Rgb b, float t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

Canvas::Canvas(int w, int h, Rgb background) : width(w), height(h), rgb(size_t(w) * h * 3) {
  fill(0, 0, w, h, background);
}

void Canvas::fill(int x, int y, int w, int h, Rgb colour) {
  const int x1 = std::min(x + w, width), y1 = std::min(y + h, height);
  for (int row = std::max(y, 0); row < y1; ++row)
    for (int col = std::max(x, 0); col < x1; ++col) {
      float* p = &rgb[(size_t(row) * width + col) * 3];
      p[0] = colour.r;
      p[1] = colour.g;
      p[2] = colour.b;
    }
}

int upscale_factor(int frame_width, int frame_height) {
  constexpr int kTargetWidth = 512, kMaxHeight = 4096;
  if (frame_width <= 0 || frame_height <= 0) return 1;
  const int wanted = (kTargetWidth + frame_width - 1) / frame_width;
  return std::max(1, std::min(wanted, kMaxHeight / frame_height));
}

void paint_frame(Canvas& canvas, int x0, int y0, int factor, int frame_width, int frame_height,
                 const std::function<Rgb(int x, int y)>& colour_of) {
  for (int y = 0; y < frame_height; ++y)
    for (int x = 0; x < frame_width; ++x)
      canvas.fill(x0 + x * factor, y0 + (frame_height - 1 - y) * factor, factor, factor,
                  colour_of(x, y));
}

#if GLRC_IMAGES
std::optional<std::string> find_font() {
  // DejaVu ships with most Linux desktops (Debian: fonts-dejavu-core); OIIO's own default font
  // is often missing. text_size loads the face, so it tells whether drawing will work.
  for (const char* name :
       {"DejaVuSans", "DejaVuSansMono", "LiberationSans-Regular", "FreeSans", "Arial"}) {
    if (OIIO::ImageBufAlgo::text_size("0", 12, name).defined()) {
      (void)OIIO::geterror();
      return std::string(name);
    }
  }
  (void)OIIO::geterror();  // drop the lookup failures, which are not errors of ours
  return std::nullopt;
}

void draw_text(Canvas& canvas, const std::optional<std::string>& font, int x, int y,
               const std::string& text, int size, Rgb colour, Align align, int max_width) {
  if (!font || text.empty()) return;
  if (max_width > 0) {
    constexpr int kSmallestReadable = 8;
    const OIIO::ROI extent = OIIO::ImageBufAlgo::text_size(text, size, *font);
    if (extent.defined() && extent.width() > max_width)
      size = std::max(kSmallestReadable, size * max_width / extent.width());
  }
  // Wraps the canvas pixels; render_text draws straight into them.
  OIIO::ImageBuf buf(rgb_spec(canvas), canvas.rgb.data());
  const float c[3] = {colour.r, colour.g, colour.b};
  const auto alignx = align == Align::left     ? OIIO::ImageBufAlgo::TextAlignX::Left
                      : align == Align::centre ? OIIO::ImageBufAlgo::TextAlignX::Center
                                               : OIIO::ImageBufAlgo::TextAlignX::Right;
  if (!OIIO::ImageBufAlgo::render_text(buf, x, y, text, size, *font, c, alignx)) {
    (void)buf.geterror();
    (void)OIIO::geterror();
  }
}

void write_png(const Canvas& canvas, const std::filesystem::path& file) {
  OIIO::ImageBuf buf(rgb_spec(canvas));
  if (!buf.set_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, canvas.rgb.data()) ||
      !buf.write(file.string(), OIIO::TypeDesc::UINT8)) {
    std::string why = buf.geterror();
    if (why.empty()) why = OIIO::geterror();
    throw std::runtime_error("cannot write " + file.string() + ": " + one_line(why));
  }
}
#else
// Built without OpenImageIO (GLRC_IMAGES=OFF): a lean glrefcheck that checks and reports in
// text, JSON and CSV, and refuses to write images.
std::optional<std::string> find_font() {
  return std::nullopt;
}
void draw_text(Canvas&, const std::optional<std::string>&, int, int, const std::string&, int, Rgb,
               Align, int) {}
void write_png(const Canvas&, const std::filesystem::path& file) {
  throw std::runtime_error("cannot write " + file.string() +
                           ": glrefcheck was built without OpenImageIO (GLRC_IMAGES=OFF)");
}
#endif

}  // namespace glrc::report
