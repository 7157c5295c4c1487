
/* ---- Making a context ---- */
static gl_proc (*get_proc_address)(const char *name);
static char platform[256];
static char error_text[2048]; /* why the last draw failed */

static int no_gl(const char *format, ...) {
  va_list a;
  fprintf(stderr, "%s: no GL: ", CASE_NAME);
  va_start(a, format);
  vfprintf(stderr, format, a);
  va_end(a);
  fputc('\n', stderr);
  return 2;
}

static void set_error(const char *format, ...) {
  va_list a;
  va_start(a, format);
  vsnprintf(error_text, sizeof error_text, format, a);
  va_end(a);
}

/* Whether the space-separated list has `name` as a whole word. */
static int has_extension(const char *list, const char *name) {
  size_t n = strlen(name);
  const char *p = list;
  while (list && (p = strstr(p, name)) != NULL) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
    p += n;
  }
  return 0;
}

/* A library's function as a pointer of its own type (POSIX: a function's address fits a void *). */
#define LIBRARY_FUNCTION(table, field, library, library_name, name)                          \
  do {                                                                                    \
    void *address_ = dlsym(library, name);                                                \
    if (!address_) return no_gl("%s has no %s: install a current Mesa", library_name, name); \
    memcpy(&table.field, &address_, sizeof address_);                                    \
  } while (0)

static struct {
  gl_proc (*GetProcAddress)(const char *name);
  EGLint (*GetError)(void);
  const char *(*QueryString)(EGLDisplay display, EGLint name);
  EGLBoolean (*Initialize)(EGLDisplay display, EGLint *major, EGLint *minor);
  EGLBoolean (*BindAPI)(EGLenum api);
  EGLBoolean (*ChooseConfig)(EGLDisplay display, const EGLint *attributes, EGLConfig *configs,
                             EGLint size, EGLint *count);
  EGLContext (*CreateContext)(EGLDisplay display, EGLConfig config, EGLContext share,
                              const EGLint *attributes);
  EGLBoolean (*MakeCurrent)(EGLDisplay display, EGLSurface draw, EGLSurface read,
                            EGLContext context);
} egl;

/* Mesa's surfaceless EGL platform, an OpenGL 3.3 core context current without a surface: what
   glrefcheck's --backend egl makes. */
static int open_egl(void) {
  static const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3,
                                              EGL_CONTEXT_MINOR_VERSION, 3,
                                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  static const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                             EGL_DONT_CARE, EGL_NONE};
  const char *driver = getenv("GALLIUM_DRIVER"), *client, *extensions, *vendor;
  EGLDisplay (*get_platform_display)(EGLenum platform, void *native, const EGLint *attributes);
  EGLDisplay display;
  EGLConfig config = NULL;
  EGLContext context;
  EGLint major = 0, minor = 0, count = 0;
  void *library;
  /* As glrefcheck does: without it Mesa tries hardware drivers first, and zink needs it to pick
     a CPU Vulkan device (lavapipe). */
  if (driver && (!strcmp(driver, "llvmpipe") || !strcmp(driver, "softpipe") || !strcmp(driver, "zink")))
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
  library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
  if (!library)
    return no_gl("libEGL.so.1 not found (%s): install libegl1 and libegl-mesa0", dlerror());
  LIBRARY_FUNCTION(egl, GetProcAddress, library, "libEGL.so.1", "eglGetProcAddress");
  LIBRARY_FUNCTION(egl, GetError, library, "libEGL.so.1", "eglGetError");
  LIBRARY_FUNCTION(egl, QueryString, library, "libEGL.so.1", "eglQueryString");
  LIBRARY_FUNCTION(egl, Initialize, library, "libEGL.so.1", "eglInitialize");
  LIBRARY_FUNCTION(egl, BindAPI, library, "libEGL.so.1", "eglBindAPI");
  LIBRARY_FUNCTION(egl, ChooseConfig, library, "libEGL.so.1", "eglChooseConfig");
  LIBRARY_FUNCTION(egl, CreateContext, library, "libEGL.so.1", "eglCreateContext");
  LIBRARY_FUNCTION(egl, MakeCurrent, library, "libEGL.so.1", "eglMakeCurrent");
  client = egl.QueryString(NULL, EGL_EXTENSIONS);
  if (!client || !has_extension(client, "EGL_EXT_platform_base") ||
      !has_extension(client, "EGL_MESA_platform_surfaceless"))
    return no_gl("libEGL.so.1 has no EGL_MESA_platform_surfaceless: install libegl-mesa0");
  get_platform_display = (EGLDisplay(*)(EGLenum, void *, const EGLint *))egl.GetProcAddress(
      "eglGetPlatformDisplayEXT");
  if (!get_platform_display) return no_gl("libEGL.so.1 has no eglGetPlatformDisplayEXT");
  display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, NULL, NULL);
  if (!display)
    return no_gl("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) failed: EGL error 0x%04X",
                 (unsigned)egl.GetError());
  if (!egl.Initialize(display, &major, &minor))
    return no_gl("eglInitialize failed on the surfaceless platform: EGL error 0x%04X%s%s%s",
                 (unsigned)egl.GetError(), driver ? " (is GALLIUM_DRIVER=" : "",
                 driver ? driver : "", driver ? " a gallium driver of this Mesa?)" : "");
  extensions = egl.QueryString(display, EGL_EXTENSIONS);
  if (!extensions || !has_extension(extensions, "EGL_KHR_surfaceless_context"))
    return no_gl("the surfaceless EGL display has no EGL_KHR_surfaceless_context");
  if (major == 1 && minor < 5 && !has_extension(extensions, "EGL_KHR_create_context"))
    return no_gl("EGL %d.%d without EGL_KHR_create_context: no core profile context", major, minor);
  if (!egl.BindAPI(EGL_OPENGL_API))
    return no_gl("eglBindAPI(EGL_OPENGL_API) failed: EGL error 0x%04X", (unsigned)egl.GetError());
  /* No surface is ever made, so no config is needed where the display allows that. */
  if (!has_extension(extensions, "EGL_KHR_no_config_context") &&
      (!egl.ChooseConfig(display, config_attributes, &config, 1, &count) || count < 1))
    return no_gl("no EGLConfig with EGL_OPENGL_BIT: EGL error 0x%04X", (unsigned)egl.GetError());
  context = egl.CreateContext(display, config, NULL, context_attributes);
  if (!context)
    return no_gl("eglCreateContext refused an OpenGL 3.3 core context: EGL error 0x%04X",
                 (unsigned)egl.GetError());
  if (!egl.MakeCurrent(display, NULL, NULL, context))
    return no_gl("eglMakeCurrent without a surface failed: EGL error 0x%04X",
                 (unsigned)egl.GetError());
  vendor = egl.QueryString(display, EGL_VENDOR);
  snprintf(platform, sizeof platform, "egl: EGL surfaceless platform (EGL %d.%d, %s)", major,
           minor, vendor ? vendor : "unknown vendor");
  get_proc_address = egl.GetProcAddress;
  return 0;
}

