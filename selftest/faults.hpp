// Planted faults: deliberate errors put into what a GL implementation draws, to prove that the
// comparator catches them. Each fault changes the case GL is given (before rendering), the
// frame GL returns (after), or both; the reference always renders the unchanged case. Knows
// nothing of GL: Case and Frame in, Case and Frame out.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"

namespace glrc::selftest {

struct Fault {
  std::string name;         // e.g. "provoking-vertex-flipped"
  std::string description;  // one line: what a broken driver would be doing
  // Either may be empty. `after` sees what a correct implementation may produce (to find, say,
  // a pixel on a shared edge) and returns whether it changed anything.
  std::function<void(Case&)> before;
  std::function<bool(const Case&, const Expectation&, Frame&)> after;
};

// The faults, in a fixed order: smooth computed as noperspective; provoking vertex flipped;
// positions shifted by half a pixel; depth range nudged by 1e-4; one value in one pixel changed
// by 1e-3 relative; varyings kept to 11 mantissa bits; two varying components swapped; one pixel
// dropped on a shared edge; every centre on a shared horizontal edge drawn by both triangles;
// a centre beside an edge two thin triangles share drawn twice; one fragment of a hidden
// triangle dropped; an identical copy winning the depth test; a strip's odd triangles provoked
// by the wrong vertex under the first-vertex convention; a fan's hub kept across a restart
// (assembly_faults.hpp); the scissor box one pixel wider; upper-left facing not reversed; clip
// distances' signs flipped; gl_FragCoord.xy half a pixel off; gl_FragCoord.w not inverted;
// gl_FrontFacing ignoring glFrontFace(GL_CW); GL_ZERO_TO_ONE ignored; GL_DEPTH_CLAMP not
// clamping, or clamping to [0, 1] instead of the depth range; a polygon offset without its
// units, or with its slope taken along x only.
const std::vector<Fault>& faults();

// x rounded to the nearest float with `bits` explicit mantissa bits (ties to even).
float keep_mantissa_bits(float x, int bits);

}  // namespace glrc::selftest
