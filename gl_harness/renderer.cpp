// The GL rendering every backend shares: a Case drawn with the programs of shaders.hpp into
// the framebuffer of framebuffer.hpp and read back into a Frame; the state the case controls,
// its vertex data, the fragment-count pass, the first draw, and create_renderer.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/primitive_assembly.hpp"
#include "gl_harness/context.hpp"
#include "gl_harness/first_draw.hpp"
#include "gl_harness/framebuffer.hpp"
#include "gl_harness/gl_functions.hpp"
#include "gl_harness/gl_harness.hpp"
#include "gl_harness/shaders.hpp"

namespace glrc::gl {
namespace {

GLenum gl_depth_func(DepthFunc f) {
  switch (f) {
    case DepthFunc::always:
      return GL_ALWAYS;
    case DepthFunc::never:
      return GL_NEVER;
    case DepthFunc::less:
      return GL_LESS;
    case DepthFunc::lequal:
      return GL_LEQUAL;
    case DepthFunc::greater:
      return GL_GREATER;
    case DepthFunc::gequal:
      return GL_GEQUAL;
    case DepthFunc::equal:
      return GL_EQUAL;
    case DepthFunc::notequal:
      return GL_NOTEQUAL;
  }
  return GL_ALWAYS;
}

// One line: shader logs and messages go into RenderError::what().
// A float as its shortest decimal ("10.5", "3"), for messages.
std::string decimal(float f) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  return std::string(buf, r.ptr);
}

std::string one_line(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\0'))
    s.pop_back();
  for (char& ch : s)
    if (ch == '\n') ch = '|';
  return s;
}

// The vertex objects of one case, deleted when it is done (or throws): one context renders
// hundreds of cases.
struct CaseObjects {
  const GlFunctions& gl;
  GLuint vertex_array = 0, vertex_buffer = 0, index_buffer = 0;

