#pragma once
// The picture of a sampling check (sampling/check.h): for each incidence angle a row of two heat
// maps, the histogram of the samples and the counts the pdf predicts, on one viridis scale per row
// (Mitsuba 3's chi2 plots). φ_o runs left to right from 0 to 2π, cos θ_o bottom (horizon) to top.
// The columns are titled "samples" and "expected (pdf)"; above each row, its angle, the χ² test's
// p-value and the angle's verdict ("θi = 45°: χ² p = 0.431, passes").
#include "specula/render/image.h"
#include "specula/sampling/check.h"

namespace specula::render {

/// `scale` pixels per cell, a gap of 2·scale between maps and rows; text at 2·scale + 2 pixels per
/// em (11 at least) in default_font(). Throws InvalidArgument when the font cannot be opened.
Srgb8Image sampling_heatmap(const sampling::SamplingCheck& check, int scale = 6);

}  // namespace specula::render
