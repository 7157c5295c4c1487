// Canvas: the RGB picture a diff image is drawn on before it becomes a PNG. Frames are painted
// upscaled and upright, legends as filled rectangles and text.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace glrc::report {

// Display-referred colour, 0..1 per channel, written to PNG as is.
struct Rgb {
  float r = 0, g = 0, b = 0;
};
Rgb mix(Rgb a, Rgb b, float t);  // a at t = 0, b at t = 1

struct Canvas {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row 0 at the top, 3 floats per pixel

  Canvas(int w, int h, Rgb background);
  void fill(int x, int y, int w, int h, Rgb colour);  // clipped to the canvas
};

// The integer factor that makes a frame about 512 px wide, without making a tall frame huge.
int upscale_factor(int frame_width, int frame_height);

// Paints a frame_width x frame_height frame, each pixel a factor x factor block, with its top
// left corner at (x0, y0). Frame row 0 is the bottom (GL window coordinates), image row 0 the
// top, so frame row y lands on image block row frame_height - 1 - y.
void paint_frame(Canvas& canvas, int x0, int y0, int factor, int frame_width, int frame_height,
                 const std::function<Rgb(int x, int y)>& colour_of);

// Text needs a TrueType font, which OIIO looks up by name in its font search path (the
// OPENIMAGEIO_FONTS variable, then system font folders). Returns the first font of a short list
// that OIIO can load, or nothing: then images are drawn without text.
std::optional<std::string> find_font();

enum class Align { left, centre, right };
// Draws one line of text with its baseline at y, in a smaller size if needed to fit max_width
// pixels (0: no limit), since channel names and counts have no bound. Does nothing without a
// font; a failure to render is swallowed, since a legend without labels is still better than no
// image.
void draw_text(Canvas& canvas, const std::optional<std::string>& font, int x, int y,
               const std::string& text, int size, Rgb colour, Align align = Align::left,
               int max_width = 0);

// Writes the canvas as an 8-bit RGB PNG; throws std::runtime_error naming the file on failure.
void write_png(const Canvas& canvas, const std::filesystem::path& file);

}  // namespace glrc::report
