// The lobe benchmark's measurements (include/specula/cost/lobe_cost.h). Timings are the fastest
// of several trials (other work on the machine only slows a trial down) and go round the rows in
// turn, so that a disturbance hits one trial of several rows rather than every trial of one.
#include "specula/cost/lobe_cost.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <random>
#include <span>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "specula/analysis/error.h"
#include "specula/exceptions.h"
#include "specula/families/families.h"
#include "specula/catalogue/catalogue.h"
#include "specula/simd/targets.h"

namespace specula::cost {
namespace {

using Clock = std::chrono::steady_clock;
using simd::Family;

/// The built-in lobe families (families/families.h), in simd::Family order.
std::span<const families::Family* const> lobe_families() {
  return std::span(families::kFamilies).first(families::kLobeFamilyCount);
}
constexpr auto kPaths = enumerators<Path, kPathCount>();

/// best = the smaller of best and value; NaN (nothing measured yet) gives value.
void keep_fastest(double& best, double value) { best = std::isnan(best) ? value : std::min(best, value); }

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Makes a value observable so that the loop computing it cannot be dropped.
template <class T>
void keep(T* data) {
  asm volatile("" : : "r"(data) : "memory");
}

/// The family's scalar double lobe at n, its other parameters at their defaults.
lobes::Lobe scalar_lobe(Family family, double n) {
  const families::Family& definition = families::lobe_family(family);
  std::vector<double> values;
  for (const auto& p : definition.params) values.push_back(p.name == "n" ? n : p.default_value);
  return definition.make_lobe(values);
}

/// The user lobes of one precision, by model id: each model's Formula at n rounded to T.
using UserLobes = std::vector<std::pair<std::string, lobes::Lobe>>;

template <class T>
UserLobes user_lobes(const Settings& s) {
  UserLobes out;
  for (const std::string& id : s.user_lobes) {
    const ModelInfo* info = find_model(id);
    if (!info || info->kind != ModelKind::lobe) throw InvalidArgument(fmt::format("bench: '{}' is not a lobe model", id));
    ParamValues values;
    if (info->find_param("n")) values["n"] = double(T(s.n));
    out.emplace_back(id, make_model(id, values).lobe());
  }
  return out;
}

/// The user lobe a row measures; nullptr for a built-in family.
const lobes::Lobe* user_lobe(const Measurement& m, const UserLobes& users) {
  if (m.family != Family::formula) return nullptr;
  for (const auto& [id, lobe] : users)
    if (id == m.lobe) return &lobe;
  throw InvalidArgument(fmt::format("bench: no user lobe '{}'", m.lobe));
}

/// The scalar path in lane type T: a built-in family's lobe struct in T per value, inlined
/// (lobes::eval_batch); a user lobe's Formula per value (expr::Program::evaluate, libm), in double.
template <class T>
void scalar_batch(const lobes::Lobe& lobe, std::span<const T> c, std::span<T> out) {
  std::visit(
      [&](const auto& l) {
        if constexpr (requires { l.template as<T>(); }) {
          lobes::eval_batch(l.template as<T>(), c, out);
        } else {
          for (std::size_t i = 0; i < c.size(); ++i) out[i] = T(l(double(c[i])));
        }
      },
      lobe);
}

/// The SIMD tier of a SIMD path (the scalar path has none).
simd::Tier tier_of(Path path) {
  switch (path) {
    case Path::exact: return simd::Tier::exact;
    case Path::fast: return simd::Tier::fast;
    case Path::scalar: break;
  }
  unreachable();
}

/// One row's evaluation of a whole array.
template <class T>
struct Evaluator {
  Family family;
  Path path;
  double n;
  const lobes::Lobe* user = nullptr;  ///< a user lobe (family == Family::formula)
  lobes::Lobe scalar;                 ///< the scalar lobe: the user's, or the family's at n in T

