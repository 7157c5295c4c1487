#define _POSIX_C_SOURCE 200809L /* setenv */
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- GL: the types, constants and entry points used (OpenGL 3.3 core) ---- */
typedef unsigned int GLenum;
typedef unsigned int GLuint;
typedef int GLint;
typedef int GLsizei;
typedef unsigned char GLboolean;
typedef unsigned char GLubyte;
typedef unsigned short GLushort;
typedef char GLchar;
typedef float GLfloat;
typedef double GLdouble;
typedef ptrdiff_t GLsizeiptr;
typedef void (*gl_proc)(void);

#define GL_NO_ERROR 0
#define GL_FALSE 0
#define GL_TRUE 1
#define GL_ONE 1
#define GL_TRIANGLES 0x0004
#define GL_TRIANGLE_STRIP 0x0005
#define GL_TRIANGLE_FAN 0x0006
#define GL_NEVER 0x0200
#define GL_LESS 0x0201
#define GL_EQUAL 0x0202
#define GL_LEQUAL 0x0203
#define GL_GREATER 0x0204
#define GL_NOTEQUAL 0x0205
#define GL_GEQUAL 0x0206
#define GL_ALWAYS 0x0207
#define GL_CLIP_DISTANCE0 0x3000
#define DISTANCE_LOCATION 8 /* gl_harness/shaders.hpp: kDistanceLocation */
#define GL_LOWER_LEFT 0x8CA1
#define GL_UPPER_LEFT 0x8CA2
#define GL_NEGATIVE_ONE_TO_ONE 0x935E
#define GL_ZERO_TO_ONE 0x935F
#define GL_FRONT 0x0404
#define GL_BACK 0x0405
#define GL_FRONT_AND_BACK 0x0408
#define GL_INVALID_ENUM 0x0500
#define GL_INVALID_VALUE 0x0501
#define GL_INVALID_OPERATION 0x0502
#define GL_OUT_OF_MEMORY 0x0505
#define GL_INVALID_FRAMEBUFFER_OPERATION 0x0506
#define GL_CW 0x0900
#define GL_CCW 0x0901
#define GL_CULL_FACE 0x0B44
#define GL_DEPTH_TEST 0x0B71
#define GL_STENCIL_TEST 0x0B90
#define GL_DITHER 0x0BD0
#define GL_BLEND 0x0BE2
#define GL_SCISSOR_TEST 0x0C11
#define GL_PACK_ALIGNMENT 0x0D05
#define GL_MAX_VIEWPORT_DIMS 0x0D3A
#define GL_SUBPIXEL_BITS 0x0D50
#define GL_UNSIGNED_BYTE 0x1401
#define GL_UNSIGNED_SHORT 0x1403
#define GL_INT 0x1404
#define GL_UNSIGNED_INT 0x1405
#define GL_FLOAT 0x1406
#define GL_COLOR 0x1800
#define GL_DEPTH 0x1801
#define GL_DEPTH_COMPONENT 0x1902
#define GL_RED 0x1903
#define GL_RGBA 0x1908
#define GL_VENDOR 0x1F00
#define GL_RENDERER 0x1F01
#define GL_VERSION 0x1F02
#define GL_EXTENSIONS 0x1F03
#define GL_FUNC_ADD 0x8006
#define GL_POLYGON_OFFSET_FILL 0x8037
#define GL_MULTISAMPLE 0x809D
#define GL_SAMPLE_ALPHA_TO_COVERAGE 0x809E
#define GL_R32F 0x822E
#define GL_RG 0x8227
#define GL_RG32F 0x8230
#define GL_R32I 0x8235
#define GL_MAJOR_VERSION 0x821B
#define GL_MINOR_VERSION 0x821C
#define GL_NUM_EXTENSIONS 0x821D
#define GL_MAX_RENDERBUFFER_SIZE 0x84E8
#define GL_DEPTH_CLAMP 0x864F
#define GL_RGBA32F 0x8814
#define GL_MAX_DRAW_BUFFERS 0x8824
#define GL_ARRAY_BUFFER 0x8892
#define GL_ELEMENT_ARRAY_BUFFER 0x8893
#define GL_STATIC_DRAW 0x88E4
#define GL_CLAMP_READ_COLOR 0x891C
#define GL_FRAGMENT_SHADER 0x8B30
#define GL_VERTEX_SHADER 0x8B31
#define GL_COMPILE_STATUS 0x8B81
#define GL_LINK_STATUS 0x8B82
#define GL_RASTERIZER_DISCARD 0x8C89
#define GL_DEPTH_COMPONENT32F 0x8CAC
#define GL_FRAMEBUFFER_COMPLETE 0x8CD5
#define GL_MAX_COLOR_ATTACHMENTS 0x8CDF
#define GL_COLOR_ATTACHMENT0 0x8CE0
#define GL_DEPTH_ATTACHMENT 0x8D00
#define GL_FRAMEBUFFER 0x8D40
#define GL_RENDERBUFFER 0x8D41
#define GL_RED_INTEGER 0x8D94
#define GL_GEOMETRY_SHADER 0x8DD9
#define GL_FIRST_VERTEX_CONVENTION 0x8E4D
#define GL_LAST_VERTEX_CONVENTION 0x8E4E
#define GL_PRIMITIVE_RESTART 0x8F9D
#define GL_PRIMITIVE_RESTART_FIXED_INDEX 0x8D69

