// The planted faults of primitive assembly (faults.hpp): what a driver that assembles strips
// and fans wrongly would draw, given to GL as GL_TRIANGLES lists with the wrong vertices.
#pragma once

#include <vector>

#include "selftest/faults.hpp"

namespace glrc::selftest {

// Appends, in this order: a strip's odd triangles provoked by v_i+1 instead of v_i under the
// first-vertex convention; a fan's hub kept from before a primitive restart.
void add_assembly_faults(std::vector<Fault>& list);

}  // namespace glrc::selftest