static struct {
  void *(*CreateContextAttribs)(const int *attributes, void *share);
  GLboolean (*MakeCurrent)(void *context, void *buffer, GLenum type, GLsizei width, GLsizei height);
  gl_proc (*GetProcAddress)(const char *name);
} osmesa;

/* Mesa's off-screen library, an OpenGL 3.3 core context with no buffers of its own (everything
   is drawn into framebuffer objects): what glrefcheck's --backend osmesa makes. */
static int open_osmesa(void) {
  static const int attributes[] = {OSMESA_FORMAT, GL_RGBA, OSMESA_DEPTH_BITS, 0,
                                   OSMESA_STENCIL_BITS, 0, OSMESA_ACCUM_BITS, 0,
                                   OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                                   OSMESA_CONTEXT_MAJOR_VERSION, 3,
                                   OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  static unsigned char pixel[4]; /* OSMesa binds a colour buffer; 1x1 is enough */
  const char *driver = getenv("GALLIUM_DRIVER");
  void *library, *context;
  /* Asked for another driver, Mesa 22.3 crashes in OSMesaCreateContextAttribs. */
  if (driver && *driver && strcmp(driver, "llvmpipe") && strcmp(driver, "softpipe"))
    return no_gl("OSMesa runs llvmpipe and softpipe only, GALLIUM_DRIVER is %s: use egl", driver);
  library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
  if (!library) library = dlopen("libOSMesa.so.6", RTLD_NOW | RTLD_LOCAL);
  if (!library)
    return no_gl("libOSMesa.so.8 not found (%s): install libosmesa6, or use egl", dlerror());
  LIBRARY_FUNCTION(osmesa, CreateContextAttribs, library, "libOSMesa", "OSMesaCreateContextAttribs");
  LIBRARY_FUNCTION(osmesa, MakeCurrent, library, "libOSMesa", "OSMesaMakeCurrent");
  LIBRARY_FUNCTION(osmesa, GetProcAddress, library, "libOSMesa", "OSMesaGetProcAddress");
  context = osmesa.CreateContextAttribs(attributes, NULL);
  if (!context)
    return no_gl("OSMesaCreateContextAttribs refused an OpenGL 3.3 core context; the driver "
                 "(GALLIUM_DRIVER) may be missing from this Mesa build");
  if (!osmesa.MakeCurrent(context, pixel, GL_UNSIGNED_BYTE, 1, 1))
    return no_gl("OSMesaMakeCurrent failed");
  snprintf(platform, sizeof platform, "osmesa: OSMesa");
  get_proc_address = osmesa.GetProcAddress;
  return 0;
}

static int load_gl(void) {
#define LOAD_GL_FUNCTION(type, name, parameters)                      \
  gl##name = (pfn_gl##name)get_proc_address("gl" #name);              \
  if (!gl##name) return no_gl("the GL context has no gl" #name);
  GL_FUNCTIONS(LOAD_GL_FUNCTION)
  return 0;
}

/* ---- Drawing as glrefcheck's GL harness does ---- */
struct frame {
  int32_t *primitive; /* gl_PrimitiveID; -1 where nothing was drawn */
  float *depth;       /* 1 where nothing was drawn */
  float *values;      /* component k of pixel i at values[k * pixels + i] */
  float *fragments;   /* fragments rasterized, depth test or not (the counting pass) */
  float *traces;      /* per pixel: the sums of p + 1 and of the hash of p over them */
};

static const char *gl_error_name(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
  }
  return "a GL error";
}

static int gl_ok(const char *when) {
  GLenum e = glGetError();
  if (e == GL_NO_ERROR) return 1;
  set_error("%s (0x%04X) while %s", gl_error_name(e), e, when);
  return 0;
}

static GLuint compile_shader(GLenum stage, const char *source) {
  GLint ok = GL_FALSE;
  GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, NULL);
  glCompileShader(shader);
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = "";
    glGetShaderInfoLog(shader, sizeof log, NULL, log);
    set_error("%s shader does not compile: %s",
              stage == GL_VERTEX_SHADER ? "vertex" : stage == GL_GEOMETRY_SHADER ? "geometry"
                                                                                   : "fragment",
              log);
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

/* A program of the given shader sources (NULL ones skipped), or 0. */
static GLuint make_program(const char *vertex, const char *geometry, const char *fragment) {
  const char *sources[3];
  const GLenum stages[3] = {GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER};
  GLuint shaders[3] = {0, 0, 0}, program = 0;
  GLint ok = GL_FALSE;
  int k;
  sources[0] = vertex, sources[1] = geometry, sources[2] = fragment;
  for (k = 0; k < 3; ++k)
    if (sources[k] && !(shaders[k] = compile_shader(stages[k], sources[k]))) goto done;
  program = glCreateProgram();
  for (k = 0; k < 3; ++k)
    if (shaders[k]) glAttachShader(program, shaders[k]);
  glLinkProgram(program);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[1024] = "";
    glGetProgramInfoLog(program, sizeof log, NULL, log);
    set_error("program does not link: %s", log);
    glDeleteProgram(program);
    program = 0;
  }
done:
  for (k = 0; k < 3; ++k)
    if (shaders[k]) glDeleteShader(shaders[k]);
  return program;
}

