// specula_lut_bench: a 32 × 32 GGX energy table E(μ, α) (f0 = 1) by specula's deterministic
// cubature against the same table by Monte Carlo with 2²³ samples per cell (Blender Cycles'
// setting) and GGX visible-normal sampling (Heitz 2018), both over cells with oneTBB; wall time and
// max |error| of each against tests/reference/ggx_lut.csv (made by
// tests/reference/make_ggx_lut_reference.py). A measurement: nothing here fails on a slow machine.
// `specula_lut_bench [SAMPLES_LOG2]` (default 23) for a shorter Monte-Carlo run.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <tbb/parallel_for.h>
#include <vector>

#include "specula/analysis/energy.h"
#include "specula/brdf/ggx.h"
#include "specula/catalogue/catalogue.h"

namespace {

using specula::Vec3;

struct Cell {
  double alpha, mu, reference;
};

std::vector<Cell> read_reference() {
  std::ifstream file(SPECULA_GGX_LUT_REFERENCE);
  if (!file) throw std::runtime_error("cannot open " SPECULA_GGX_LUT_REFERENCE);
  std::string line;
  std::getline(file, line);  // alpha,mu,E
  std::vector<Cell> cells;
  Cell c{};
  while (std::getline(file, line))
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf", &c.alpha, &c.mu, &c.reference) == 3) cells.push_back(c);
  if (cells.size() != 32 * 32) throw std::runtime_error("ggx_lut.csv: expected 1024 cells");
  return cells;
}

/// Heitz 2018: a microfacet normal m drawn from GGX's visible normals seen from `i` (local frame).
Vec3 sample_visible_normal(const Vec3& i, double alpha, double u1, double u2) {
  const Vec3 vh = specula::normalized(Vec3{alpha * i.x, alpha * i.y, i.z});
  const double lensq = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = lensq > 0 ? Vec3{-vh.y, vh.x, 0} * (1 / std::sqrt(lensq)) : Vec3{1, 0, 0};
  const Vec3 t2 = specula::cross(vh, t1);
  const double r = std::sqrt(u1), phi = 2 * std::numbers::pi * u2;
  const double p1 = r * std::cos(phi), s = 0.5 * (1 + vh.z);
  const double p2 = (1 - s) * std::sqrt(1 - p1 * p1) + s * r * std::sin(phi);
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
  return specula::normalized(Vec3{alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)});
}

/// E(μ) = E over visible normals of G₂(i, o)/G₁(i) (F = 1), o the mirror of i about m.
double monte_carlo_albedo(double alpha, double mu, std::uint64_t samples, std::uint64_t seed) {
  const Vec3 i{std::sqrt(1 - mu * mu), 0, mu};
  const double a2 = alpha * alpha;
  const double lambda_i = specula::Ggx::smith_lambda(mu, a2);
  std::mt19937_64 rng(seed);
  constexpr double kToUnit = 0x1p-53;
  double sum = 0;
  for (std::uint64_t k = 0; k < samples; ++k) {
    const double u1 = static_cast<double>(rng() >> 11) * kToUnit, u2 = static_cast<double>(rng() >> 11) * kToUnit;
    const Vec3 m = sample_visible_normal(i, alpha, u1, u2);
    const double mu_o = 2 * specula::dot(i, m) * m.z - mu;
    if (mu_o > 0) sum += (1 + lambda_i) / (1 + lambda_i + specula::Ggx::smith_lambda(mu_o, a2));
  }
  return sum / static_cast<double>(samples);
}

struct Run {
  double seconds = 0, max_error = 0, mean_error = 0;
};

template <class F>
Run timed(const std::vector<Cell>& cells, const F& table) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> e = table();
  Run run{std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const double error = std::abs(e[k] - cells[k].reference);
    run.max_error = std::max(run.max_error, error);
    run.mean_error += error / static_cast<double>(cells.size());
  }
  return run;
}

std::vector<double> axis(const std::vector<Cell>& cells, bool alpha) {
  std::vector<double> v;
  for (std::size_t k = 0; k < 32; ++k) v.push_back(alpha ? cells[k * 32].alpha : cells[k].mu);
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const int log2_samples = argc > 1 ? std::atoi(argv[1]) : 23;
  if (log2_samples < 1 || log2_samples > 30) {
    std::fprintf(stderr, "usage: specula_lut_bench [SAMPLES_LOG2 in 1..30]\n");
    return 2;
  }
  const std::uint64_t samples = std::uint64_t{1} << log2_samples;
  const std::vector<Cell> cells = read_reference();
  const std::vector<double> alphas = axis(cells, true), mus = axis(cells, false);

  const Run cubature = timed(cells, [&] {
    const auto ggx = [](double alpha) { return specula::make_model("ggx", {{"alpha", alpha}, {"f0", 1}}); };
    return specula::analysis::albedo_lut(ggx, alphas, mus, false).e;
  });
  const Run monte_carlo = timed(cells, [&] {
    std::vector<double> e(cells.size());
    tbb::parallel_for(std::size_t{0}, cells.size(), [&](std::size_t k) {
      e[k] = monte_carlo_albedo(cells[k].alpha, cells[k].mu, samples, 0x9e3779b97f4a7c15ULL * (k + 1));
    });
    return e;
  });

  fmt::print("GGX E(mu, alpha), f0 = 1, 32 x 32 cells (alpha = 0.05:1@32, mu = 0.03125:1@32), both over cells\n"
             "with oneTBB; errors against tests/reference/ggx_lut.csv (a second method, 1e-13)\n\n");
  fmt::print("{:<40}  {:>10}  {:>12}  {:>12}\n", "method", "wall time", "max |error|", "mean |error|");
  fmt::print("{:<40}  {:>8.3f} s  {:>12.3g}  {:>12.3g}\n", "specula cubature (analysis::albedo_lut)", cubature.seconds,
             cubature.max_error, cubature.mean_error);
  fmt::print("{:<40}  {:>8.3f} s  {:>12.3g}  {:>12.3g}\n", fmt::format("Monte Carlo, 2^{} VNDF samples per cell", log2_samples),
             monte_carlo.seconds, monte_carlo.max_error, monte_carlo.mean_error);
  fmt::print("\nspecula is {:.3g}x faster and {:.3g}x more accurate (max |error|) than Monte Carlo\n",
             monte_carlo.seconds / cubature.seconds, monte_carlo.max_error / cubature.max_error);
  return 0;
}
