// Internal to gl_harness: the GL entry points the renderer uses, as pointers looked up through
// the backend's Context::proc_address. glrefcheck never links a GL library, so no gl* symbol
// is ever called directly.
#pragma once

// Types and enums only: prototypes would invite direct (linked) calls.
#undef GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

namespace glrc::gl {

class Context;

// X(type, name): every function the renderer calls, all in OpenGL 3.3 core. glDepthRange (the
// double version) rather than glDepthRangef, which is only core from 4.1: every float is a
// double exactly, so the range set is the same.
#define GLRC_GL_FUNCTIONS(X)                                   \
  X(PFNGLGETSTRINGPROC, GetString)                             \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                         \
  X(PFNGLGETERRORPROC, GetError)                               \
  X(PFNGLFINISHPROC, Finish)                                   \
  X(PFNGLCREATESHADERPROC, CreateShader)                       \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                       \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                     \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                         \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)               \
  X(PFNGLDELETESHADERPROC, DeleteShader)                       \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                     \
  X(PFNGLATTACHSHADERPROC, AttachShader)                       \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                         \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                       \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)             \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                     \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                           \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                 \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                 \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)           \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)   \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)               \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)               \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)         \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer) \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)         \
  X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                         \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                           \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                     \
  X(PFNGLCLEARBUFFERIVPROC, ClearBufferiv)                     \
  X(PFNGLVIEWPORTPROC, Viewport)                               \
  X(PFNGLDEPTHRANGEPROC, DepthRange)                           \
  X(PFNGLENABLEPROC, Enable)                                   \
  X(PFNGLDISABLEPROC, Disable)                                 \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                             \
  X(PFNGLDEPTHMASKPROC, DepthMask)                             \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                             \
  X(PFNGLBLENDEQUATIONPROC, BlendEquation)                     \
  X(PFNGLCULLFACEPROC, CullFace)                               \
  X(PFNGLFRONTFACEPROC, FrontFace)                             \
  X(PFNGLPROVOKINGVERTEXPROC, ProvokingVertex)                 \
  X(PFNGLCLAMPCOLORPROC, ClampColor)                           \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                 \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)           \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                           \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                           \
  X(PFNGLBUFFERDATAPROC, BufferData)                           \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                     \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)         \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                       \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                           \
  X(PFNGLPRIMITIVERESTARTINDEXPROC, PrimitiveRestartIndex)     \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)           \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                             \
  X(PFNGLSCISSORPROC, Scissor)                                 \
  X(PFNGLGETFLOATVPROC, GetFloatv)                             \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                         \
  X(PFNGLREADPIXELSPROC, ReadPixels)                           \
  X(PFNGLGETSTRINGIPROC, GetStringi)                           \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)

struct GlFunctions {
  // Beyond 3.3 core, loaded where the context has it (GL 4.5 or GL_ARB_clip_control), else
  // null: glClipControl.
  PFNGLCLIPCONTROLPROC ClipControl = nullptr;
  // Likewise glViewportIndexedf (GL 4.1 or GL_ARB_viewport_array): a fractional viewport.
  PFNGLVIEWPORTINDEXEDFPROC ViewportIndexedf = nullptr;
  // Likewise glPolygonOffsetClamp (GL 4.6, GL_ARB_polygon_offset_clamp or
  // GL_EXT_polygon_offset_clamp, whose glPolygonOffsetClampEXT is the same function).
  PFNGLPOLYGONOFFSETCLAMPPROC PolygonOffsetClamp = nullptr;
#define GLRC_GL_FUNCTION_MEMBER(type, name) type name = nullptr;
  GLRC_GL_FUNCTIONS(GLRC_GL_FUNCTION_MEMBER)
#undef GLRC_GL_FUNCTION_MEMBER

  GlFunctions() = default;
  // Looks every entry point up; a missing one throws Unavailable naming it.
  explicit GlFunctions(const Context& context);
};

// "GL_INVALID_OPERATION" etc.
const char* gl_error_name(GLenum error);

}  // namespace glrc::gl