  simd::LobeSpec spec() const { return user ? simd::spec_of(*user) : simd::LobeSpec{family, double(T(n))}; }
  void operator()(std::span<const T> c, std::span<T> out) const {
    if (path == Path::scalar) return scalar_batch<T>(scalar, c, out);
    simd::eval_batch(spec(), tier_of(path), c, out);
  }
};

/// Cosines as shading sees them near a highlight (bench/lobes_bench.cpp's "peaked"): θ = (π/2)x²,
/// x stratified on (0, 1), shuffled with a fixed seed; the pattern repeats to fill `count`.
template <class T>
std::vector<T> peaked_cosines(std::size_t count) {
  constexpr std::size_t kPattern = 4096;
  std::vector<T> pattern(kPattern);
  for (std::size_t i = 0; i < kPattern; ++i) {
    const double x = (double(i) + 0.5) / double(kPattern);
    pattern[i] = T(std::cos(std::numbers::pi / 2 * x * x));
  }
  std::shuffle(pattern.begin(), pattern.end(), std::mt19937(20231105u));
  std::vector<T> c(count);
  for (std::size_t i = 0; i < count; ++i) c[i] = pattern[i % kPattern];
  return c;
}

// ---------------------------------------------------------------------------------------------
// Timing

/// ns per value of one in-cache trial: whole passes over `c` until `seconds` have gone by. The
/// clock is read every 64 passes: once per pass would add ~20 ns to a 4 KiB pass of a lobe that
/// takes 0.1 ns per value.
template <class T, class Eval>
double cache_trial(const Eval& eval, std::span<const T> c, std::span<T> out, double seconds) {
  constexpr std::size_t kPassesPerClock = 64;
  std::size_t values = 0;
  const auto start = Clock::now();
  double elapsed = 0;
  do {
    for (std::size_t p = 0; p < kPassesPerClock; ++p) {
      keep(c.data());
      eval(c, out);
      keep(out.data());
    }
    values += kPassesPerClock * c.size();
    elapsed = seconds_since(start);
  } while (elapsed < seconds);
  return elapsed * 1e9 / double(values);
}

/// ns per value per core with every thread of `arena` on its own in-cache arrays, each running
/// `passes` passes.
template <class T>
double cache_threads_trial(tbb::task_arena& arena, const Evaluator<T>& eval, std::span<const T> c, std::size_t passes) {
  const int threads = arena.max_concurrency();
  const auto start = Clock::now();
  arena.execute([&] {
    tbb::parallel_for(0, threads, [&](int) {
      std::vector<T> in(c.begin(), c.end()), out(c.size());
      for (std::size_t p = 0; p < passes; ++p) {
        keep(in.data());
        eval(in, out);
        keep(out.data());
      }
    });
  });
  // wall time × threads ÷ (passes × size × threads) values
  return seconds_since(start) * 1e9 / (double(passes) * double(c.size()));
}

/// ns per value per core of one pass over the large arrays, on one core or split over all.
template <class T>
double stream_pass(tbb::task_arena* arena, const Evaluator<T>& eval, std::span<const T> c, std::span<T> out) {
  const auto start = Clock::now();
  if (!arena) {
    eval(c, out);
  } else {
    arena->execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, c.size(), 1 << 16), [&](const auto& r) {
        eval(c.subspan(r.begin(), r.size()), out.subspan(r.begin(), r.size()));
      });
    });
  }
  keep(out.data());
  const int cores = arena ? arena->max_concurrency() : 1;
  return seconds_since(start) * 1e9 * cores / double(c.size());
}

template <class T>
Evaluator<T> evaluator(const Measurement& m, double n, const UserLobes& users) {
  const lobes::Lobe* user = user_lobe(m, users);
  return {m.family, m.path, n, user, user ? *user : scalar_lobe(m.family, double(T(n)))};
}

