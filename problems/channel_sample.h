// The channel quality of a communication problem sampled for figures (the paper's Figs. 4, 8).
#pragma once

#include <optional>

#include "core/field_sample.h"
#include "core/ocp.h"
#include "problems/channel/channel_quality.h"

namespace ocpb {

/// log10 s(q) on the nodes of a `spacing` grid over [0, workspace]^2 (quantity "log10_s"; the
/// s_map field of a record that keeps its trajectory; results/plotting/paper_figures.py draws
/// paths over it). Values are rounded to 1e-4 in log10 (0.02 % in s): a figure needs no more,
/// and 51 x 51 values stay a small part of a record. A workspace wider than 500 spacings is
/// sampled at workspace / 500 instead (kMaxFieldSamplePoints).
FieldSample SampleChannel(const ChannelQuality& channel, double workspace, double spacing = 1.0);

/// ProblemInfo::sample_for_figures of comm-path2d: its channel on a 1 m grid.
std::optional<FieldSample> SampleCommPath2dChannel(const Ocp& ocp);

}  // namespace ocpb