  explicit CaseObjects(const GlFunctions& functions) : gl(functions) {}
  CaseObjects(const CaseObjects&) = delete;
  CaseObjects& operator=(const CaseObjects&) = delete;
  ~CaseObjects() {
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    gl.BindRenderbuffer(GL_RENDERBUFFER, 0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.UseProgram(0);
    if (index_buffer) gl.DeleteBuffers(1, &index_buffer);
    if (vertex_buffer) gl.DeleteBuffers(1, &vertex_buffer);
    if (vertex_array) gl.DeleteVertexArrays(1, &vertex_array);
  }
};

class GlRenderer final : public Renderer {
 public:
  GlRenderer(const Target& t, std::unique_ptr<Context> context)
      : context_(std::move(context)),
        gl_(*context_),
        framebuffer_(gl_, t.depth_format),
        count_framebuffer_(gl_, t.depth_format),
        trace_framebuffer_(gl_, t.depth_format),
        set_provoking_vertex_(t.set_provoking_vertex) {
    auto string = [this](GLenum name) {
      const GLubyte* s = gl_.GetString(name);
      return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
    };
    info_.vendor = string(GL_VENDOR);
    info_.renderer = string(GL_RENDERER);
    info_.version = string(GL_VERSION);
    info_.subpixel_bits = integer(GL_SUBPIXEL_BITS);
    info_.initial_provoking_vertex = integer(GL_PROVOKING_VERTEX) == GL_FIRST_VERTEX_CONVENTION
                                         ? ProvokingVertex::first
                                         : ProvokingVertex::last;
    info_.platform = context_->describe();
    info_.library = loaded_library({"libOSMesa.so", "libEGL_mesa.so", "libEGL_nvidia.so"});
    check_driver(t, info_.renderer, context_->describe());

    int major = integer(GL_MAJOR_VERSION), minor = integer(GL_MINOR_VERSION);
    if (major * 10 + minor < 33)
      throw Unavailable("OpenGL " + std::to_string(major) + "." + std::to_string(minor) + " on " +
                        context_->describe() + " ('" + info_.renderer +
                        "'); glrefcheck needs 3.3 core");
    max_draw_buffers_ = std::min(integer(GL_MAX_DRAW_BUFFERS), integer(GL_MAX_COLOR_ATTACHMENTS));
    max_renderbuffer_size_ = integer(GL_MAX_RENDERBUFFER_SIZE);
    GLint dims[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    max_viewport_[0] = dims[0];
    max_viewport_[1] = dims[1];
    if (major * 10 + minor >= 41) {
      GLfloat range[2] = {0, 0};
      gl_.GetFloatv(GL_VIEWPORT_BOUNDS_RANGE, range);
      viewport_bounds_[0] = int(range[0]);
      viewport_bounds_[1] = int(range[1]);
    }
    // GLSL's gl_CullDistance through the extension directive (shaders.cpp): listed by every
    // GL 4.5 implementation, which must support it.
    cull_distance_ = has_extension("GL_ARB_cull_distance");
    if (major * 10 + minor >= 41 || has_extension("GL_ARB_viewport_array")) {
      gl_.ViewportIndexedf =
          reinterpret_cast<PFNGLVIEWPORTINDEXEDFPROC>(context_->proc_address("glViewportIndexedf"));
      if (gl_.ViewportIndexedf) info_.viewport_subpixel_bits = integer(GL_VIEWPORT_SUBPIXEL_BITS);
    }
    if (major * 10 + minor >= 46 || has_extension("GL_ARB_polygon_offset_clamp"))
      gl_.PolygonOffsetClamp = reinterpret_cast<PFNGLPOLYGONOFFSETCLAMPPROC>(
          context_->proc_address("glPolygonOffsetClamp"));
    else if (has_extension("GL_EXT_polygon_offset_clamp"))
      gl_.PolygonOffsetClamp = reinterpret_cast<PFNGLPOLYGONOFFSETCLAMPPROC>(
          context_->proc_address("glPolygonOffsetClampEXT"));
    if (major * 10 + minor >= 45 || has_extension("GL_ARB_clip_control"))
      gl_.ClipControl =
          reinterpret_cast<PFNGLCLIPCONTROLPROC>(context_->proc_address("glClipControl"));
    if (GLenum e = gl_.GetError())
      throw Unavailable(std::string("querying GL limits failed: ") + gl_error_name(e));
    probe();
  }

  ~GlRenderer() override {
    try {
      context_->make_current();
      for (auto& [key, program] : programs_)
        gl_.DeleteProgram(program);
      for (auto& [key, program] : count_programs_)
        if (program) gl_.DeleteProgram(program);
      for (auto& [key, program] : trace_programs_)
        if (program) gl_.DeleteProgram(program);
      framebuffer_.release();
      count_framebuffer_.release();
      trace_framebuffer_.release();
    } catch (...) {
      // Tearing down: the context goes anyway.
    }
  }

  const GlInfo& info() const override { return info_; }

  Frame render(const Case& c) override { return render_reusing(c, Frame()); }

  Frame render_reusing(const Case& c, Frame&& storage) override {
    Frame frame = std::exchange(storage, Frame());
    draw(c);
    read_rows_into(c, 0, c.fb_height, frame);
    return frame;
  }

  void draw(const Case& c) override {
    drawn_ = traced_ = false;
    validate(c);
    context_->make_current();
    while (gl_.GetError() != GL_NO_ERROR) {
      // Errors a previous, failed case left behind are not this case's.
    }
    const int n = int(c.varyings.size());
    const int w = c.fb_width, h = c.fb_height;
    CaseObjects objects(gl_);

    const GLuint program = program_for(c);
    gl_.UseProgram(program);
    framebuffer_.bind(c.name, w, h, case_colour_formats(n));
    set_state(c);
    clear(c, n);
    scissor(c, true);  // after the clear, which the scissor test would cut
    draw(c, objects, program);
    check_error(c, "drawing");
    count_fragments(c);
    drawn_ = true;
  }

  Frame read_rows(const Case& c, int y0, int rows) override {
    Frame frame;
    read_rows_into(c, y0, rows, frame);
    return frame;
  }

  Frame read_rows_reusing(const Case& c, int y0, int rows, Frame&& storage) override {
    Frame frame = std::exchange(storage, Frame());
    read_rows_into(c, y0, rows, frame);
    return frame;
  }
  std::vector<std::optional<FragmentTrace>> fragment_traces(
      const Case& c, const std::vector<size_t>& pixels) override {
    if (!drawn_) throw RenderError("case '" + c.name + "': traces read before it was drawn");
    context_->make_current();
    if (!traced_) trace_fragments(c);
    traced_ = true;
    count_framebuffer_.use();
    const std::vector<float> counts =
        count_framebuffer_.read_at(pixels, GL_COLOR_ATTACHMENT0, GL_RED, 1);
    const bool apart = !traces_in_count_pass();
    if (apart) trace_framebuffer_.use();
    const std::vector<float> sums =
        (apart ? trace_framebuffer_ : count_framebuffer_)
            .read_at(pixels, GLenum(GL_COLOR_ATTACHMENT0 + !apart), GL_RG, 2);
    check_error(c, "reading fragment traces");
    std::vector<std::optional<FragmentTrace>> traces(pixels.size());
    // Integers below 2^24 each (a NaN fails every test), as exact float sums are.
    const auto whole = [](float v) { return v >= 0 && v < 0x1p24f && v == std::floor(v); };
    for (size_t k = 0; k < pixels.size(); ++k)
      if (whole(counts[k]) && whole(sums[2 * k]) && whole(sums[2 * k + 1]))
        traces[k] =
            FragmentTrace{uint32_t(counts[k]), uint32_t(sums[2 * k]), uint32_t(sums[2 * k + 1])};
    return traces;
  }

 private:
  // read_rows() into `frame`, whose buffers are reused (Frame::reset).
  void read_rows_into(const Case& c, int y0, int rows, Frame& frame) {
    if (!drawn_) throw RenderError("case '" + c.name + "': read back before it was drawn");
    if (y0 < 0 || rows < 0 || rows > c.fb_height - y0)
      throw RenderError("case '" + c.name + "': rows " + std::to_string(y0) + " + " +
                        std::to_string(rows) + " outside the framebuffer");
    context_->make_current();
    // Every value of the frame is read back below (or the case is an error).
    frame.reset_uncleared(c.fb_width, rows, c.component_count());
    framebuffer_.use();
    framebuffer_.read_varyings(c, frame, y0);
    framebuffer_.read_depth(frame, y0);
    check_error(c, "reading back");
    count_framebuffer_.use();
    count_framebuffer_.read_fragment_counts(frame, y0);
    check_error(c, "reading fragment counts");
  }

  // Draws the case again with positions only, into its own framebuffer, adding 1 per fragment
  // rasterization produces, without the depth test: how many fragments each pixel received,
  // which the final primitive id cannot tell (a shared edge drawn twice shows only its last
  // triangle). Not through the depth test, because which of two fragments whose depths are
  // within rounding of each other passes it is free, and a later nearer triangle may then hide
  // either: the count would depend on that order (core/frame.hpp). Culling and clipping stay.
  // Where gl_PrimitiveID needs no geometry shader, each fragment also adds its trace's terms
  // into a second attachment (RG32F), read where traces are asked: no second draw, and no
  // second program to compile, for a case whose traces are read (8 bytes a pixel more, and a
  // little more blending, for every case). Elsewhere (softpipe) the count pass stays as it is
  // and the trace pass draws them apart (trace_fragments).
  bool traces_in_count_pass() const { return !info_.primitive_id_from_geometry_shader; }

  void count_fragments(const Case& c) {
    const bool traces = traces_in_count_pass();
    const bool base = several_draws(c);
    GLuint& program =
        count_programs_[std::string(base ? "base," : "") + distances_key(c.distances)];
    if (!program) {
      const GLuint vs = compile(GL_VERTEX_SHADER, count_vertex_shader_source(c.distances), c);
      const GLuint fs = compile(
          GL_FRAGMENT_SHADER,
          traces ? count_and_trace_fragment_shader_source(base) : count_fragment_shader_source(),
          c);
      program = link({vs, fs}, c);
    }
    gl_.UseProgram(program);
    if (traces)
      count_framebuffer_.bind(c.name, c.fb_width, c.fb_height, {GL_R32F, GL_RG32F});
    else
      count_framebuffer_.bind(c.name, c.fb_width, c.fb_height, {GL_R32F});
    const GLfloat zero[4] = {0, 0, 0, 0};
    scissor(c, false);
    gl_.ClearBufferfv(GL_COLOR, 0, zero);
    if (traces) gl_.ClearBufferfv(GL_COLOR, 1, zero);
    scissor(c, true);
    gl_.Disable(GL_DEPTH_TEST);  // set_state enables it again for the next case
    gl_.Enable(GL_BLEND);
    gl_.BlendEquation(GL_FUNC_ADD);
    gl_.BlendFunc(GL_ONE, GL_ONE);
    issue_draws(c, program);
    gl_.Disable(GL_BLEND);
    check_error(c, "counting fragments");
    traced_ = traces;
  }

  // Where the count pass does not trace (traces_in_count_pass: the driver needs the geometry
  // shader for gl_PrimitiveID): the count pass again, once a case and only where traces are
  // asked (a case's coverage differs inside a band: seldom), each fragment adding its trace's
  // terms (p + 1, the hash of p) instead of 1, into a framebuffer of its own: the case's state
  // (culling, viewport) is still set, its vertices are given again. Through the pass-through
  // geometry shader whatever the case's work_arounds say: the pass is the harness's own
  // instrument, not the case's draw.
  void trace_fragments(const Case& c) {
    const bool base = several_draws(c);
    GLuint& program =
        trace_programs_[std::string(base ? "base," : "") + distances_key(c.distances)];
    if (!program) {
      std::vector<GLuint> shaders;
      try {
        shaders.push_back(compile(GL_VERTEX_SHADER, count_vertex_shader_source(c.distances), c));
        shaders.push_back(
            compile(GL_GEOMETRY_SHADER, count_geometry_shader_source(c.distances), c));
        shaders.push_back(compile(GL_FRAGMENT_SHADER, trace_fragment_shader_source(base), c));
      } catch (...) {
        for (GLuint shader : shaders)
          gl_.DeleteShader(shader);
        throw;
      }
      program = link(shaders, c);
    }
    CaseObjects objects(gl_);
    gl_.UseProgram(program);
    trace_framebuffer_.bind(c.name, c.fb_width, c.fb_height, {GL_RG32F});
    const GLfloat zero[4] = {0, 0, 0, 0};
    scissor(c, false);
    gl_.ClearBufferfv(GL_COLOR, 0, zero);
    scissor(c, true);
    gl_.Disable(GL_DEPTH_TEST);
    gl_.Enable(GL_BLEND);
    gl_.BlendEquation(GL_FUNC_ADD);
    gl_.BlendFunc(GL_ONE, GL_ONE);
    draw(c, objects, program);
    gl_.Disable(GL_BLEND);
    check_error(c, "tracing fragments");
  }

  // Whether the context lists the extension (glGetStringi, GL 3.0).
  bool has_extension(std::string_view name) const {
    const GLint n = integer(GL_NUM_EXTENSIONS);
    for (GLint i = 0; i < n; ++i) {
      const GLubyte* e = gl_.GetStringi(GL_EXTENSIONS, GLuint(i));
      if (e && name == reinterpret_cast<const char*>(e)) return true;
    }
    return false;
  }

  GLint integer(GLenum name) const {
    GLint v = 0;
    gl_.GetIntegerv(name, &v);
    return v;
  }

  void check_error(const Case& c, const char* when) const {
    if (GLenum e = gl_.GetError())
      throw RenderError("case '" + c.name + "': " + gl_error_name(e) + " while " + when);
  }

  // What GL would reject or misread: reported as this case's error rather than left to GL.
  void validate(const Case& c) const {
    auto fail = [&c](const std::string& why) {
      throw RenderError("case '" + c.name + "': " + why);
    };
    const int n = int(c.varyings.size());
    if (n > kMaxVaryings || n + 1 > max_draw_buffers_)
      fail(std::to_string(n) + " varyings; the GL harness takes at most " +
           std::to_string(std::min(kMaxVaryings, max_draw_buffers_ - 1)) +
           " (one draw buffer each, plus one for gl_PrimitiveID)");
    for (const Varying& v : c.varyings)
      if (v.size < 1 || v.size > 4)
        fail("varying '" + v.name + "' has size " + std::to_string(v.size));
    if (c.fb_width < 1 || c.fb_height < 1 || c.fb_width > max_renderbuffer_size_ ||
        c.fb_height > max_renderbuffer_size_)
      fail("framebuffer " + std::to_string(c.fb_width) + "x" + std::to_string(c.fb_height) +
           " outside 1.." + std::to_string(max_renderbuffer_size_) + " (GL_MAX_RENDERBUFFER_SIZE)");
    const Viewport& vp = c.viewport;
    if (!(vp.width >= 0) || !(vp.height >= 0) || vp.width > float(max_viewport_[0]) ||
        vp.height > float(max_viewport_[1]))
      fail("viewport " + decimal(vp.width) + "x" + decimal(vp.height) +
           " outside GL_MAX_VIEWPORT_DIMS " + std::to_string(max_viewport_[0]) + "x" +
           std::to_string(max_viewport_[1]));
    if (viewport_bounds_[0] < viewport_bounds_[1] &&
        (vp.x < float(viewport_bounds_[0]) || vp.y < float(viewport_bounds_[0]) ||
         vp.x > float(viewport_bounds_[1]) || vp.y > float(viewport_bounds_[1])))
      fail("viewport origin (" + decimal(vp.x) + ", " + decimal(vp.y) +
           ") outside GL_VIEWPORT_BOUNDS_RANGE [" + std::to_string(viewport_bounds_[0]) + ", " +
           std::to_string(viewport_bounds_[1]) + "]");
    if (!vp.integral() && !gl_.ViewportIndexedf)
      throw FeatureMissing("case '" + c.name + "': a viewport of fractional bounds (" +
                           decimal(vp.x) + ", " + decimal(vp.y) + ", " + decimal(vp.width) + ", " +
                           decimal(vp.height) +
                           ") needs glViewportIndexedf: OpenGL 4.1 or GL_ARB_viewport_array, "
                           "which " +
                           info_.renderer + " (" + info_.version + ") does not have");
    if (c.scissor && (c.scissor->width < 0 || c.scissor->height < 0))
      fail("scissor box of negative size");
    if (c.distances.cull > 0 && !cull_distance_)
      throw FeatureMissing("case '" + c.name + "': gl_CullDistance needs OpenGL 4.5 or " +
                           "GL_ARB_cull_distance, which " + info_.renderer + " (" + info_.version +
                           ") does not have");
    for (const Vertex& v : c.vertices)
      if (v.distances.size() != size_t(c.distances.clip + c.distances.cull))
        fail("a vertex with " + std::to_string(v.distances.size()) + " distances, expected " +
             std::to_string(c.distances.clip + c.distances.cull));
    if ((c.clip_origin != ClipOrigin::lower_left ||
         c.clip_depth != ClipDepth::negative_one_to_one) &&
        !gl_.ClipControl)
      throw FeatureMissing("case '" + c.name + "': glClipControl needs OpenGL 4.5 or " +
                           "GL_ARB_clip_control, which " + info_.renderer + " (" + info_.version +
                           ") does not have");
    if (c.polygon_offset && c.polygon_offset->clamp && !gl_.PolygonOffsetClamp)
      throw FeatureMissing("case '" + c.name + "': glPolygonOffsetClamp needs OpenGL 4.6, " +
                           "GL_ARB_polygon_offset_clamp or GL_EXT_polygon_offset_clamp, which " +
                           info_.renderer + " (" + info_.version + ") does not have");
    const size_t components = size_t(c.component_count());
    for (size_t i = 0; i < c.vertices.size(); ++i)
      if (c.vertices[i].values.size() != components)
        fail("vertex " + std::to_string(i) + " has " + std::to_string(c.vertices[i].values.size()) +
             " varying components, expected " + std::to_string(components));
    for (const auto& t : c.triangles)
      for (uint32_t index : t)
        if (index >= c.vertices.size())
          fail("triangle index " + std::to_string(index) + " past the " +
               std::to_string(c.vertices.size()) + " vertices");
    for (size_t d = 0; d < c.draws.size(); ++d)
      for (uint32_t index : c.draws[d].elements())
        if (index >= c.vertices.size() && !c.draws[d].restarts_at(index))
          fail("draw " + std::to_string(d) + " index " + std::to_string(index) + " past the " +
               std::to_string(c.vertices.size()) + " vertices");
    // The reference draws c.triangles: they must be what GL assembles from the draws.
    if (!c.draws.empty() && c.triangles != assemble(c.draws, c.provoking).triangles)
      fail("its triangles are not the assembly of its draws (core/primitive_assembly.hpp)");
  }

  // softpipe (Mesa 22.3.6) drops every triangle when the fragment shader reads gl_PrimitiveID
  // and no geometry shader runs. A pass-through geometry shader avoids that and, on softpipe,
  // leaves every varying and depth bit as it is; on llvmpipe it does not (it changes bits), so
  // it is used only where the plain draw of a triangle covering the whole framebuffer is wrong
  // and the geometry shader's is right (choose_first_draw). A draw wrong either way is the
  // implementation's fault, which is what the cases are there to report: a warning
  // (GlInfo::warnings), never Unavailable.
  void probe() {
    const Case c = first_draw_case();
    FirstDrawVerdict plain;
    try {
      plain = judge_first_draw(render(c));
    } catch (const RenderError& e) {
      // create_renderer promises Unavailable: a context that cannot even set up this draw (its
      // framebuffer formats, its shaders) cannot run any case.
      throw Unavailable("'" + info_.renderer + "' on " + context_->describe() +
                        " fails a first draw: " + e.what());
    }
    if (plain.right()) return;
    use_geometry_shader(true);
    std::optional<FirstDrawVerdict> with_gs;
    try {
      with_gs = judge_first_draw(render(c));
    } catch (const RenderError& e) {
      with_gs = FirstDrawVerdict{kFirstDrawPixels, std::string("no draw: ") + e.what()};
    }
    const FirstDrawChoice choice = choose_first_draw(plain, with_gs);
    if (!choice.geometry_shader) use_geometry_shader(false);
    if (!choice.warning.empty())
      info_.warnings.push_back("'" + info_.renderer + "' on " + context_->describe() + ": " +
                               choice.warning);
  }

  // Programs of the other choice are not needed again: switching drops them.
  void use_geometry_shader(bool on) {
    for (auto& [key, program] : programs_)
      gl_.DeleteProgram(program);
    programs_.clear();
    // The count pass traces only where no geometry shader is needed (traces_in_count_pass).
    for (auto& [key, program] : count_programs_)
      gl_.DeleteProgram(program);
    count_programs_.clear();
    info_.primitive_id_from_geometry_shader = on;
  }

  GLuint compile(GLenum stage, const std::string& source, const Case& c) {
    GLuint shader = gl_.CreateShader(stage);
    const char* text = source.c_str();
    gl_.ShaderSource(shader, 1, &text, nullptr);
    gl_.CompileShader(shader);
    GLint ok = GL_FALSE;
    gl_.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      std::string log(4096, '\0');
      gl_.GetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
      gl_.DeleteShader(shader);
      throw RenderError("case '" + c.name + "': " +
                        (stage == GL_VERTEX_SHADER     ? "vertex"
                         : stage == GL_GEOMETRY_SHADER ? "geometry"
                                                       : "fragment") +
                        " shader does not compile: " + one_line(log.c_str()));
    }
    return shader;
  }

