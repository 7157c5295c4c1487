// ChannelError: the per-pixel error of one channel (depth or one varying component) between
// the GL frame and the reference, measured as the comparator measures it, for the diff images.
// compare computes only statistics; the images need every pixel.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/case.hpp"
#include "core/expectation.hpp"

namespace glrc::report {

struct ChannelError {
  std::string name;  // "depth" or "color.x"
  int width = 0, height = 0;
  std::vector<float> reference, gl;  // the channel's values in each frame, every pixel
  // Per pixel, where both frames cover it with the same primitive: gl - reference in value
  // units (NaN if either is NaN), and |gl - reference| in ULPs of the attribute scale (+inf when
  // the values differ and either is not finite). NaN in both where the pixel is not compared.
  std::vector<float> signed_error;
  std::vector<double> ulps;
  std::vector<bool> compared;
  // Per pixel, the allowance in the same ULPs (where compared; the tolerance the comparator
  // applied: the specification's per-pixel one, a fixed number, or 0 in exact mode).
  std::vector<double> allowed_ulps;
  std::vector<float> allowed;  // the same in value units; NaN where not compared
  double max_finite_ulps = 0;  // over compared pixels with a finite error
  size_t non_finite = 0;       // compared pixels whose error is not finite
  // What `ulps` holds, for titles and legends: the error itself by default; as_allowance_map
  // and as_ratio_map put other per-pixel quantities in its place.
  std::string quantity = "|GL - reference| in ulp of the attribute scale";
  std::string unit = "ulp";
  bool judged = true;  // false for the allowance map: nothing in it is over or under a limit
};

// The depth is of scale 1.0 (depth range [0, 1]); a component's is its triangle's largest
// |v_i| (compare::attribute_scale). Errors are compare::pixel_error at the pixels compare compares.
ChannelError channel_error(const Case& c, const Expectation& expected, const Frame& gl,
                           Channel channel, const Tolerance& tolerance);

// The allowance itself, in ULPs, as a map of its own.
ChannelError as_allowance_map(const ChannelError& e);
// How much of the allowance each pixel used: error / allowance (over 1 fails).
ChannelError as_ratio_map(const ChannelError& e);

// The map shrunk by `factor` in x and y (blocks of factor x factor pixels; the last ones may be
// partial), each block showing its worst pixel: a non-finite error first, then the largest
// share of the allowance, then the largest error, so that no failure disappears from a picture
// of a large frame. max_finite_ulps and non_finite keep the whole frame's values. With a factor
// over 1 the result is a map only: ulps, allowed_ulps and compared (what render_heatmap,
// as_allowance_map and as_ratio_map read); reference, gl, signed_error and allowed are empty.
ChannelError downsampled(const ChannelError& e, int factor);

// The side of the blocks a width x height frame's pictures shrink to when `channels` maps are
// shown: 1 for a frame of 2^20 pixels or fewer; else at least enough for 1024 pixels on the
// long side, doubled until all the maps together take at most 128 MiB (17 bytes a map pixel):
// a 4096 x 4096 frame gets 1024 x 1024 maps for up to 7 channels, 512 x 512 for 29. Its
// coverage picture shrinks by map_factor(width, height, 1).
int map_factor(int width, int height, size_t channels);

// The pixel whose error uses the largest share of its allowance (non-finite first); -1 when
// nothing is compared.
long worst_pixel(const ChannelError& e);
// How bad pixel i is, for choosing what a block or a tile shows: compared first, then a
// non-finite error, then the share of the allowance, then the error; larger (in lexicographic
// order) is worse.
std::array<double, 4> badness(const ChannelError& e, size_t i);

}  // namespace glrc::report
