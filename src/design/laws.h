#pragma once
// A shape's constants as formulas in the parameter (a material's uniforms): each constant's
// values over the grid fitted by fit::search (simplified, snapped), the smallest formula kept
// whose lobe stays within 2 % of the per-value optimum on the grid; the constants after it are
// refitted per value with it held, so that they absorb what it misses.
#include <optional>
#include <span>

#include "fitting.h"

namespace specula::design {

/// The finished lobe: F as one expression in c and the parameter.
struct Lawful {
  expr::Expression lobe;   ///< variables: the per-pixel ones (c), then the parameter
  double grid_error = 0;   ///< the objective's largest error on the grid's rows
};

/// Laws for every constant of `shape` fitted over `grid` (its GridFit `fitted`); nullopt if the
/// search was stopped (`stop`). Without a range parameter, the one grid value's constants.
std::optional<Lawful> constant_laws(const Shape& shape, std::span<const Samples> grid, const GridFit& fitted,
                                    const Settings& s, const std::function<bool()>& stop);

/// The shape with constant k replaced by laws[k] (expressions in the parameter alone): an
/// expression in `variables`, then `param`.
expr::Expression substitute_laws(const Shape& shape, std::span<const expr::Expression> laws,
                                 const std::vector<std::string>& variables, const std::string& param);

}  // namespace specula::design