  GLuint program_for(const Case& c) {
    // The work-around only where the case allows it (Case::work_arounds).
    const bool gs = info_.primitive_id_from_geometry_shader && c.work_arounds;
    std::string key = program_key(c) + (gs ? "gs" : "");
    if (auto it = programs_.find(key); it != programs_.end()) return it->second;
    std::vector<GLuint> shaders;
    try {
      shaders.push_back(compile(GL_VERTEX_SHADER, vertex_shader_source(c), c));
      if (gs) shaders.push_back(compile(GL_GEOMETRY_SHADER, geometry_shader_source(c), c));
      shaders.push_back(compile(GL_FRAGMENT_SHADER, fragment_shader_source(c, gs), c));
    } catch (...) {
      for (GLuint shader : shaders)
        gl_.DeleteShader(shader);
      throw;
    }
    const GLuint program = link(shaders, c);
    programs_.emplace(std::move(key), program);
    return program;
  }

  GLuint link(const std::vector<GLuint>& shaders, const Case& c) {
    GLuint program = gl_.CreateProgram();
    for (GLuint shader : shaders)
      gl_.AttachShader(program, shader);
    gl_.LinkProgram(program);
    // Flagged for deletion; they go with the program.
    for (GLuint shader : shaders)
      gl_.DeleteShader(shader);
    GLint ok = GL_FALSE;
    gl_.GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
      std::string log(4096, '\0');
      gl_.GetProgramInfoLog(program, GLsizei(log.size()), nullptr, log.data());
      gl_.DeleteProgram(program);
      throw RenderError("case '" + c.name + "': program does not link: " + one_line(log.c_str()));
    }
    return program;
  }

