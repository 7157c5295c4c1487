// Internal to gl_harness: the first draw every renderer makes, and how it is judged. Pure
// functions of a Frame, so that a wrong first draw can be tested without a wrong driver.
//
// The first draw decides one thing: whether gl_PrimitiveID needs a pass-through geometry
// shader (softpipe in Mesa 22.3.6 draws nothing without one). A driver that draws it wrong
// either way is what glrefcheck exists to find: the run goes on, each case passes or fails on
// its own, and the fault is reported (GlInfo::warnings), never an exit 2.
#pragma once

#include <optional>
#include <string>

#include "core/case.hpp"
#include "core/frame.hpp"

namespace glrc::gl {

// One triangle covering the whole 4x4 framebuffer (clip (-1,-1), (3,-1), (-1,3)), one flat
// float varying of 1 on every vertex: every pixel must read primitive 0 and value 1.
Case first_draw_case();
inline constexpr int kFirstDrawPixels = 4 * 4;

struct FirstDrawVerdict {
  int wrong_pixels = 0;  // of first_draw_case()'s kFirstDrawPixels
  // "" when right; else one line: the first wrong pixel (GL window coordinates), what was
  // expected there and what came, and how many pixels are wrong.
  std::string fault;
  bool right() const { return wrong_pixels == 0; }
};

// Judges a frame of first_draw_case(): primitive 0 and flat value exactly 1 at every pixel.
// A frame of another size or without one component is wrong at every pixel.
FirstDrawVerdict judge_first_draw(const Frame& f);

// What the renderer does after the first draw without a geometry shader (`plain`) and, when
// that was wrong, with one (`with_geometry_shader`; its fault is the render error's text when
// it could not draw at all).
struct FirstDrawChoice {
  bool geometry_shader = false;  // supply gl_PrimitiveID through a geometry shader
  std::string warning;           // "" when the plain draw is right; else one line
};
// The geometry shader is used only when it draws right where the plain draw does not (the
// softpipe case: the warning names the bug and the work-around), or, when both are wrong, when
// it gets fewer pixels wrong; a wrong draw is a warning, never an error.
FirstDrawChoice choose_first_draw(const FirstDrawVerdict& plain,
                                  const std::optional<FirstDrawVerdict>& with_geometry_shader);

}  // namespace glrc::gl
