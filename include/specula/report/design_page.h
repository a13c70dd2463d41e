#pragma once
// The lobe designer's pictures and page (docs/designer.md): the front as a chart of measured cost
// against error, and index.html — the front, each member's formula, error curves, normalization,
// check verdict and GLSL — self-contained, as the report is.
#include <filesystem>
#include <string>

#include "specula/design/design.h"
#include "specula/report/plot.h"

namespace specula::report {

/// Cost (ns per value, log; the cost model's units where the front was not timed) against the
/// largest |F − target| (log): the members as a staircase, each reference a labelled point.
Chart design_front_chart(const design::Result& result);

/// GPU cost (ps per evaluation, log) against the largest |F − target| (log): the members on the
/// GPU's front as a staircase, each reference timed on the GPU a labelled point.
Chart design_gpu_chart(const design::Result& result);

/// |F − target| against c for `member` at the range's ends and its middle.
Chart design_error_chart(const design::Result& result, const design::Lobe& member);

/// index.html for the designer's output directory.
std::string design_page(const design::Result& result);

/// front.svg, front.png and index.html into `dir` (a staged directory, beside front.csv and models.toml).
void write_design_pictures(const design::Result& result, const std::filesystem::path& dir);

}  // namespace specula::report
