#include "report/canvas.hpp"

#include <algorithm>
#include <stdexcept>

#include "report/image_plugin.hpp"

namespace glrc::report {
namespace {

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

std::optional<std::string> find_font() {
  const glrc_images_api* api = nullptr;
  try {
    api = &image_plugin();
  } catch (const std::exception&) {
    return std::nullopt;  // write_png says why, once per image
  }
  // DejaVu ships with most Linux desktops (Debian: fonts-dejavu-core); OIIO's own default font
  // is often missing.
  for (const char* name :
       {"DejaVuSans", "DejaVuSansMono", "LiberationSans-Regular", "FreeSans", "Arial"}) {
    if (api->font_loads(name)) return std::string(name);
  }
  return std::nullopt;
}

void draw_text(Canvas& canvas, const std::optional<std::string>& font, int x, int y,
               const std::string& text, int size, Rgb colour, Align align, int max_width) {
  if (!font || text.empty()) return;
  // A font was found, so the plugin is loaded.
  const glrc_images_api& api = image_plugin();
  if (max_width > 0) {
    constexpr int kSmallestReadable = 8;
    int width = 0, height = 0;
    if (api.text_size(text.c_str(), size, font->c_str(), &width, &height, nullptr, 0) &&
        width > max_width)
      size = std::max(kSmallestReadable, size * max_width / width);
  }
  const float c[3] = {colour.r, colour.g, colour.b};
  const int alignx = align == Align::left     ? GLRC_IMAGES_LEFT
                     : align == Align::centre ? GLRC_IMAGES_CENTRE
                                              : GLRC_IMAGES_RIGHT;
  (void)api.render_text(canvas.rgb.data(), canvas.width, canvas.height, x, y, text.c_str(), size,
                        font->c_str(), c, alignx, nullptr, 0);
}

void write_png(const Canvas& canvas, const std::filesystem::path& file) {
  try {
    const glrc_images_api& api = image_plugin();
    char why[512] = "";
    if (!api.write_image(file.c_str(), canvas.width, canvas.height, 3, canvas.rgb.data(),
                         GLRC_IMAGES_UINT8, nullptr, nullptr, why, sizeof why))
      throw std::runtime_error(why);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write " + file.string() + ": " + one_line(e.what()));
  }
}

}  // namespace glrc::report