/* A framebuffer of `colours` colour renderbuffers (formats[k] at attachment k, all drawn to)
   and a 32-bit float depth renderbuffer: the harness's layout. */
static GLuint make_framebuffer(int width, int height, int colours, const GLenum *formats,
                               GLuint *renderbuffers) {
  GLenum draw_buffers[16], error, status;
  GLuint framebuffer = 0;
  int k;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glGenRenderbuffers(colours + 1, renderbuffers);
  for (k = 0; k <= colours; ++k) {
    const GLenum attachment = k < colours ? GL_COLOR_ATTACHMENT0 + k : GL_DEPTH_ATTACHMENT;
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[k]);
    glRenderbufferStorage(GL_RENDERBUFFER, k < colours ? formats[k] : GL_DEPTH_COMPONENT32F,
                          width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, renderbuffers[k]);
    if (k < colours) draw_buffers[k] = attachment;
  }
  glDrawBuffers(colours, draw_buffers);
  error = glGetError();
  status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (error == GL_NO_ERROR && status == GL_FRAMEBUFFER_COMPLETE) return framebuffer;
  if (error != GL_NO_ERROR)
    set_error("%s while creating the framebuffer", gl_error_name(error));
  else
    set_error("framebuffer incomplete: status 0x%04X", status);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteRenderbuffers(colours + 1, renderbuffers);
  return 0;
}

static GLint gl_integer(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

/* Whether the context lists extension `name` (glGetStringi: a core context has no list in one
   string). */
static int gl_extension(const char *name) {
  const GLint count = gl_integer(GL_NUM_EXTENSIONS);
  GLint k;
  for (k = 0; k < count; ++k) {
    const GLubyte *extension = glGetStringi(GL_EXTENSIONS, (GLuint)k);
    if (extension && !strcmp((const char *)extension, name)) return 1;
  }
  return 0;
}

/* The scene's draws, in order, with `program` in use: each indexed one's indices given to the
   bound element buffer, its primitive restart on around it, and the program's uniform
   primitive_base (where it has one) set to the draw's first triangle. */
static void draw_all(const struct scene *s, GLuint program) {
  const GLint base = glGetUniformLocation(program, "primitive_base");
  int d;
  for (d = 0; d < s->draw_count; ++d) {
    const struct draw *draw = &s->draws[d];
    if (base >= 0) glUniform1i(base, draw->primitive_base);
    if (!draw->index_type) {
      glDrawArrays(draw->mode, draw->first, draw->count);
      continue;
    }
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, draw->index_bytes, draw->indices, GL_STATIC_DRAW);
    if (draw->restart) glEnable(draw->restart);
    if (draw->restart == GL_PRIMITIVE_RESTART) glPrimitiveRestartIndex(draw->restart_index);
    glDrawElements(draw->mode, draw->count, draw->index_type, (const void *)0);
    if (draw->restart) glDisable(draw->restart);
  }
}

