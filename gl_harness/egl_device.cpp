// Backend "egl-device": one EGLDevice (EGL_EXT_device_enumeration + EGL_EXT_platform_device),
// picked by Target::device_index. The way to reach a GPU's driver (NVIDIA's above all) without
// a window system; Mesa also lists a software device, so llvmpipe/softpipe work here too.
#include <algorithm>
#include <vector>

#include "gl_harness/egl_context.hpp"

namespace glrc::gl {
namespace {

// "0: /dev/dri/card0 (EGL_EXT_device_drm ...)" or "1: software (EGL_MESA_device_software)":
// enough to tell which index is which GPU in a message.
std::string describe_device(const EglLibrary& egl, EGLDeviceEXT device, int index) {
  std::string d = std::to_string(index) + ": ";
  if (!has_extension(egl.client_extensions, "EGL_EXT_device_query") &&
      !has_extension(egl.client_extensions, "EGL_EXT_device_base"))
    return d + "device";
  auto query = egl.extension_function<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT",
                                                                      "EGL_EXT_device_query");
  const char* ext = query(device, EGL_EXTENSIONS);
  std::string_view extensions = ext ? ext : "";
  std::string name;
  if (has_extension(extensions, "EGL_EXT_device_query_name"))
    if (const char* r = query(device, EGL_RENDERER_EXT)) name = r;
  if (name.empty() && has_extension(extensions, "EGL_EXT_device_drm"))
    if (const char* f = query(device, EGL_DRM_DEVICE_FILE_EXT)) name = f;
  if (name.empty() && has_extension(extensions, "EGL_MESA_device_software")) name = "software";
  if (name.empty()) name = "device";
  egl.GetError();  // a query this device does not answer is not an error of ours
  return d + name + " (" + std::string(extensions) + ")";
}

}  // namespace

std::unique_ptr<Context> create_egl_device_context(const Target& t) {
  const EglLibrary& egl = egl_library();
  constexpr const char* kHow =
      "install a current libegl1 (glvnd) and libegl-mesa0, or the GPU vendor's EGL driver";
  // EGL_EXT_device_base is the older name of enumeration + query together.
  if (!has_extension(egl.client_extensions, "EGL_EXT_device_base"))
    require_client_extension(egl, "EGL_EXT_device_enumeration", kHow);
  require_client_extension(egl, "EGL_EXT_platform_base", kHow);
  require_client_extension(egl, "EGL_EXT_platform_device", kHow);
  auto query_devices = egl.extension_function<PFNEGLQUERYDEVICESEXTPROC>(
      "eglQueryDevicesEXT", "EGL_EXT_device_enumeration");
  auto get_platform_display = egl.extension_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      "eglGetPlatformDisplayEXT", "EGL_EXT_platform_base");

  EGLint count = 0;
  if (!query_devices(0, nullptr, &count))
    throw Unavailable(std::string("eglQueryDevicesEXT failed: ") + egl_error_name(egl.GetError()));
  std::vector<EGLDeviceEXT> devices(size_t(std::max(count, 0)));
  if (count > 0 && !query_devices(count, devices.data(), &count))
    throw Unavailable(std::string("eglQueryDevicesEXT failed: ") + egl_error_name(egl.GetError()));
  devices.resize(size_t(std::max(count, 0)));
  if (t.device_index < 0 || size_t(t.device_index) >= devices.size()) {
    std::string listed;
    for (size_t i = 0; i < devices.size(); ++i)
      listed += (i ? "; " : " ") + describe_device(egl, devices[i], int(i));
    throw Unavailable("EGL device " + std::to_string(t.device_index) + " asked for, but " +
                      kEglLibrary + " lists " + std::to_string(devices.size()) + " EGL device(s)" +
                      (listed.empty() ? "" : ":" + listed) + "; pick another device index or " +
                      kHow);
  }
  EGLDeviceEXT device = devices[size_t(t.device_index)];
  std::string platform = "EGL device " + describe_device(egl, device, t.device_index);
  EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
  if (display == EGL_NO_DISPLAY)
    throw Unavailable("eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT) failed for " + platform +
                      ": " + egl_error_name(egl.GetError()));
  return create_egl_context(egl, display, platform);
}

}  // namespace glrc::gl
