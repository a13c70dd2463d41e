#pragma once
// Lobes timed as native code: each lobe's formula written out as a Highway kernel in float lanes
// (one vector operation per formula operation, a·x + b fused into one FMA, the parameter's
// subexpressions computed once per call as a shader's uniforms are), compiled at run time by the
// compiler that built specula into a shared object, loaded, checked against the formula, and
// timed in the benchmark's harness (cost::time_in_cache) beside the built-in lobes' kernels.
#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "specula/cost/lobe_cost.h"
#include "specula/expr/expr.h"

namespace specula::design {

/// A lobe to compile: F in c and the parameter, at the parameter value it is timed at.
struct NativeLobe {
  expr::Expression formula;  ///< variables: c, then the parameter
  double param = 20;
};

/// The kernel's source: one function `specula_lobe_<i>` per lobe, and its vector operations
/// per value (FMA, a transcendental function, a division: one each).
struct NativeSource {
  std::string text;
  std::vector<int> operations;
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

/// The largest |kernel − formula| over cosines spread on [0, 1] (the formula in double, with the
/// lobe conventions: F = 0 for c ≤ 0, c clamped to 1): the check a kernel passes before it is timed.
double kernel_deviation(const cost::FloatKernel& kernel, const NativeLobe& lobe);

}  // namespace specula::design
