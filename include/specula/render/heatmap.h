#pragma once
// The picture of a sampling check (sampling/check.h): for each incidence angle a row of two heat
// maps, the histogram of the samples and the counts the pdf predicts, on one viridis scale per row
// (Mitsuba 3's chi2 plots). φ_o runs left to right from 0 to 2π, cos θ_o bottom (horizon) to top.
#include "specula/render/image.h"
#include "specula/sampling/check.h"

namespace specula::render {

/// `scale` pixels per cell, a gap of 2·scale between maps and rows.
Srgb8Image sampling_heatmap(const sampling::SamplingCheck& check, int scale = 6);

}  // namespace specula::render