/* Draws scene `s` (with the pass-through geometry shader when `geometry_shader`), then counts
   its fragments, and reads both back into `f`. 0 with error_text set when GL refuses. */
/* `count_geometry_shader`: the counting pass reads gl_PrimitiveID through the pass-through
   geometry shader (where the first draw needs it, whatever the case's work_arounds). */
static int draw_scene(const struct scene *s, int geometry_shader, int count_geometry_shader,
                      struct frame *f) {
  static const GLenum caps_off[] = {GL_DITHER, GL_BLEND, GL_MULTISAMPLE, GL_SCISSOR_TEST,
                                    GL_STENCIL_TEST, GL_SAMPLE_ALPHA_TO_COVERAGE,
                                    GL_RASTERIZER_DISCARD, GL_PRIMITIVE_RESTART};
  static const GLfloat zero[4] = {0, 0, 0, 0};
  static const GLint no_primitive[4] = {-1, 0, 0, 0};
  const int n = s->varying_count, w = s->width, h = s->height;
  const size_t pixels = (size_t)w * (size_t)h;
  const GLsizei stride =
      (GLsizei)((4 + s->component_count + s->distance_count) * sizeof(float));
  GLenum formats[9], count_formats[2] = {GL_R32F, GL_RG32F};
  GLuint program = 0, count_program = 0, trace_program = 0, framebuffer = 0, count_framebuffer = 0;
  GLuint renderbuffers[10], count_renderbuffers[3], vertex_array = 0, buffers[2] = {0, 0};
  GLint dims[2] = {0, 0};
  float *rgba = NULL;
  size_t i, offset = 4;
  int k, j, component = 0, ok = 0, limit, fractional = 0;
  for (k = 0; k < 100 && glGetError() != GL_NO_ERROR; ++k) {
    /* errors an earlier draw left are not this one's */
  }
  /* What GL would refuse or misread, said plainly first. */
  limit = gl_integer(GL_MAX_DRAW_BUFFERS);
  if (gl_integer(GL_MAX_COLOR_ATTACHMENTS) < limit) limit = gl_integer(GL_MAX_COLOR_ATTACHMENTS);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
  if (n + 1 > limit || n > 8) {
    set_error("%d varyings need %d draw buffers; this GL has %d", n, n + 1, limit);
    return 0;
  }
  if (w > gl_integer(GL_MAX_RENDERBUFFER_SIZE) || h > gl_integer(GL_MAX_RENDERBUFFER_SIZE)) {
    set_error("framebuffer %dx%d beyond GL_MAX_RENDERBUFFER_SIZE %d", w, h,
              gl_integer(GL_MAX_RENDERBUFFER_SIZE));
    return 0;
  }
  if (s->viewport[2] > (float)dims[0] || s->viewport[3] > (float)dims[1]) {
    set_error("viewport %gx%g beyond GL_MAX_VIEWPORT_DIMS %dx%d", s->viewport[2], s->viewport[3],
              dims[0], dims[1]);
    return 0;
  }
  for (k = 0; k < 4; ++k)
    fractional = fractional || s->viewport[k] != (float)(long)s->viewport[k];
  if (fractional && !glViewportIndexedf &&
      !(glViewportIndexedf = (pfn_glViewportIndexedf)get_proc_address("glViewportIndexedf"))) {
    set_error("the GL context has no glViewportIndexedf (GL 4.1 or GL_ARB_viewport_array) for a "
              "fractional viewport");
    return 0;
  }
  if (s->clip_control[0] && !glClipControl &&
      !(glClipControl = (pfn_glClipControl)get_proc_address("glClipControl"))) {
    set_error("the GL context has no glClipControl (GL 4.5 or GL_ARB_clip_control)");
    return 0;
  }
  if (s->polygon_offset.clamped && !glPolygonOffsetClamp) {
    /* The name GL 4.6 or an extension gives, as the harness looks it up: Mesa answers a name it
       lacks with a stub that fails. */
    const char *name = NULL;
    if (gl_integer(GL_MAJOR_VERSION) * 10 + gl_integer(GL_MINOR_VERSION) >= 46 ||
        gl_extension("GL_ARB_polygon_offset_clamp"))
      name = "glPolygonOffsetClamp";
    else if (gl_extension("GL_EXT_polygon_offset_clamp"))
      name = "glPolygonOffsetClampEXT";
    if (name) glPolygonOffsetClamp = (pfn_glPolygonOffsetClamp)get_proc_address(name);
    if (!glPolygonOffsetClamp) {
      set_error("the GL context has no glPolygonOffsetClamp (GL 4.6, GL_ARB_polygon_offset_clamp "
                "or GL_EXT_polygon_offset_clamp)");
      return 0;
    }
  }

  program = make_program(s->vertex_shader, geometry_shader ? s->geometry_shader : NULL,
                         geometry_shader ? s->fragment_after_geometry : s->fragment_shader);
  if (!program) goto done;
  glUseProgram(program);
  /* One RGBA32F attachment per varying (unused components 0), then gl_PrimitiveID in R32I. */
  for (k = 0; k < n; ++k) formats[k] = GL_RGBA32F;
  formats[n] = GL_R32I;
  if (!(framebuffer = make_framebuffer(w, h, n + 1, formats, renderbuffers))) goto done;

  /* The state the case controls; nothing else may touch a value on its way to the readback. */
  if (fractional)
    glViewportIndexedf(0, s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
  else
    glViewport((GLint)s->viewport[0], (GLint)s->viewport[1], (GLsizei)s->viewport[2],
               (GLsizei)s->viewport[3]);
  glDepthRange(s->depth_near, s->depth_far);
  if (s->clip_control[0]) glClipControl(s->clip_control[0], s->clip_control[1]);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(s->depth_func);
  glDepthMask(GL_TRUE);
  if (s->cull) {
    glEnable(GL_CULL_FACE);
    glCullFace(s->cull);
  } else {
    glDisable(GL_CULL_FACE);
  }
  glFrontFace(s->front_face);
  for (k = 0; k < 8; ++k) {
    if (s->clip_planes >> k & 1u)
      glEnable((GLenum)(GL_CLIP_DISTANCE0 + k));
    else
      glDisable((GLenum)(GL_CLIP_DISTANCE0 + k));
  }
  glProvokingVertex(s->provoking_vertex);
  /* Both stay on for the fragment-count pass, as in the harness: under GL_DEPTH_CLAMP the near
     and far planes clip nothing there either. */
  if (s->depth_clamp)
    glEnable(GL_DEPTH_CLAMP);
  else
    glDisable(GL_DEPTH_CLAMP);
  if (s->polygon_offset.enabled) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    if (s->polygon_offset.clamped)
      glPolygonOffsetClamp(s->polygon_offset.factor, s->polygon_offset.units,
                           s->polygon_offset.clamp);
    else
      glPolygonOffset(s->polygon_offset.factor, s->polygon_offset.units);
  } else {
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  for (k = 0; k < (int)(sizeof caps_off / sizeof caps_off[0]); ++k) glDisable(caps_off[k]);
  glClampColor(GL_CLAMP_READ_COLOR, GL_FALSE);

  for (k = 0; k < n; ++k) glClearBufferfv(GL_COLOR, k, zero);
  glClearBufferiv(GL_COLOR, n, no_primitive);
  glClearBufferfv(GL_DEPTH, 0, &s->depth_clear);
  /* The scissor test after the clears, which it would cut. */
  if (s->scissor[0]) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(s->scissor[1], s->scissor[2], s->scissor[3], s->scissor[4]);
  }

  /* Interleaved: clip coordinates (attribute 0), each varying (attribute k + 1), then each
     distance (attribute DISTANCE_LOCATION + k). */
  glGenVertexArrays(1, &vertex_array);
  glBindVertexArray(vertex_array);
  glGenBuffers(2, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(s->vertex_count * stride), s->vertices,
               GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[1]);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride, (const void *)0);
  for (k = 0; k < n; ++k) {
    glEnableVertexAttribArray((GLuint)(k + 1));
    glVertexAttribPointer((GLuint)(k + 1), s->varying_sizes[k], GL_FLOAT, GL_FALSE, stride,
                          (const void *)(offset * sizeof(float)));
    offset += (size_t)s->varying_sizes[k];
  }
  for (k = 0; k < s->distance_count; ++k) {
    glEnableVertexAttribArray((GLuint)(DISTANCE_LOCATION + k));
    glVertexAttribPointer((GLuint)(DISTANCE_LOCATION + k), 1, GL_FLOAT, GL_FALSE, stride,
                          (const void *)((offset + (size_t)k) * sizeof(float)));
  }
  draw_all(s, program);
  if (!gl_ok("drawing")) goto done;

  /* The same triangles again, positions only, adding 1 per fragment rasterization produces,
     without the depth test: how many fragments each pixel received, which the primitive id
     cannot tell. Not through the depth test: which of two fragments of close depths passes it
     is free, and a later nearer triangle may hide either, so the count would depend on it.
     Then, into a second attachment, each pixel's trace: the sums of p + 1 and of a hash of p
     over its fragments, which tell whose fragments they were (gl_PrimitiveID through the
     geometry shader where the first draw needs one). */
  count_program = make_program(s->count_vertex_shader, NULL, s->count_fragment_shader);
  if (!count_program) goto done;
  trace_program = make_program(s->count_vertex_shader,
                               count_geometry_shader ? s->count_geometry_shader : NULL,
                               s->trace_fragment_shader);
  if (!trace_program) goto done;
  if (!(count_framebuffer = make_framebuffer(w, h, 2, count_formats, count_renderbuffers)))
    goto done;
  if (s->scissor[0]) glDisable(GL_SCISSOR_TEST);
  glClearBufferfv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_COLOR, 1, zero);
  if (s->scissor[0]) glEnable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  for (k = 0; k < 2; ++k) {
    const GLenum target = GL_COLOR_ATTACHMENT0 + k; /* each program's location 0 */
    glDrawBuffers(1, &target);
    glUseProgram(k == 0 ? count_program : trace_program);
    draw_all(s, k == 0 ? count_program : trace_program);
  }
  glDisable(GL_BLEND);
  if (!gl_ok("counting fragments")) goto done;

  /* Read back, bottom row first (GL window coordinates, as the embedded expectation). */
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  rgba = (float *)malloc(pixels * 4 * sizeof *rgba);
  if (!rgba) {
    set_error("out of memory");
    goto done;
  }
  for (k = 0; k < n; ++k) {
    glReadBuffer(GL_COLOR_ATTACHMENT0 + k);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba);
    for (j = 0; j < s->varying_sizes[k]; ++j, ++component)
      for (i = 0; i < pixels; ++i) f->values[(size_t)component * pixels + i] = rgba[4 * i + j];
  }
  glReadBuffer(GL_COLOR_ATTACHMENT0 + n);
  glReadPixels(0, 0, w, h, GL_RED_INTEGER, GL_INT, f->primitive);
  glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, f->depth);
  if (!gl_ok("reading back")) goto done;
  glBindFramebuffer(GL_FRAMEBUFFER, count_framebuffer);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, f->fragments);
  glReadBuffer(GL_COLOR_ATTACHMENT0 + 1);
  glReadPixels(0, 0, w, h, GL_RG, GL_FLOAT, f->traces);
  ok = gl_ok("reading fragment counts");

