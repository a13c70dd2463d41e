#pragma once
// The designer's search space: lobe shapes F(c) built from c by the operations shaders and SIMD
// units have, each with free constants that the designer fits per parameter value (a material's
// uniforms, not charged per evaluation). Shapes are enumerated exhaustively in order of a cost
// model, cheapest first, one shape per canonical text.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "specula/design/design.h"
#include "specula/expr/expr.h"

namespace specula::design {

/// The variables of a lobe's shapes.
inline const std::vector<std::string> kLobeVariables{"c"};

/// A shape: postfix nodes over the per-pixel variables (c for a lobe); its plain constants are free.
struct Shape {
  std::vector<expr::Node> nodes;
  std::string key;       ///< to_infix with every free constant printed as "k"
  int cost = 0;          ///< the cost model's units (operation_cost)
  int constants = 0;     ///< free constants
  /// The last step that built it (combination: a·x + b·y).
  enum class Step { leaf, affine, square, clamp, sqrt, exp, log2, product, sum, quotient, combination } step = Step::leaf;
  bool nonnegative = false;  ///< ≥ 0 for any constants (max, squares, square roots, exp, products of such)

  expr::Expression expression(const std::vector<std::string>& variables = kLobeVariables) const;
};

/// The most free constants a shape may have.
inline constexpr int kMaxShapeConstants = 4;

/// Every shape of cost ≤ max_cost over `operations` (the affine step a·x + b is Operation::fma; the
/// combination a·x + b·y of two shapes without free constants, a linear model in computed
/// features, costs an fma and a mul)
/// built from the leaves `variables` (one per per-pixel variable), cheapest first, then in a fixed
/// order; at most `limit` shapes, fewer when `stop` (asked every 1024 shapes) says so.
/// Deterministic but for the stop.
std::vector<Shape> enumerate_shapes(std::span<const Operation> operations, int max_cost, std::size_t limit,
                                    const std::function<bool()>& stop = {},
                                    const std::vector<std::string>& variables = kLobeVariables);

/// The expression `shape` with its free constants set to `values` (in node order).
expr::Expression with_constants(const Shape& shape, std::span<const double> values,
                                const std::vector<std::string>& variables = kLobeVariables);

}  // namespace specula::design
