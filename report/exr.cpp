#include "report/exr.hpp"

#include <algorithm>
#include <stdexcept>

#include "report/image_plugin.hpp"

namespace glrc::report {

void write_exr(const std::filesystem::path& file, int width, int height,
               const std::vector<float>& values, const std::string& description) {
  if (values.size() != size_t(width) * height)
    throw std::runtime_error("cannot write " + file.string() + ": frame size mismatch");
  std::vector<float> upright(values.size());
  for (int y = 0; y < height; ++y)
    std::copy_n(values.begin() + ptrdiff_t(y) * width, width,
                upright.begin() + ptrdiff_t(height - 1 - y) * width);

  try {
    const glrc_images_api& api = image_plugin();
    char why[512] = "";
    if (!api.write_image(file.c_str(), width, height, 1, upright.data(), GLRC_IMAGES_FLOAT,
                         description.c_str(), "zip", why, sizeof why))
      throw std::runtime_error(why);
  } catch (const std::exception& e) {
    std::string why = e.what();
    std::replace(why.begin(), why.end(), '\n', ' ');
    throw std::runtime_error("cannot write " + file.string() + ": " + why);
  }
}

}  // namespace glrc::report
