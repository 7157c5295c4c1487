// The image plugin (image_io/, glrefcheck_images.so): the only code that links OpenImageIO,
// loaded on first use so that a glrefcheck that writes no image starts without OpenImageIO's
// ~260 shared libraries.
#pragma once

#include "image_io/glrc_images.h"

namespace glrc::report {

// The plugin's functions, loading it at the first call and keeping it for the process. Looked
// for in this order: the file $GLRC_IMAGES_PLUGIN names (then nowhere else), then
// glrefcheck_images.so next to the running executable, in <executable's folder>/../lib/glrefcheck/,
// and where this build put it (the build tree). Throws std::runtime_error with one line naming
// every path tried and why each failed (dlerror), or that the plugin found is of another ABI
// version; the same error again on every later call, without a second search. Built with
// GLRC_IMAGES=OFF, always throws that glrefcheck was built without images.
const glrc_images_api& image_plugin();

}  // namespace glrc::report
