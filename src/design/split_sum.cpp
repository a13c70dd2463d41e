#include "split_sum.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <vector>

#include "specula/analysis/albedo.h"
#include "specula/catalogue/catalogue.h"

namespace specula::design {
namespace {

constexpr int kN = kSplitSumNodes;
constexpr double kSmallestMu = 1e-6, kSmallestAlpha = 0.001;

using Table = std::vector<double>;  // [i_u * kN + i_r]

Table tabulate(const std::string& model, SplitSumPart part) {
  Table t(kN * kN);
  // Isolated: a thread waiting here under table()'s lock takes no other task of the search, which
  // could ask for the table again.
  tbb::this_task_arena::isolate([&] { tbb::parallel_for(0, kN * kN, [&](int k) {
    const double u = static_cast<double>(k / kN) / (kN - 1), v = static_cast<double>(k % kN) / (kN - 1);
    const double mu = std::max(u * u * u * u, kSmallestMu), r = v * v, alpha = std::max(r * r, kSmallestAlpha);
    const bool a = part == SplitSumPart::a;
    const Model m = make_model(model, {{"alpha", alpha}, {"f0", a ? 1.0 : 0.0}, {"f90", a ? 0.0 : 1.0}});
    t[static_cast<std::size_t>(k)] = analysis::albedo(m, std::acos(mu)).value;
  }); });
  return t;
}

// Catmull–Rom weights of the four nodes around a point at fraction t of its cell.
std::array<double, 4> catmull_rom(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {(-t3 + 2 * t2 - t) / 2, (3 * t3 - 5 * t2 + 2) / 2, (-3 * t3 + 4 * t2 + t) / 2, (t3 - t2) / 2};
}

double interpolate(const Table& t, double u, double r) {
  const auto cell = [](double x, int& i) {
    const double scaled = std::clamp(x, 0.0, 1.0) * (kN - 1);
    i = std::min(static_cast<int>(scaled), kN - 2);
    return scaled - i;
  };
  int iu = 0, ir = 0;
  const auto wu = catmull_rom(cell(u, iu)), wr = catmull_rom(cell(r, ir));
  const auto at = [&](int a, int b) { return t[static_cast<std::size_t>(a * kN + b)]; };
  // Past an end, the line through the last two nodes (a repeated node would flatten the last cell).
  const auto along_r = [&](int a, int b) {
    return b < 0 ? 2 * at(a, 0) - at(a, 1) : b >= kN ? 2 * at(a, kN - 1) - at(a, kN - 2) : at(a, b);
  };
  const auto node = [&](int a, int b) {
    return a < 0 ? 2 * along_r(0, b) - along_r(1, b) : a >= kN ? 2 * along_r(kN - 1, b) - along_r(kN - 2, b) : along_r(a, b);
  };
  double sum = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) sum += wu[a] * wr[b] * node(iu - 1 + a, ir - 1 + b);
  return sum;
}

const Table& table(std::string_view model, SplitSumPart part) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, SplitSumPart>, std::shared_ptr<const Table>> tables;
  const std::lock_guard lock(mutex);
  auto& slot = tables[{std::string(model), part}];
  if (!slot) slot = std::make_shared<const Table>(tabulate(std::string(model), part));
  return *slot;
}

}  // namespace

double split_sum(std::string_view model, SplitSumPart part, double mu, double r) {
  // A cubic overshoots by a few 10⁻⁶ below 0 where B vanishes (the mirror at normal incidence).
  return std::max(0.0, interpolate(table(model, part), std::sqrt(std::sqrt(std::clamp(mu, 0.0, 1.0))),
                                   std::sqrt(std::clamp(r, 0.0, 1.0))));
}

}  // namespace specula::design
