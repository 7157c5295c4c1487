// Guessing the floor below which no error of a channel can be among its largest values, from a
// sample of its plain runs (internal to compare/): in a frame whose errors rise from row to row
// the floor of the largest values so far climbs slowly, and until then many values are kept only
// to be dropped (compare/README.md). A guess the frame does not bear out is undone
// (LargestValues::complete): the figures never depend on it.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "compare/channel_accumulator.hpp"
#include "compare/compare.hpp"

namespace glrc::compare {

// Below a sample's value at the share that should be kept, `margin` times what a compaction
// keeps (one and a half for a sample of the whole frame: with 4096 samples or more, the
// frame's share above it is within a few percent of the sample's), and strictly below it, so
// that a value many pixels share is kept rather than dropped: that share, for a frame of
// `pixels` pixels, `plain` of its runs plain, `sampled` of them sampled; none where plain runs
// are under half the frame (many small triangles: a sample of them would be a poor one, and
// their values rise little), or too few are sampled.
std::optional<double> floor_share(const ChannelAccumulator& acc, double plain, double pixels,
                                  size_t sampled, double margin = 1.5);

// The order keys of a sample of a frame's (or a slice's) ulps and shares of the allowance, for
// guessing the floors of a channel's largest values: one pixel of each plain run (compared
// against the reference's own fragment of one primitive, as add_run takes them), at an offset
// that moves from run to run and row to row. With a deferred allowance, each sampled pixel's
// run's bound above it stands for it (`bounds`, as add_channel's): the ratios sampled are then
// no larger than the pixels' own, the floor guessed no higher (a lower one keeps more values,
// which complete() allows; what the figures are does not depend on the floor, only how many
// values are kept on the way). Appended to ulps and ratios.
void sample_floor_keys(const std::vector<int32_t>& plain_runs, const UlpTable& table,
                       const ChannelAllowance& allowance, const Frame& reference,
                       const float* gl_values, const float* own_values, Channel ch,
                       const Comparator::ChannelBounds* bounds, std::vector<uint32_t>& ulps,
                       std::vector<uint32_t>& ratios);

// The floors of a channel's largest values (LargestValues::assume_floor) from the keys of a
// sample (sample_floor_keys) at `share` (floor_share); none from too few (non-finite values
// left out).
void assume_sampled_floors(ChannelAccumulator& acc, std::vector<uint32_t>& ulps,
                           std::vector<uint32_t>& ratios, double share);

// The floors of a channel's largest values guessed from a sample of a frame compared whole
// (sample_floor_keys, floor_share).
void assume_floors(ChannelAccumulator& acc, const std::vector<int32_t>& plain_runs,
                   const UlpTable& table, const ChannelAllowance& allowance, const Frame& reference,
                   const float* gl_values, const float* own_values, Channel ch,
                   const Comparator::ChannelBounds* bounds);

}  // namespace glrc::compare
