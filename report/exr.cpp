#include "report/exr.hpp"

#include <algorithm>
#include <stdexcept>

#if GLRC_IMAGES
#include <OpenImageIO/imagebuf.h>
#endif

namespace glrc::report {

void write_exr(const std::filesystem::path& file, int width, int height,
               const std::vector<float>& values, const std::string& description) {
  if (values.size() != size_t(width) * height)
    throw std::runtime_error("cannot write " + file.string() + ": frame size mismatch");
  std::vector<float> upright(values.size());
  for (int y = 0; y < height; ++y)
    std::copy_n(values.begin() + ptrdiff_t(y) * width, width,
                upright.begin() + ptrdiff_t(height - 1 - y) * width);

#if GLRC_IMAGES
  OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"Y"};
  spec.attribute("ImageDescription", description);
  spec.attribute("compression", "zip");
  OIIO::ImageBuf buf(spec);
  if (!buf.set_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, upright.data()) ||
      !buf.write(file.string(), OIIO::TypeDesc::FLOAT)) {
    std::string why = buf.geterror();
    if (why.empty()) why = OIIO::geterror();
    std::replace(why.begin(), why.end(), '\n', ' ');
    throw std::runtime_error("cannot write " + file.string() + ": " + why);
  }
#else
  (void)description;
  throw std::runtime_error("cannot write " + file.string() +
                           ": glrefcheck was built without OpenImageIO (GLRC_IMAGES=OFF)");
#endif
}

}  // namespace glrc::report