template <class T>
void time_in_cache(std::vector<Measurement>& rows, const Settings& s, const UserLobes& users, tbb::task_arena& arena) {
  const std::vector<T> c = peaked_cosines<T>(std::max<std::size_t>(s.cache_bytes / sizeof(T), 1));
  std::vector<T> out(c.size());
  for (auto& m : rows) cache_trial(evaluator<T>(m, s.n, users), std::span<const T>(c), std::span<T>(out), s.trial_seconds / 4);
  for (int trial = 0; trial < s.trials; ++trial)
    for (auto& m : rows) {
      const double ns = cache_trial(evaluator<T>(m, s.n, users), std::span<const T>(c), std::span<T>(out), s.trial_seconds);
      keep_fastest(m.cache_ns, ns);
    }
  if (!s.threaded) return;
  for (int trial = 0; trial < s.trials; ++trial)
    for (auto& m : rows) {
      const auto passes = std::size_t(std::max(1.0, s.trial_seconds * 1e9 / (m.cache_ns * double(c.size()))));
      const double ns = cache_threads_trial(arena, evaluator<T>(m, s.n, users), std::span<const T>(c), passes);
      keep_fastest(m.cache_threads_ns, ns);
    }
}

template <class T>
void time_streaming(std::vector<Measurement>& rows, const Settings& s, const UserLobes& users, tbb::task_arena& arena) {
  const std::vector<T> c = peaked_cosines<T>(s.stream_bytes / sizeof(T));
  std::vector<T> out(c.size());
  const int passes = (s.trials + 1) / 2;
  for (int pass = 0; pass < passes; ++pass)
    for (auto& m : rows) {
      const double one = stream_pass<T>(nullptr, evaluator<T>(m, s.n, users), c, out);
      keep_fastest(m.stream_ns, one);
      if (!s.threaded) continue;
      const double all = stream_pass<T>(&arena, evaluator<T>(m, s.n, users), c, out);
      keep_fastest(m.stream_threads_ns, all);
    }
}

// ---------------------------------------------------------------------------------------------
// Accuracy and the machine

/// Cosines for the accuracy columns: dense in c, in t = −n log₂ c (the log lobe's variable) and in
/// the angle, as tests/simd does (which enforces the stated bounds over many more n).
template <class T>
std::vector<T> accuracy_cosines(double n, std::size_t points) {
  std::vector<T> c;
  for (std::size_t i = 0; i <= points; ++i) {
    const double x = double(i) / double(points);
    c.push_back(T(x));
    c.push_back(T(std::exp2(-4 * x / n)));
    c.push_back(T(std::cos(std::min(std::sqrt(60 / n), std::numbers::pi / 2) * x)));
  }
  return c;
}

template <class T>
void measure_accuracy(std::vector<Measurement>& rows, const Settings& s, const UserLobes& users) {
  const std::vector<T> c = accuracy_cosines<T>(double(T(s.n)), s.accuracy_points);
  std::vector<T> out(c.size());
  for (auto& m : rows) {
    evaluator<T>(m, s.n, users)(c, out);
    const Evaluator<T> eval = evaluator<T>(m, s.n, users);
    const lobes::Lobe& reference = eval.scalar;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double f = lobes::eval(reference, double(c[i])), error = std::abs(double(out[i]) - f);
      m.max_abs_error = std::max(m.max_abs_error, error);
      if (f >= 1e-3) m.max_rel_error = std::max(m.max_rel_error, error / f);
    }
    if (m.path != Path::scalar) m.ops_per_value = simd::ops_per_value(eval.spec(), tier_of(m.path), sizeof(T) == 4);
  }
}

