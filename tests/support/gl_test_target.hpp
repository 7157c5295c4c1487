// The GL target of a GL test binary, from the environment: Mesa picks its driver once per
// process, so ctest runs the same binary once per backend and driver.
//   GLRC_TEST_BACKEND = osmesa (default) | egl | egl-device
//   GLRC_TEST_DRIVER  = llvmpipe (default) | softpipe | "" (set but empty: the platform's own)
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

#include "gl_harness/gl_harness.hpp"

namespace glrc::test {

// A misspelt backend sets `error`, so that every renderer test fails with that message rather
// than quietly testing osmesa.
inline gl::Target gl_test_target(std::string& error) {
  gl::Target t;
  const char* backend = std::getenv("GLRC_TEST_BACKEND");
  if (std::optional<gl::Backend> b = gl::backend_from_string(backend ? backend : "osmesa"))
    t.backend = *b;
  else
    error = "GLRC_TEST_BACKEND='" + std::string(backend) + "' is not osmesa, egl or egl-device";
  if (const char* driver = std::getenv("GLRC_TEST_DRIVER")) t.driver = driver;
  return t;
}

}  // namespace glrc::test