done:
  free(rgba);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  if (buffers[0]) glDeleteBuffers(2, buffers);
  if (vertex_array) glDeleteVertexArrays(1, &vertex_array);
  if (framebuffer) {
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteRenderbuffers(n + 2, renderbuffers);
  }
  if (count_framebuffer) {
    glDeleteFramebuffers(1, &count_framebuffer);
    glDeleteRenderbuffers(3, count_renderbuffers);
  }
  if (program) glDeleteProgram(program);
  if (count_program) glDeleteProgram(count_program);
  if (trace_program) glDeleteProgram(trace_program);
  return ok;
}

static int alloc_frame(struct frame *f, size_t pixels, int components) {
  f->primitive = (int32_t *)calloc(pixels, sizeof *f->primitive);
  f->depth = (float *)calloc(pixels, sizeof *f->depth);
  f->values = (float *)calloc(pixels * (size_t)(components > 0 ? components : 1), sizeof *f->values);
  f->fragments = (float *)calloc(pixels, sizeof *f->fragments);
  f->traces = (float *)calloc(2 * pixels, sizeof *f->traces);
  return f->primitive && f->depth && f->values && f->fragments && f->traces;
}

/* ---- The harness's first draw: does gl_PrimitiveID need a geometry shader? ---- */

/* How many of the first draw's 16 pixels are not primitive 0 with flat value 1; the first in
   `fault`. */
