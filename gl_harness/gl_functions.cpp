#include "gl_harness/gl_functions.hpp"

#include <string>

#include "gl_harness/context.hpp"

namespace glrc::gl {

GlFunctions::GlFunctions(const Context& context) {
  auto load = [&context](auto& fn, const char* name) {
    void* p = context.proc_address(name);
    if (!p)
      throw Unavailable(std::string("GL entry point ") + name + " not found on " +
                        context.describe() + "; glrefcheck needs OpenGL 3.3 core");
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(p);
  };
#define GLRC_GL_FUNCTION_LOAD(type, name) load(name, "gl" #name);
  GLRC_GL_FUNCTIONS(GLRC_GL_FUNCTION_LOAD)
#undef GLRC_GL_FUNCTION_LOAD
}

const char* gl_error_name(GLenum error) {
  switch (error) {
    case GL_NO_ERROR:
      return "GL_NO_ERROR";
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
  }
  return "unknown GL error";
}

}  // namespace glrc::gl