  // All state the case controls, set every time: the previous case may have changed it.
  void set_state(const Case& c) {
    // Whole numbers through glViewport, as a GL 3.3 application sets them; fractions through
    // glViewportIndexedf (validate() refused them where it is missing). Viewport 0 is the one
    // glViewport sets too.
    const Viewport& vp = c.viewport;
    if (vp.integral())
      gl_.Viewport(GLint(vp.x), GLint(vp.y), GLsizei(vp.width), GLsizei(vp.height));
    else if (gl_.ViewportIndexedf)
      gl_.ViewportIndexedf(0, vp.x, vp.y, vp.width, vp.height);
    gl_.DepthRange(double(c.depth_near), double(c.depth_far));  // exact: float ⊂ double
    for (int i = 0; i < kMaxDistances; ++i) {  // GL_CLIP_DISTANCEi as the case enables them
      const GLenum cap = GLenum(GL_CLIP_DISTANCE0 + i);
      if (c.distances.plane_enabled(i))
        gl_.Enable(cap);
      else
        gl_.Disable(cap);
    }
    if (gl_.ClipControl)  // validate() refused a case that needs it where it is missing
      gl_.ClipControl(
          c.clip_origin == ClipOrigin::upper_left ? GL_UPPER_LEFT : GL_LOWER_LEFT,
          c.clip_depth == ClipDepth::zero_to_one ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(gl_depth_func(c.depth_func));
    gl_.DepthMask(GL_TRUE);
    if (c.cull == CullFace::none) {
      gl_.Disable(GL_CULL_FACE);
    } else {
      gl_.Enable(GL_CULL_FACE);
      gl_.CullFace(c.cull == CullFace::front  ? GL_FRONT
                   : c.cull == CullFace::back ? GL_BACK
                                              : GL_FRONT_AND_BACK);
    }
    gl_.FrontFace(c.front_face == FrontFace::ccw ? GL_CCW : GL_CW);
    if (set_provoking_vertex_)
      gl_.ProvokingVertex(c.provoking == ProvokingVertex::last ? GL_LAST_VERTEX_CONVENTION
                                                               : GL_FIRST_VERTEX_CONVENTION);
    if (c.depth_clamp)
      gl_.Enable(GL_DEPTH_CLAMP);
    else
      gl_.Disable(GL_DEPTH_CLAMP);
    if (const auto& o = c.polygon_offset) {
      gl_.Enable(GL_POLYGON_OFFSET_FILL);
      if (o->clamp)  // validate() refused the case where glPolygonOffsetClamp is missing
        gl_.PolygonOffsetClamp(o->factor, o->units, *o->clamp);
      else
        gl_.PolygonOffset(o->factor, o->units);
    } else {
      gl_.Disable(GL_POLYGON_OFFSET_FILL);
    }
    // Nothing may touch the values between the fragment shader and the readback.
    for (GLenum cap : {GL_DITHER, GL_BLEND, GL_MULTISAMPLE, GL_SCISSOR_TEST, GL_STENCIL_TEST,
                       GL_SAMPLE_ALPHA_TO_COVERAGE, GL_RASTERIZER_DISCARD, GL_PRIMITIVE_RESTART})
      gl_.Disable(cap);
    gl_.ClampColor(GL_CLAMP_READ_COLOR, GL_FALSE);
  }

  // The case's scissor test (Case::scissor), on or off: off around every clear, which it would
  // cut, on for every pass that draws the case. set_state leaves it off.
  void scissor(const Case& c, bool on) {
    if (!c.scissor) return;
    if (!on) {
      gl_.Disable(GL_SCISSOR_TEST);
      return;
    }
    gl_.Enable(GL_SCISSOR_TEST);
    gl_.Scissor(c.scissor->x, c.scissor->y, c.scissor->width, c.scissor->height);
  }

  void clear(const Case& c, int n) {
    const GLfloat zero[4] = {0, 0, 0, 0};
    for (int k = 0; k < n; ++k)
      gl_.ClearBufferfv(GL_COLOR, k, zero);
    const GLint none[4] = {Frame::kNoPrimitive, 0, 0, 0};
    gl_.ClearBufferiv(GL_COLOR, n, none);
    gl_.ClearBufferfv(GL_DEPTH, 0, &c.depth_clear);
  }

  // Gives GL the case's vertices and indices, then issues its draws (issue_draws).
  void draw(const Case& c, CaseObjects& objects, GLuint program) {
    // Interleaved: clip (4 floats), then every varying's components in Case order, then the
    // distances.
    const size_t components = size_t(c.component_count());
    const size_t distances = size_t(c.distances.clip + c.distances.cull);
    const size_t stride = 4 + components + distances;
    std::vector<float> data(c.vertices.size() * stride);
    for (size_t i = 0; i < c.vertices.size(); ++i) {
      std::memcpy(&data[i * stride], c.vertices[i].clip.data(), 4 * sizeof(float));
      if (components)
        std::memcpy(&data[i * stride + 4], c.vertices[i].values.data(), components * sizeof(float));
      if (distances)
        std::memcpy(&data[i * stride + 4 + components], c.vertices[i].distances.data(),
                    distances * sizeof(float));
    }
    const std::vector<unsigned char> indices = index_bytes_of(c);

    gl_.GenVertexArrays(1, &objects.vertex_array);
    gl_.BindVertexArray(objects.vertex_array);
    gl_.GenBuffers(1, &objects.vertex_buffer);
    gl_.BindBuffer(GL_ARRAY_BUFFER, objects.vertex_buffer);
    gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(),
                   GL_STATIC_DRAW);
    gl_.GenBuffers(1, &objects.index_buffer);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, objects.index_buffer);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size()), indices.data(),
                   GL_STATIC_DRAW);

    const GLsizei stride_bytes = GLsizei(stride * sizeof(float));
    auto attribute = [&](GLuint location, int size, size_t first_float) {
      gl_.EnableVertexAttribArray(location);
      gl_.VertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, stride_bytes,
                              reinterpret_cast<const void*>(first_float * sizeof(float)));
    };
    attribute(0, 4, 0);
    size_t offset = 4;
    for (size_t k = 0; k < c.varyings.size(); ++k) {
      // A built-in's zeros (core/case.hpp) are in the buffer, read by no attribute.
      if (!c.varyings[k].is_builtin()) attribute(GLuint(k + 1), c.varyings[k].size, offset);
      offset += size_t(c.varyings[k].size);
    }
    for (size_t i = 0; i < distances; ++i)
      attribute(GLuint(kDistanceLocation + int(i)), 1, offset + i);
    issue_draws(c, program);
  }

  // Every indexed draw's indices in its own type, one after another, each starting at a
  // multiple of 4 bytes (GL wants an offset aligned to the type); sets draws_ and
  // index_offsets_ (and first_triangles_).
  std::vector<unsigned char> index_bytes_of(const Case& c) {
    draws_ = draws_of(c);
    first_triangles_ = assemble(draws_, c.provoking).first_triangle;
    index_offsets_.assign(draws_.size(), 0);
    std::vector<unsigned char> bytes;
    for (size_t d = 0; d < draws_.size(); ++d) {
      const Draw& draw = draws_[d];
      if (!draw.indexed()) continue;
      bytes.resize((bytes.size() + 3) / 4 * 4);
      index_offsets_[d] = bytes.size();
      const size_t size = size_t(index_bytes(draw.index_type));
      for (uint32_t i : draw.indices) {
        // Little-endian, as the machine's GL reads a GLushort or GLuint (both x86-64 and
        // AArch64 Linux): the index's low bytes first.
        for (size_t k = 0; k < size; ++k)
          bytes.push_back(static_cast<unsigned char>(i >> (8 * k)));
      }
    }
    return bytes;
  }

  // The case's draws as GL commands, in order, with the program in use: each with its
  // primitive restart state and, for a case of several draws, `primitive_base` set to the
  // draw's first triangle (gl_PrimitiveID counts from 0 again in every draw). Restart is off
  // again afterwards, as set_state leaves it.
  void issue_draws(const Case& c, GLuint program) {
    static constexpr GLenum kModes[] = {GL_TRIANGLES, GL_TRIANGLE_STRIP, GL_TRIANGLE_FAN};
    static constexpr GLenum kTypes[] = {0, GL_UNSIGNED_BYTE, GL_UNSIGNED_SHORT, GL_UNSIGNED_INT};
    const GLint base = several_draws(c) ? gl_.GetUniformLocation(program, "primitive_base") : -1;
    for (size_t d = 0; d < draws_.size(); ++d) {
      const Draw& draw = draws_[d];
      if (base >= 0) gl_.Uniform1i(base, GLint(first_triangles_[d]));
      const GLenum mode = kModes[int(draw.mode)];
      if (!draw.indexed()) {
        gl_.DrawArrays(mode, GLint(draw.first), GLsizei(draw.count));
        continue;
      }
      if (draw.restart == Restart::fixed_index) gl_.Enable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
      if (draw.restart == Restart::index) {
        gl_.Enable(GL_PRIMITIVE_RESTART);
        gl_.PrimitiveRestartIndex(draw.restart_index);
      }
      gl_.DrawElements(mode, GLsizei(draw.indices.size()), kTypes[int(draw.index_type)],
                       reinterpret_cast<const void*>(index_offsets_[d]));
      if (draw.restart == Restart::fixed_index) gl_.Disable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
      if (draw.restart == Restart::index) gl_.Disable(GL_PRIMITIVE_RESTART);
    }
  }

  std::unique_ptr<Context> context_;  // first: destroyed last, after the programs
  GlFunctions gl_;
  GlInfo info_;
  std::map<std::string, GLuint> programs_;
  // The case's (case_colour_formats) and the fragment-count pass's (R32F).
  Framebuffer framebuffer_, count_framebuffer_, trace_framebuffer_;
  bool drawn_ = false;  // both hold the last draw()'s case
  // Each for a case of one draw [0] and of several [1] (the uniform primitive_base).
  // By base (several draws) and distances (distances_key).
  std::map<std::string, GLuint> count_programs_;
  // The fragment-trace pass's program, through the pass-through geometry shader.
  std::map<std::string, GLuint> trace_programs_;
  // The case's draws (draws_of) and where each one's indices start in the index buffer, in
  // bytes: set by draw(), used by every pass of the case.
  std::vector<Draw> draws_;
  std::vector<uint32_t> first_triangles_;  // each draw's first triangle (AssembledTriangles)
  std::vector<size_t> index_offsets_;
  bool traced_ = false;  // the trace pass drawn for the case drawn last
  int max_draw_buffers_ = 8, max_renderbuffer_size_ = 0;
  int max_viewport_[2] = {0, 0};
  bool cull_distance_ = false;  // GL_ARB_cull_distance
  // GL_VIEWPORT_BOUNDS_RANGE (GL 4.1); {0, 0} where the context has no such limit to ask.
  int viewport_bounds_[2] = {0, 0};
  bool set_provoking_vertex_ = true;  // Target::set_provoking_vertex
};

}  // namespace

Frame Renderer::read_rows(const Case& c, int y0, int rows) {
  if (drawn_.width != c.fb_width || drawn_.height != c.fb_height)
    throw RenderError("case '" + c.name + "': read back before it was drawn");
  if (y0 < 0 || rows < 0 || rows > drawn_.height - y0)
    throw RenderError("case '" + c.name + "': rows " + std::to_string(y0) + " + " +
                      std::to_string(rows) + " outside the framebuffer");
  return drawn_.rows(y0, rows);
}

std::unique_ptr<Renderer> create_renderer(const Target& t) {
  // Before the library creates its screen: that is when Mesa reads GALLIUM_DRIVER.
  select_driver(t);
  std::unique_ptr<Context> context;
  switch (t.backend) {
    case Backend::osmesa:
      context = create_osmesa_context(t);
      break;
    case Backend::egl:
      context = create_egl_surfaceless_context(t);
      break;
    case Backend::egl_device:
      context = create_egl_device_context(t);
      break;
  }
  if (!context) throw Unavailable("unknown GL backend");
  return std::make_unique<GlRenderer>(t, std::move(context));
}

}  // namespace glrc::gl
