// render(): a case through the draw module into one driver's setup, rasterizer and fragment
// evaluation; names; llvmpipe's FMA choice.
#include <cpuid.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include <strings.h>

#include "driver_models/draw.hpp"
#include "driver_models/driver_models.hpp"
#include "driver_models/frame_writer.hpp"
#include "driver_models/llvmpipe_raster.hpp"
#include "driver_models/softpipe_quad.hpp"

namespace glrc::driver_models {

const char* to_string(Driver d) {
  return name_of(d).data();
}

std::optional<Driver> driver_from_string(std::string_view s) {
  return from_name<Driver>(s);
}

// util_cpu_detect (src/util/u_cpu_detect.c): has_fma = CPUID.1:ECX.FMA && has_avx, has_avx =
// AVX && OSXSAVE && XCR0 saves XMM and YMM, and AVX is off without SSE4.1 (and the chain of
// SSE levels below it) or when GALLIUM_OVERRIDE_CPU_CAPS names a level up to sse4.1, or
// GALLIUM_NOSSE is set. gallivm then targets "+fma" exactly when has_fma.
bool llvmpipe_uses_fma() {
  static const bool fma = [] {
#if defined(__x86_64__) || defined(__i386__)
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
    const bool sse = edx >> 25 & 1, sse2 = edx >> 26 & 1, sse3 = ecx & 1, ssse3 = ecx >> 9 & 1;
    const bool sse41 = ecx >> 19 & 1, fma_bit = ecx >> 12 & 1;
    bool avx = (ecx >> 28 & 1) && (ecx >> 27 & 1);
    if (avx) {
      unsigned xcr0_lo = 0, xcr0_hi = 0;
      __asm__("xgetbv" : "=a"(xcr0_lo), "=d"(xcr0_hi) : "c"(0));
      avx = (xcr0_lo & 6) == 6;
    }
    if (!(sse && sse2 && sse3 && ssse3 && sse41)) avx = false;
    // debug_get_bool_option: anything but 0, n, no, f, false (any case) is true.
    if (const char* nosse = std::getenv("GALLIUM_NOSSE")) {
      bool off = false;
      for (const char* no : {"0", "n", "no", "f", "false"})
        off = off || strcasecmp(nosse, no) == 0;
      if (!off) avx = false;
    }
    if (const char* o = std::getenv("GALLIUM_OVERRIDE_CPU_CAPS"))
      for (const char* level : {"nosse", "sse", "sse2", "sse3", "ssse3", "sse4.1"})
        if (std::strcmp(o, level) == 0) avx = false;
    return fma_bit && avx;
#else
    return false;
#endif
  }();
  return fma;
}

namespace {
constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;  // MXCSR bits
}  // namespace

Frame render(const Case& c, Driver d, const Options& o) {
  Frame frame(c.fb_width, c.fb_height, c.component_count());
  frame.fragments.assign(frame.pixel_count(), 0);
  std::fill(frame.depth.begin(), frame.depth.end(), c.depth_clear);  // glClearDepth
  FrameWriter writer(frame, c.depth_func);
  if (d == Driver::llvmpipe) {
    LlvmpipeRasterizer raster(c, o.fma, writer);
    run_draw(c, DrawConfig{VertexPath::llvm, o.fma}, raster);
  } else {
    // softpipe computes in plain C on a thread whose SSE control flushes denormal results to
    // zero and reads denormal inputs as zero (Mesa's util_fpstate_set_denorms_to_zero):
    // measured, subnormal attributes come back as 0. So does the model.
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(saved | kFlushToZero | kDenormalsAreZero);
    SoftpipeRasterizer raster(c, writer);
    run_draw(c, DrawConfig{VertexPath::c, false, true}, raster);
    _mm_setcsr(saved);
    // softpipe's bug with gl_PrimitiveID read in a fragment shader and no geometry shader
    // (piglit's primitive-id-no-gs; 22.3.6 and 25.0.7): the draw writes no fragment. The
    // harness works around it with a pass-through geometry shader, except in a case that turns
    // work-arounds off; its counting pass reads no gl_PrimitiveID and counts as usual.
    if (!c.work_arounds) {
      std::fill(frame.primitive.begin(), frame.primitive.end(), Frame::kNoPrimitive);
      std::fill(frame.depth.begin(), frame.depth.end(), c.depth_clear);
      for (std::vector<float>& component : frame.components)
        std::fill(component.begin(), component.end(), 0.0f);
    }
  }
  return frame;
}

}  // namespace glrc::driver_models
