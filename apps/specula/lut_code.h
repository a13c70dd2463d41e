#pragma once
// `specula lut --format cpp|glsl|hlsl`: an albedo table as ready-to-paste C++, GLSL or HLSL arrays with their
// bilinear lookup, stating how the table was made and its measured interpolation error.
#include <span>
#include <string>

#include "specula/analysis/energy.h"

namespace specula::cli {

/// How the table was made, for the header comment.
struct LutDescription {
  std::string command;        ///< the command line that makes it again, the version and the values' hash
  std::string model;          ///< the model with its fixed parameter values
  std::string param;          ///< the swept parameter's name, or "" for a table of one row
  /// Each axis is evenly spaced in x^(1/power) (io::spacing_power: 1 linear, 2 in √x, …); the
  /// lookup maps x so before it locates the cell.
  double mu_power = 1, p_power = 1;
  /// A second --sweep: its name, values and power; the channels are then its tables, one per value.
  std::string q_param = "";
  std::vector<double> q = {};
  double q_power = 1;
};

/// One table of the file: the plain one (suffix ""), or E at F0 = 0 and at F0 = 1 of
/// --schlick-split (suffixes "_f0_0" and "_f0_1"; the file then has the lookup at any F0 too).
struct LutChannel {
  std::string suffix;
  const analysis::AlbedoLut* lut;
  analysis::LutError error;  ///< measured at the cells' centres (lut_interpolation_error)
};

/// Every channel on one grid of evenly spaced values (the lookup computes the index); the caller checks.
std::string lut_cpp(std::span<const LutChannel> channels, const LutDescription& description);
std::string lut_glsl(std::span<const LutChannel> channels, const LutDescription& description);
std::string lut_hlsl(std::span<const LutChannel> channels, const LutDescription& description);

}  // namespace specula::cli
