// A stand-in for a glrefcheck_images.so left from an older build: the entry point is there, the
// ABI version is not this build's. The loader must refuse it by name, not call into it.
#include "image_io/glrc_images.h"

namespace {
constexpr glrc_images_api kStale = {GLRC_IMAGES_ABI_VERSION - 1, nullptr, nullptr, nullptr,
                                    nullptr};
}

extern "C" __attribute__((visibility("default"))) const glrc_images_api* glrc_images_entry(void) {
  return &kStale;
}
