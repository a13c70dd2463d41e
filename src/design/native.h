#pragma once
// Lobes timed as native code: each lobe's formula written out as a Highway kernel in float lanes
// (one vector operation per formula operation, a·x + b fused into one FMA, the parameter's
// subexpressions computed once per material as a shader's uniforms are, outside the timing),
// compiled at run time by the compiler that built specula into a shared object, loaded, checked
// against the formula, and timed in the benchmark's harness (cost::time_in_cache) beside the
// built-in lobes' kernels.
#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "specula/cost/lobe_cost.h"
#include "specula/expr/expr.h"

namespace specula::design {

/// A lobe to compile: F in c (or in several per-pixel variables) and the parameter, at the
/// parameter value it is timed at.
struct NativeLobe {
  expr::Expression formula;  ///< variables: c (or the per-pixel ones), then the parameter
  double param = 20;
  std::size_t variables = 1;  ///< per-pixel variables, each its own input lanes
};

/// Per-pixel variable v (of k) at point i of the cosines c a kernel is given: c itself for v = 0,
/// else c rotated by v·n/k, so that each variable sweeps the same values in another order.
inline float variable_value(std::span<const float> c, std::size_t i, std::size_t v, std::size_t k) {
  return c[(i + v * c.size() / k) % c.size()];
}

/// The input arrays of a kernel of several variables, made from the cosines it is called with
/// (variable_value), kept while the same span comes again.
class VariableInputs {
 public:
  explicit VariableInputs(std::size_t variables) : pointers_(variables) {}
  const std::vector<const float*>& of(std::span<const float> c);

 private:
  const float* source_ = nullptr;
  std::size_t size_ = 0;
  std::vector<std::vector<float>> values_;
  std::vector<const float*> pointers_;
};

/// The kernel's source: per lobe, `specula_uniforms_<i>(p, u)` writing the constants that depend
/// on the parameter alone (a material's uniforms, computed once and not timed) and the kernel
/// `specula_lobe_<i>` reading them; its vector operations per value (FMA, a transcendental
/// function, a division: one each), and its count of uniforms.
struct NativeSource {
  std::string text;
  std::vector<int> operations;
  std::vector<std::size_t> uniforms;
};
NativeSource native_source(const std::vector<NativeLobe>& lobes);

/// The compiler: $SPECULA_CXX if set (a path, or a name looked up in PATH; InvalidArgument if it
/// names no executable file: a compiler the user chose is never replaced by another), else the
/// one that built specula; empty if that one is gone.
std::string native_compiler();

/// How long a compilation may take: $SPECULA_COMPILE_TIMEOUT seconds if set (a whole number in
/// [1, 3600]; InvalidArgument otherwise), else 180 s. A compiler that runs longer is killed, with
/// everything it started, and the formula lobes keep the cost model's cost.
inline constexpr std::chrono::seconds kDefaultCompileLimit{180}, kMaxCompileLimit{3600};
std::chrono::seconds compile_limit();

/// Compiled and loaded kernels, in the order of the lobes (each valid while this lives).
class NativeKernels {
 public:
  /// Compiles `lobes` in `work_dir` (which must exist). Throws std::runtime_error with the
  /// compiler's first error line if the compilation fails or takes over compile_limit(), and
  /// Interrupted if `stop` says so meanwhile.
  NativeKernels(const std::vector<NativeLobe>& lobes, const std::filesystem::path& work_dir,
                const std::function<bool()>& stop);
  ~NativeKernels();
  NativeKernels(const NativeKernels&) = delete;
  NativeKernels& operator=(const NativeKernels&) = delete;

  const std::vector<cost::FloatKernel>& kernels() const { return kernels_; }
  const std::vector<int>& operations() const { return operations_; }

 private:
  void* library_ = nullptr;
  std::vector<cost::FloatKernel> kernels_;
  std::vector<int> operations_;
};

/// The largest |kernel − formula| over cosines spread on [0, 1] (each variable's values as
/// variable_value gives them; the formula in double, with the lobe conventions: F = 0 where a
/// variable is ≤ 0, each clamped to 1): the check a kernel passes before it is timed.
double kernel_deviation(const cost::FloatKernel& kernel, const NativeLobe& lobe);

}  // namespace specula::design