/* X(return type, name without "gl", parameters): every GL function this file calls. */
#define GL_FUNCTIONS(X)                                                                          \
  X(const GLubyte *, GetString, (GLenum name))                                                   \
  X(const GLubyte *, GetStringi, (GLenum name, GLuint index))                                    \
  X(void, GetIntegerv, (GLenum name, GLint * data))                                              \
  X(GLenum, GetError, (void))                                                                    \
  X(GLuint, CreateShader, (GLenum type))                                                         \
  X(void, ShaderSource, (GLuint shader, GLsizei count, const GLchar *const *text, const GLint *length)) \
  X(void, CompileShader, (GLuint shader))                                                        \
  X(void, GetShaderiv, (GLuint shader, GLenum name, GLint * value))                              \
  X(void, GetShaderInfoLog, (GLuint shader, GLsizei size, GLsizei * length, GLchar * log))       \
  X(void, DeleteShader, (GLuint shader))                                                         \
  X(GLuint, CreateProgram, (void))                                                               \
  X(void, AttachShader, (GLuint program, GLuint shader))                                         \
  X(void, LinkProgram, (GLuint program))                                                         \
  X(void, GetProgramiv, (GLuint program, GLenum name, GLint * value))                            \
  X(void, GetProgramInfoLog, (GLuint program, GLsizei size, GLsizei * length, GLchar * log))     \
  X(void, DeleteProgram, (GLuint program))                                                       \
  X(void, UseProgram, (GLuint program))                                                          \
  X(void, GenFramebuffers, (GLsizei n, GLuint * framebuffers))                                   \
  X(void, BindFramebuffer, (GLenum target, GLuint framebuffer))                                  \
  X(void, DeleteFramebuffers, (GLsizei n, const GLuint *framebuffers))                           \
  X(GLenum, CheckFramebufferStatus, (GLenum target))                                             \
  X(void, GenRenderbuffers, (GLsizei n, GLuint * renderbuffers))                                 \
  X(void, BindRenderbuffer, (GLenum target, GLuint renderbuffer))                                \
  X(void, RenderbufferStorage, (GLenum target, GLenum format, GLsizei width, GLsizei height))    \
  X(void, FramebufferRenderbuffer, (GLenum target, GLenum attachment, GLenum rb_target, GLuint rb)) \
  X(void, DeleteRenderbuffers, (GLsizei n, const GLuint *renderbuffers))                         \
  X(void, DrawBuffers, (GLsizei n, const GLenum *buffers))                                       \
  X(void, ReadBuffer, (GLenum buffer))                                                           \
  X(void, ClearBufferfv, (GLenum buffer, GLint draw_buffer, const GLfloat *value))               \
  X(void, ClearBufferiv, (GLenum buffer, GLint draw_buffer, const GLint *value))                 \
  X(void, Viewport, (GLint x, GLint y, GLsizei width, GLsizei height))                           \
  X(void, DepthRange, (GLdouble near_value, GLdouble far_value))                                 \
  X(void, Enable, (GLenum cap))                                                                  \
  X(void, Disable, (GLenum cap))                                                                 \
  X(void, DepthFunc, (GLenum func))                                                              \
  X(void, DepthMask, (GLboolean flag))                                                           \
  X(void, PolygonOffset, (GLfloat factor, GLfloat units))                                        \
  X(void, BlendFunc, (GLenum source, GLenum destination))                                        \
  X(void, BlendEquation, (GLenum mode))                                                          \
  X(void, CullFace, (GLenum mode))                                                               \
  X(void, FrontFace, (GLenum mode))                                                              \
  X(void, ProvokingVertex, (GLenum mode))                                                        \
  X(void, ClampColor, (GLenum target, GLenum clamp))                                             \
  X(void, GenVertexArrays, (GLsizei n, GLuint * arrays))                                         \
  X(void, BindVertexArray, (GLuint array))                                                       \
  X(void, DeleteVertexArrays, (GLsizei n, const GLuint *arrays))                                 \
  X(void, GenBuffers, (GLsizei n, GLuint * buffers))                                             \
  X(void, BindBuffer, (GLenum target, GLuint buffer))                                            \
  X(void, BufferData, (GLenum target, GLsizeiptr size, const void *data, GLenum usage))          \
  X(void, DeleteBuffers, (GLsizei n, const GLuint *buffers))                                     \
  X(void, VertexAttribPointer,                                                                   \
    (GLuint index, GLint size, GLenum type, GLboolean normalized, GLsizei stride, const void *offset)) \
  X(void, EnableVertexAttribArray, (GLuint index))                                               \
  X(void, DrawElements, (GLenum mode, GLsizei count, GLenum type, const void *offset))           \
  X(void, DrawArrays, (GLenum mode, GLint first, GLsizei count))                                 \
  X(void, PrimitiveRestartIndex, (GLuint index))                                                 \
  X(GLint, GetUniformLocation, (GLuint program, const GLchar *name))                             \
  X(void, Uniform1i, (GLint location, GLint value))                                              \
  X(void, Scissor, (GLint x, GLint y, GLsizei width, GLsizei height))                            \
  X(void, PixelStorei, (GLenum name, GLint value))                                               \
  X(void, ReadPixels,                                                                            \
    (GLint x, GLint y, GLsizei width, GLsizei height, GLenum format, GLenum type, void *pixels))