/// Bytes per second of a streaming copy (read + written), on one core or all.
double copy_bandwidth(tbb::task_arena* arena, std::size_t bytes, int passes) {
  const std::vector<float> in = peaked_cosines<float>(bytes / sizeof(float));
  std::vector<float> out(in.size());
  double best = INFINITY;
  for (int p = 0; p < passes; ++p) {
    const auto start = Clock::now();
    if (!arena) {
      simd::stream_copy(in.data(), out.data(), in.size());
    } else {
      arena->execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), 1 << 16), [&](const auto& r) {
          simd::stream_copy(in.data() + r.begin(), out.data() + r.begin(), r.size());
        });
      });
    }
    keep(out.data());
    best = std::min(best, seconds_since(start));
  }
  return 2.0 * double(in.size() * sizeof(float)) / best;
}

double sum_bandwidth(std::size_t bytes, int passes) {
  const std::vector<float> in = peaked_cosines<float>(bytes / sizeof(float));
  double best = INFINITY;
  for (int p = 0; p < passes; ++p) {
    const auto start = Clock::now();
    volatile float sink = simd::stream_sum(in.data(), in.size());
    (void)sink;
    best = std::min(best, seconds_since(start));
  }
  return double(in.size() * sizeof(float)) / best;
}

Machine measure_machine(const Settings& s, tbb::task_arena& arena) {
  const simd::TargetInfo target = simd::current_target();
  Machine m{target.name, target.lanes_f32, target.lanes_f64, arena.max_concurrency()};
  for (int t = 0; t < std::max(1, s.trials); ++t)
    m.fma_per_s = std::isnan(m.fma_per_s) ? simd::measure_fma_per_second(s.trial_seconds)
                                          : std::max(m.fma_per_s, simd::measure_fma_per_second(s.trial_seconds));
  if (!s.streaming) return m;
  const int passes = 2 * s.trials;  // one pass is noisy; the lobes' streams run many more
  m.copy_bytes_per_s = copy_bandwidth(nullptr, s.stream_bytes, passes);
  if (s.threaded) m.copy_bytes_per_s_all = copy_bandwidth(&arena, s.stream_bytes, passes);
  m.sum_bytes_per_s = sum_bandwidth(s.stream_bytes, passes);
  return m;
}

std::vector<Measurement> rows_for(bool single, const Settings& s) {
  std::vector<Measurement> rows;
  for (const families::Family* family : lobe_families())
    for (const Path path : kPaths) rows.push_back({family->simd, std::string(family->name), path, single});
  for (const std::string& id : s.user_lobes)
    for (const Path path : kPaths) rows.push_back({Family::formula, id, path, single});
  return rows;
}

template <class T>
std::vector<Measurement> measure_precision(const Settings& s, tbb::task_arena& arena,
                                           const std::function<void(std::string_view)>& progress) {
  std::vector<Measurement> rows = rows_for(sizeof(T) == 4, s);
  const UserLobes users = user_lobes<T>(s);
  const char* type = sizeof(T) == 4 ? "float" : "double";
  progress(std::string("lobes in ") + type + ": accuracy");
  measure_accuracy<T>(rows, s, users);
  progress(std::string("lobes in ") + type + ": in cache");
  time_in_cache<T>(rows, s, users, arena);
  if (s.streaming) {
    progress(std::string("lobes in ") + type + ": streaming");
    time_streaming<T>(rows, s, users, arena);
  }
  return rows;
}

}  // namespace

namespace {

// The paths' names ("" outside the enum).
constexpr const char* name_of(Path path) noexcept {
  switch (path) {
    case Path::scalar: return "scalar";
    case Path::exact: return "exact";
    case Path::fast: return "fast";
  }
  return "";
}
static_assert(names_complete<Path, kPathCount>(name_of));

}  // namespace

const char* to_string(Path path) noexcept { return name_of(path); }

Settings Settings::quick() {
  Settings s;
  s.stream_bytes = 16u << 20;
  s.trial_seconds = 0.004;
  s.trials = 3;
  s.accuracy_points = 1 << 12;
  return s;
}

Settings Settings::with_registered_user_lobes() const {
  Settings s = *this;
  s.user_lobes.clear();
  for (const ModelInfo& info : models())
    if (!info.is_builtin() && info.kind == ModelKind::lobe) s.user_lobes.push_back(info.id);
  return s;
}

