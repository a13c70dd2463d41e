#pragma once
// `specula lut --format cpp|glsl|hlsl`: an albedo table as ready-to-paste C++, GLSL or HLSL arrays with their
// bilinear lookup, stating how the table was made and its measured interpolation error.
#include <string>

#include "specula/analysis/energy.h"

namespace specula::cli {

/// How the table was made, for the header comment.
struct LutDescription {
  std::string command;        ///< the command line that makes it again, the version and the values' hash
  std::string model;          ///< the model with its fixed parameter values
  std::string param;          ///< the swept parameter's name, or "" for a table of one row
  analysis::LutError error;   ///< measured at the cells' centres (lut_interpolation_error)
};

/// Both need grids of evenly spaced values (the lookup computes the index); the caller checks.
std::string lut_cpp(const analysis::AlbedoLut& lut, const LutDescription& description);
std::string lut_glsl(const analysis::AlbedoLut& lut, const LutDescription& description);
std::string lut_hlsl(const analysis::AlbedoLut& lut, const LutDescription& description);

}  // namespace specula::cli