static int first_draw_wrong(const struct frame *f, char *fault, size_t size) {
  int wrong = 0, x, y;
  for (y = 0; y < FIRST_DRAW.height; ++y)
    for (x = 0; x < FIRST_DRAW.width; ++x) {
      const size_t i = (size_t)y * (size_t)FIRST_DRAW.width + (size_t)x;
      if (f->primitive[i] == 0 && f->values[i] == 1.0f) continue;
      if (wrong++ == 0)
        snprintf(fault, size, "pixel (%d, %d) expected primitive 0 and flat value 1, got primitive "
                 "%d and value %.9g", x, y, (int)f->primitive[i], (double)f->values[i]);
    }
  return wrong;
}

/* A fragment count read from the R32F count target: additive blending of 1.0 per fragment. */
static unsigned fragment_count(float counted) {
  if (!(counted >= 0.0f)) return 0;
  return counted > 65535.0f ? 65535u : (unsigned)counted;
}

/* ---- Reporting ---- */
static const char *number(char *buffer, size_t size, double v) {
  if (isnan(v)) return "nan";
  if (isinf(v)) return v < 0 ? "-inf" : "inf";
  snprintf(buffer, size, "%.9g", v);
  return buffer;
}

static const char *primitive_name(char *buffer, size_t size, int p) {
  if (p < 0) return "none";
  snprintf(buffer, size, "%d", p);
  return buffer;
}

static void lower_case(char *out, size_t size, const char *text) {
  size_t n;
  for (n = 0; n + 1 < size && text[n]; ++n)
    out[n] = (char)(text[n] >= 'A' && text[n] <= 'Z' ? text[n] - 'A' + 'a' : text[n]);
  out[n] = '\0';
}