Settings Settings::report(bool quick) {
  Settings s = quick ? Settings::quick() : Settings::full();
  s.streaming = false;
  s.threaded = false;
  if (quick) s.trials = 2;
  return s;
}

const Measurement& Result::at(Family family, Path path, bool single) const {
  for (const auto& m : rows)
    if (m.family == family && m.path == path && m.single == single) return m;
  throw InvalidArgument("bench: no such measurement");
}

const Measurement& Result::at(std::string_view lobe, Path path, bool single) const {
  for (const auto& m : rows)
    if (m.lobe == lobe && m.path == path && m.single == single) return m;
  throw InvalidArgument(fmt::format("bench: no measurement of '{}'", lobe));
}

double Result::compute_limit_ns(const Measurement& m) const noexcept {
  return m.ops_per_value / machine.fma_per_s * 1e9;
}

double Result::memory_limit_ns(const Measurement& m, bool all_cores) const noexcept {
  const double bytes = 2.0 * (m.single ? 4 : 8);
  const double bandwidth = all_cores ? machine.copy_bytes_per_s_all / machine.threads : machine.copy_bytes_per_s;
  return bytes / bandwidth * 1e9;
}

Result run(const Settings& settings, const std::function<void(std::string_view)>& progress_callback) {
  if (!(settings.n > 0) || settings.cache_bytes < 64 || settings.trials < 1 || !(settings.trial_seconds > 0))
    throw InvalidArgument("bench: n, array sizes, trials and trial length must be positive");
  auto progress = [&](std::string_view what) {
    if (progress_callback) progress_callback(what);
  };
  tbb::task_arena arena;
  Result result{settings, {}, {}, {}, {}};
  progress("machine: peak FMA rate and streaming bandwidth");
  result.machine = measure_machine(settings, arena);
  result.rows = measure_precision<float>(settings, arena, progress);
  if (settings.doubles) {
    auto rows = measure_precision<double>(settings, arena, progress);
    result.rows.insert(result.rows.end(), rows.begin(), rows.end());
  }
  progress("lobes against cⁿ");
  for (const families::Family* family : lobe_families()) {
    result.lobes.emplace_back(family->name);
    result.error_vs_power.push_back(
        analysis::approximation_error(scalar_lobe(family->simd, settings.n), lobes::Power<double>{settings.n}).max_abs);
  }
  for (const auto& [id, lobe] : user_lobes<double>(settings)) {
    result.lobes.push_back(id);
    result.error_vs_power.push_back(analysis::approximation_error(lobe, lobes::Power<double>{settings.n}).max_abs);
  }
  return result;
}

std::vector<double> time_in_cache(std::span<const FloatKernel> kernels, const Settings& s) {
  const std::vector<float> c = peaked_cosines<float>(std::max<std::size_t>(s.cache_bytes / sizeof(float), 1));
  std::vector<float> out(c.size());
  std::vector<double> fastest(kernels.size(), NAN);
  for (const auto& kernel : kernels) cache_trial(kernel, std::span<const float>(c), std::span<float>(out), s.trial_seconds / 4);
  for (int trial = 0; trial < s.trials; ++trial)
    for (std::size_t k = 0; k < kernels.size(); ++k)
      keep_fastest(fastest[k], cache_trial(kernels[k], std::span<const float>(c), std::span<float>(out), s.trial_seconds));
  return fastest;
}

FloatKernel lobe_kernel(const lobes::Lobe& lobe, Path path) {
  if (path == Path::scalar) return [lobe](std::span<const float> c, std::span<float> out) { scalar_batch<float>(lobe, c, out); };
  return [lobe, tier = tier_of(path)](std::span<const float> c, std::span<float> out) {
    simd::eval_batch(simd::spec_of(lobe), tier, c, out);
  };
}

}  // namespace specula::cost