#define DECLARE_GL_FUNCTION(type, name, parameters) \
  typedef type(*pfn_gl##name) parameters;           \
  static pfn_gl##name gl##name;
GL_FUNCTIONS(DECLARE_GL_FUNCTION)
/* GL 4.5 or GL_ARB_clip_control: looked up only for a scene that calls it. */
typedef void (*pfn_glClipControl)(GLenum origin, GLenum depth);
static pfn_glClipControl glClipControl;
/* GL 4.6 or GL_ARB_polygon_offset_clamp (glPolygonOffsetClamp), or GL_EXT_polygon_offset_clamp
   (glPolygonOffsetClampEXT): looked up only for a scene that calls it, by the version and the
   extensions (Mesa gives a stub for a name it lacks). */
typedef void (*pfn_glPolygonOffsetClamp)(GLfloat factor, GLfloat units, GLfloat clamp);
static pfn_glPolygonOffsetClamp glPolygonOffsetClamp;
typedef void (*pfn_glViewportIndexedf)(GLuint index, GLfloat x, GLfloat y, GLfloat w, GLfloat h);
static pfn_glViewportIndexedf glViewportIndexedf;

/* ---- EGL and OSMesa: what making a context needs ---- */
typedef void *EGLDisplay;
typedef void *EGLConfig;
typedef void *EGLContext;
typedef void *EGLSurface;
typedef int32_t EGLint;
typedef unsigned int EGLBoolean;
typedef unsigned int EGLenum;
#define EGL_NONE 0x3038
#define EGL_DONT_CARE (-1)
#define EGL_OPENGL_BIT 0x0008
#define EGL_SURFACE_TYPE 0x3033
#define EGL_RENDERABLE_TYPE 0x3040
#define EGL_VENDOR 0x3053
#define EGL_EXTENSIONS 0x3055
#define EGL_CONTEXT_MAJOR_VERSION 0x3098
#define EGL_OPENGL_API 0x30A2
#define EGL_CONTEXT_MINOR_VERSION 0x30FB
#define EGL_CONTEXT_OPENGL_PROFILE_MASK 0x30FD
#define EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT 0x0001
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD

#define OSMESA_FORMAT 0x22
#define OSMESA_DEPTH_BITS 0x30
#define OSMESA_STENCIL_BITS 0x31
#define OSMESA_ACCUM_BITS 0x32
#define OSMESA_PROFILE 0x33
#define OSMESA_CORE_PROFILE 0x34
#define OSMESA_CONTEXT_MAJOR_VERSION 0x36
#define OSMESA_CONTEXT_MINOR_VERSION 0x37

/* ---- What one draw takes ---- */
/* One draw command: glDrawArrays(mode, first, count) when index_type is 0, else
   glDrawElements(mode, count, index_type, ...) of `indices` (index_bytes bytes), with primitive
   restart `restart` enabled around it (0: none; GL_PRIMITIVE_RESTART with restart_index, or
   GL_PRIMITIVE_RESTART_FIXED_INDEX). primitive_base: the number of triangles the earlier draws
   assemble, which the fragment shader adds to gl_PrimitiveID (uniform primitive_base). */
struct draw {
  GLenum mode, index_type;
  GLint first;
  GLsizei count;
  const void *indices;
  GLsizeiptr index_bytes;
  GLenum restart;
  GLuint restart_index;
  GLint primitive_base;
};
struct scene {
  const char *name;
  int width, height; /* the framebuffer */
  float viewport[4]; /* glViewport(x, y, width, height); glViewportIndexedf where fractional */
  int scissor[5];    /* enabled (0 or 1), then glScissor(x, y, width, height) */
  GLenum clip_control[2]; /* glClipControl(origin, depth); {0, 0}: never called */
  double depth_near, depth_far; /* glDepthRange */
  int depth_clamp;   /* GL_DEPTH_CLAMP enabled (0 or 1) */
  struct {
    int enabled;           /* GL_POLYGON_OFFSET_FILL (0 or 1); 0: the rest unused */
    GLfloat factor, units; /* glPolygonOffset(factor, units)... */
    int clamped;           /* ...or, where 1, glPolygonOffsetClamp(factor, units, clamp) */
    GLfloat clamp;
  } polygon_offset;
  GLenum cull;       /* glCullFace's mode; 0: GL_CULL_FACE disabled */
  GLenum front_face, provoking_vertex, depth_func;
  GLfloat depth_clear; /* glClearDepth */
  int work_arounds;    /* 0: never the geometry shader's work-around for gl_PrimitiveID */
  int varying_count;
  const int *varying_sizes; /* 1 to 4 components each */
  int component_count;      /* the sum of the sizes */
  int distance_count;       /* gl_ClipDistance then gl_CullDistance values per vertex */
  unsigned clip_planes;     /* bit i: GL_CLIP_DISTANCEi enabled */
  int vertex_count;
  const float *vertices;    /* per vertex: clip x, y, z, w, every varying's components, then
                               the distances */
  int draw_count;
  const struct draw *draws;
  const char *vertex_shader, *geometry_shader, *fragment_shader, *fragment_after_geometry;
  /* The fragment-count pass, and the trace pass with its pass-through geometry shader for
     gl_PrimitiveID. */
  const char *count_vertex_shader, *count_geometry_shader, *count_fragment_shader;
  const char *trace_fragment_shader;
};
