// Generators of random cases for `glrefcheck fuzz`: each makes an ordinary Case from a seed and
// an index, the same Case on every machine and build (campaign/random.hpp), aimed at one kind of
// input where rasterizers go wrong. Every case is valid as casefile::load would accept it (at
// most 7 varyings, a viewport inside the framebuffer, noperspective only where every vertex a
// triangle uses has w_c > 0), so casefile/write.hpp can write it as a case file.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/case.hpp"

namespace glrc::campaign {

class Random;

struct Generator {
  std::string_view name;
  std::string_view aims_at;  // one line, for `fuzz --help` and the campaign's results
  Case (*make)(Random& random);
};

// Every generator, in a fixed order:
//   sizes       1 to 2,047 triangles from sub-pixel to several times the viewport, slivers, and
//               triangles far from the window origin (framebuffers up to 4096 pixels wide or
//               high);
//   clip        w over orders of magnitude, w <= 0, vertices and edges on and near the clip
//               planes (x = ±w, y = ±w, z = ±w), near and far crossings, all three qualifiers;
//   mesh        shared edges: fans around random centres with sub-pixel rim steps, jittered
//               grids, meshes whose vertices are pixel centres;
//   attributes  values from 1e-30 to 1e30, mixed signs and magnitudes in one vector, all three
//               qualifiers, up to 7 varyings;
//   states      cull, front face, provoking vertex, depth range (reversed too), depth function,
//               viewport offsets and sizes;
//   dense       100 to 800 triangles with the depth test (less) in framebuffers 64 to 512
//               pixels a side: pairs of different triangles in one exact depth plane, or a few
//               ulps of z_c apart, each under a later, clearly nearer triangle (hidden depth
//               contests, issue 44); bitwise-identical copies of earlier triangles; clip-heavy
//               triangles (x_c, y_c within ±3 w_c, z_c within ±1.2 w_c, w_c in [0.2, 3.2]);
//               fans and strips sharing vertices by index, of sub-pixel, small (< 4 px), medium
//               (16 to 64 px) and large (64 to 384 px) triangles;
//   assembly    strips, fans and lists in one to four draws: glDrawArrays and glDrawElements
//               with 8-, 16- and 32-bit indices, primitive restart (fixed index and
//               glPrimitiveRestartIndex), repeated indices, both provoking vertices, culling,
//               vertices beyond the clip planes;
//   window      viewports with negative origins, larger than the framebuffer (up to 16384),
//               partly or wholly outside it; scissor boxes inside, across and beyond it, empty
//               ones too;
//   distances   gl_ClipDistance and gl_CullDistance, up to 8 together;
//   depth       GL_DEPTH_CLAMP, polygon offsets (and their clamp), depth ranges full, partial
//               and reversed, both glClipControl depth modes, every depth function.
// New generators go last, and none is ever removed or reordered: a campaign of every generator
// makes case I with generator I mod n, so adding one changes which case such a campaign's
// `--replay S:I` names (a campaign of named generators, and `--generator G --replay S:I`,
// which each case's description gives, are unchanged).
const std::vector<Generator>& generators();
// The generator of that name, or nullptr.
const Generator* find_generator(std::string_view name);

// Which generator makes case `index` of a campaign over `chosen` (in the order given, not
// empty): chosen[index mod size], so a campaign spreads its cases evenly over its generators.
const Generator& generator_for(const std::vector<const Generator*>& chosen, uint64_t index);

// Case `index` of the campaign (`seed`, `chosen`): named "fuzz_<generator>_<seed>_<index>",
// described by its generator and how to make it again. The same arguments give the same
// Case, bit for bit.
Case generate(const std::vector<const Generator*>& chosen, uint64_t seed, uint64_t index);

}  // namespace glrc::campaign