#define MOST_PRINTED 30
static long failures, coverage_failures, value_failures;

int main(int argc, char **argv) {
  const char *backend = argc > 1 ? argv[1] : "egl";
  const char *gl_renderer, *gl_version, *driver = getenv("GALLIUM_DRIVER");
  char renderer_lower[256], driver_lower[64], fault[256] = "", gs_fault[256] = "";
  struct frame probe, frame;
  const struct candidate *candidate = CANDIDATES, *candidates_end = CANDIDATES + CANDIDATE_COUNT;
  long judged = 0, undetermined = 0, undetermined_non_finite = 0, covered = 0;
  double worst_ratio = 0;
  int use_geometry_shader = 0, count_geometry_shader = 0, wrong, status, x, y, k, major, minor;

  if (argc > 2 || (strcmp(backend, "egl") && strcmp(backend, "osmesa"))) {
    fprintf(stderr, "usage: %s [egl|osmesa]  (GALLIUM_DRIVER picks Mesa's driver)\n", argv[0]);
    return 2;
  }
  status = strcmp(backend, "egl") ? open_osmesa() : open_egl();
  if (status) return status;
  if ((status = load_gl())) return status;
  gl_renderer = (const char *)glGetString(GL_RENDERER);
  gl_version = (const char *)glGetString(GL_VERSION);
  if (!gl_renderer) gl_renderer = "?";
  if (!gl_version) gl_version = "?";
  major = gl_integer(GL_MAJOR_VERSION), minor = gl_integer(GL_MINOR_VERSION);
  if (major * 10 + minor < 33)
    return no_gl("OpenGL %d.%d on %s ('%s'); the reproducer needs 3.3 core", major, minor,
                 platform, gl_renderer);
  /* The driver asked for must be the one running (zink names the Vulkan driver under it). */
  lower_case(renderer_lower, sizeof renderer_lower, gl_renderer);
  lower_case(driver_lower, sizeof driver_lower, driver ? driver : "");
  if (driver && *driver &&
      (!strstr(renderer_lower, driver_lower) ||
       (!strncmp(renderer_lower, "zink", 4) && strcmp(driver_lower, "zink"))))
    return no_gl("GALLIUM_DRIVER is %s, but GL_RENDERER is '%s' (%s)", driver, gl_renderer,
                 platform);

  if (!alloc_frame(&probe, (size_t)FIRST_DRAW.width * (size_t)FIRST_DRAW.height, 1) ||
      !alloc_frame(&frame, PIXELS, COMPONENT_COUNT))
    return no_gl("out of memory");
  /* softpipe (Mesa 22.3.6) draws nothing when the fragment shader reads gl_PrimitiveID and no
     geometry shader runs; on llvmpipe a geometry shader changes bits. So, as the harness: the
     plain draw unless it is wrong and the geometry shader's is right. */
  if (!draw_scene(&FIRST_DRAW, 0, 0, &probe))
    return no_gl("'%s' fails a first draw: %s", gl_renderer, error_text);
  wrong = first_draw_wrong(&probe, fault, sizeof fault);
  if (wrong > 0) {
    const int gs_wrong = draw_scene(&FIRST_DRAW, 1, 1, &probe)
                             ? first_draw_wrong(&probe, gs_fault, sizeof gs_fault)
                             : (snprintf(gs_fault, sizeof gs_fault, "no draw: %.200s", error_text),
                                FIRST_DRAW.width * FIRST_DRAW.height);
    use_geometry_shader = gs_wrong < wrong;
    if (gs_wrong > 0)
      printf("warning: the first draw (one triangle covering a 4x4 framebuffer) is wrong: %s (%d "
             "of 16 pixels wrong); with a pass-through geometry shader for gl_PrimitiveID: %s; "
             "drawing %s it\n", fault, wrong, gs_fault, use_geometry_shader ? "with" : "without");
  }

  count_geometry_shader = use_geometry_shader;
  if (use_geometry_shader && !THE_CASE.work_arounds) {
    printf("warning: gl_PrimitiveID without a geometry shader is wrong on '%s' (%s); the case "
           "allows no work-around, so it is drawn without one\n", gl_renderer, fault);
    use_geometry_shader = 0;
  }
  if (!draw_scene(&THE_CASE, use_geometry_shader, count_geometry_shader, &frame)) {
    printf("error: %s\n", error_text);
    printf("%s: FAIL, GL could not draw the case, on GL_RENDERER \"%s\", GL_VERSION \"%s\" (%s)\n",
           CASE_NAME, gl_renderer, gl_version, platform);
    return 1;
  }

  for (y = 0; y < FB_HEIGHT; ++y)
    for (x = 0; x < FB_WIDTH; ++x) {
      const int i = y * FB_WIDTH + x;
      const int reference = REF_PRIMITIVE[i], gl_primitive = frame.primitive[i];
      const unsigned gl_fragments = fragment_count(frame.fragments[i]);
      const struct expected_coverage expected_here = {REF_PRIMITIVE[i], REF_FRAGMENTS[i],
                                                      REF_EDGES[i]};
      const struct candidate *first = candidate, *other;
      const float *expected = NULL;
      const double *allowed = NULL;
      enum label label;
      char a[32], b[32];
      /* This pixel's depth-test candidates. */
      while (candidate != candidates_end && candidate->pixel == i) ++candidate;
      other = gl_primitive != reference ? candidate_of(first, candidate, gl_primitive) : NULL;

      label = pixel_label(COVERAGE_VERDICT, COUNTS_CHECKED, &TRACE_LIST, i, &expected_here,
                          gl_primitive, gl_fragments, &frame.traces[2 * (size_t)i], other);
      if (LABEL_FAILS[label]) {
        ++coverage_failures;
        if (failures < MOST_PRINTED) {
          if (label == GAP || label == DOUBLE_HIT)
            printf("%s at (%d, %d): %u fragment%s, reference %u\n",
                   label == GAP ? "gap" : "double hit", x, y, gl_fragments,
                   gl_fragments == 1 ? "" : "s", (unsigned)REF_FRAGMENTS[i]);
          else if (gl_primitive == reference)
            printf("coverage at (%d, %d): %u fragment%s, reference %u\n", x, y, gl_fragments,
                   gl_fragments == 1 ? "" : "s", (unsigned)REF_FRAGMENTS[i]);
          else
            printf("coverage at (%d, %d): GL primitive %s, reference %s%s\n", x, y,
                   primitive_name(a, sizeof a, gl_primitive), primitive_name(b, sizeof b, reference),
                   label == EXACT_TIE ? " (an exact tie)"
                   : label == WITHIN_SNAPPING ? " (within snapping)" : "");
        }
        ++failures;
      }

      /* Values where GL drew the reference's triangle, or a candidate of the depth test. */
      if (reference >= 0) ++covered;
      if (reference >= 0 && gl_primitive == reference) {
        expected = &REF_VALUES[(covered - 1) * CHANNELS];
        allowed = &REF_ALLOWED[(covered - 1) * CHANNELS];
      } else if (other) {
        expected = other->values;
        allowed = other->allowed;
      } else {
        continue;
      }
      for (k = 0; k < CHANNELS; ++k) {
        const float e = expected[k];
        const float g = k == 0 ? frame.depth[i] : frame.values[(size_t)(k - 1) * PIXELS + (size_t)i];
        double error;
        /* No value the specification determines (or, with an unbounded allowance, no bound on
           it: NaN or Inf is not determined either): not judged. */
        if (!isfinite(e) || (SPEC_ALLOWANCE && isinf(allowed[k]) && !isfinite(g))) {
          ++undetermined;
          if (!isfinite(g)) ++undetermined_non_finite;
          continue;
        }
        ++judged;
        error = fabs((double)g - (double)e);
        if (isfinite(g) && error <= allowed[k]) {
          if (error > 0) {
            const double ratio = allowed[k] > 0 ? error / allowed[k] : INFINITY;
            if (ratio > worst_ratio) worst_ratio = ratio;
          }
          continue;
        }
        ++value_failures;
        if (failures++ < MOST_PRINTED) {
          printf("%s at (%d, %d): GL %s, reference %s, allowed +-%.3g", CHANNEL_NAMES[k], x, y,
                 number(a, sizeof a, g), number(b, sizeof b, e), allowed[k]);
          if (other) printf(" (GL kept primitive %d, a candidate of the depth test)", gl_primitive);
          printf("\n");
        }
      }
    }

  if (failures > MOST_PRINTED) printf("... and %ld more\n", failures - MOST_PRINTED);
  if (undetermined_non_finite > 0)
    printf("note: GL drew NaN or Inf at %ld of the %ld values the specification does not "
           "determine (not judged; glrefcheck calls such a case outside what GL specifies)\n",
           undetermined_non_finite, undetermined);
  if (failures > 0 && OUTSIDE_SPECIFIED_RANGE[0])
    printf("note: outside GL's specified range: %s (glrefcheck run reports this case as a skip)\n",
           OUTSIDE_SPECIFIED_RANGE);
  if (failures > 0) {
    printf("%s: FAIL: %ld of %d pixels' coverage and %ld of %ld values fail, on GL_RENDERER "
           "\"%s\", GL_VERSION \"%s\" (%s)\n",
           CASE_NAME, coverage_failures, PIXELS, value_failures, judged, gl_renderer, gl_version,
           platform);
    return 1;
  }
  if (worst_ratio > 0)
    snprintf(fault, sizeof fault, "at most %.3gx the allowance", worst_ratio);
  else
    snprintf(fault, sizeof fault, "every value exact");
  printf("%s: pass: %d pixels' coverage and %ld values within what is allowed (%s), on "
         "GL_RENDERER \"%s\", GL_VERSION \"%s\" (%s)\n",
         CASE_NAME, PIXELS, judged, fault, gl_renderer, gl_version, platform);
  return 0;
}
