// specula_walk_bench: how long the random walk (walk/walk.h) takes to bring the standard error of
// the multiply scattered albedo of one (μ, α, F) cell to 1e-4, on one core (the walk's own
// threads limited to one). For each cell the paths grow until the error is reached; the line
// gives the last run's paths and seconds. A measurement, never an assertion.
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>

#include "specula/walk/walk.h"

using namespace specula;

int main() {
  constexpr double kTarget = 1e-4;
  const tbb::global_control one_core(tbb::global_control::max_allowed_parallelism, 1);
  const fresnel::Channel one{}, schlick{fresnel::Kind::schlick, 0.04, 1, 5};
  fmt::print("{:<9} {:>5} {:>4} {:<8} {:>10} {:>10} {:>10} {:>8} {:>12}\n", "surface", "alpha", "mu", "fresnel",
             "E_ms", "se", "paths", "s", "paths/s");
  double worst = 0;
  for (const auto distribution : {walk::Distribution::ggx, walk::Distribution::beckmann})
    for (double alpha : {0.1, 0.5, 1.0})
      for (double mu : {0.1, 0.5, 1.0})
        for (const auto* f : {&one, &schlick}) {
          walk::Options options;
          options.paths = walk::kMinPaths;
          walk::Albedo a;
          double seconds = 0;
          for (;;) {
            const auto start = std::chrono::steady_clock::now();
            a = walk::conductor_albedo({distribution, alpha}, {f, 1}, mu, options)[0];
            seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (a.multiple.error <= kTarget) break;
            const double grow = std::max(2.0, 1.3 * std::pow(a.multiple.error / kTarget, 2));
            options.paths = std::uint64_t(double(options.paths) * grow);
          }
          worst = std::max(worst, seconds);
          fmt::print("{:<9} {:>5} {:>4} {:<8} {:>10.6f} {:>10.2e} {:>10} {:>8.3f} {:>12.3g}\n",
                     distribution == walk::Distribution::ggx ? "ggx" : "beckmann", alpha, mu,
                     f == &one ? "one" : "f0=0.04", a.multiple.value, a.multiple.error, options.paths, seconds,
                     double(options.paths) / seconds);
        }
  fmt::print("slowest cell to a standard error of {:g} on the multiply scattered albedo: {:.3f} s on one core\n",
             kTarget, worst);
}
