// The lobe benchmark's output: plain-text tables with ratios and limits, and JSON.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "specula/cost/lobe_cost.h"
#include "specula/exceptions.h"

namespace specula::cost {
namespace {

using simd::Family;

constexpr auto kPaths = enumerators<Path, kPathCount>();

std::string cell(double v, const char* spec = "{:.3g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(spec), v) : "—";
}

/// Where a measured time sits against its limit: the limit's share of the time (100 % = at it).
double at_limit(double ns, double limit_ns) { return limit_ns / ns; }

/// The binding limit for streaming: the slower of compute and memory, and which it is.
std::pair<double, const char*> nearer_limit(const Result& r, const Measurement& m, bool all_cores) {
  const double compute = r.compute_limit_ns(m), memory = r.memory_limit_ns(m, all_cores);
  if (!std::isfinite(compute)) return {memory, "memory"};
  return compute >= memory ? std::pair{compute, "compute"} : std::pair{memory, "memory"};
}

std::string machine_lines(const Result& r) {
  const Machine& m = r.machine;
  std::string out = fmt::format(
      "specula bench: every lobe at n = {}, Highway target {} ({} float / {} double lanes), {} core{}\n"
      "peak vector rate (measured, 12 independent FMA chains): {} vector FMA/s per core = {} float lane-FMA/s\n",
      r.settings.n, m.target, m.lanes_f32, m.lanes_f64, m.threads, m.threads > 1 ? "s" : "", cell(m.fma_per_s),
      cell(m.fma_per_s * double(m.lanes_f32)));
  if (std::isfinite(m.copy_bytes_per_s))
    out += fmt::format("streaming copy (read + write, {} MiB arrays): {} GB/s on one core, {} GB/s on {}; "
                       "read-only sum: {} GB/s on one core\n",
                       r.settings.stream_bytes >> 20, cell(m.copy_bytes_per_s / 1e9), cell(m.copy_bytes_per_s_all / 1e9),
                       m.threads, cell(m.sum_bytes_per_s / 1e9));
  return out;
}

std::string row_line(const Result& r, const Measurement& m, const Measurement& libm) {
  const double compute = r.compute_limit_ns(m);
  const auto [stream_limit, which] = nearer_limit(r, m, false);
  return fmt::format("{:<17} {:<6} {:>9} {:>9} {:>9} {:>9} {:>11} {:>7} {:>10} {:>9} {:>9} {:>8} {:>10}\n",
                     m.path == Path::scalar ? m.lobe : "", to_string(m.path), cell(m.cache_ns),
                     cell(m.cache_threads_ns), cell(m.stream_ns), cell(m.stream_threads_ns),
                     cell(m.evals_per_s_per_core()), cell(libm.cache_ns / m.cache_ns, "{:.3g}×"),
                     cell(m.max_rel_error, "{:.2g}"), cell(m.ops_per_value), cell(compute),
                     cell(100 * at_limit(m.cache_ns, compute), "{:.0f} %"),
                     std::isfinite(m.stream_ns) && std::isfinite(compute)
                         ? fmt::format("{:.0f} % {}", 100 * at_limit(m.stream_ns, stream_limit), which)
                         : "—");
}

std::string precision_table(const Result& r, bool single) {
  std::string out = fmt::format(
      "\n{}: ns per evaluation per core (c = 1c one core, {}c all cores; cache: {} B arrays; stream: {} MiB)\n"
      "{:<17} {:<6} {:>9} {:>9} {:>9} {:>9} {:>11} {:>7} {:>10} {:>9} {:>9} {:>8} {:>10}\n",
      single ? "float" : "double", r.machine.threads, r.settings.cache_bytes, r.settings.stream_bytes >> 20, "lobe",
      "path", "cache 1c", "cache " + std::to_string(r.machine.threads) + "c", "stream 1c",
      "stream " + std::to_string(r.machine.threads) + "c", "evals/s/core", "× libm", "max rel err", "ops/value",
      "limit ns", "of limit", "stream");
  for (const std::string& lobe : r.lobes)
    for (const Path p : kPaths) out += row_line(r, r.at(lobe, p, single), r.at(lobe, Path::scalar, single));
  return out;
}

std::string baselines(const Result& r) {
  const auto& pow_libm = r.at(Family::power, Path::scalar, true);
  const auto& pow_exact = r.at(Family::power, Path::exact, true);
  const auto& pow_fast = r.at(Family::power, Path::fast, true);
  std::string out = fmt::format(
      "\nbaselines (float, in cache, one core): cⁿ through libm (std::pow) {} ns; through the SIMD path {} ns exact "
      "({}× libm), {} ns fast ({}×); Schlick's rational form c/(n − nc + c): {} ns scalar, {} ns SIMD\n"
      "{:<17} {:>12} {:>12} {:>12} {:>14}\n",
      cell(pow_libm.cache_ns), cell(pow_exact.cache_ns), cell(pow_libm.cache_ns / pow_exact.cache_ns),
      cell(pow_fast.cache_ns), cell(pow_libm.cache_ns / pow_fast.cache_ns), cell(r.at(Family::schlick, Path::scalar, true).cache_ns),
      cell(r.at(Family::schlick, Path::exact, true).cache_ns), "lobe", "÷ libm cⁿ", "÷ SIMD cⁿ", "÷ fast cⁿ",
      "max |F − cⁿ|");
  for (std::size_t i = 0; i < r.lobes.size(); ++i) {
    const std::string& f = r.lobes[i];
    out += fmt::format("{:<17} {:>12} {:>12} {:>12} {:>14}\n", f,
                       cell(r.at(f, Path::scalar, true).cache_ns / pow_libm.cache_ns, "{:.3g}×"),
                       cell(r.at(f, Path::exact, true).cache_ns / pow_exact.cache_ns, "{:.3g}×"),
                       cell(r.at(f, Path::fast, true).cache_ns / pow_fast.cache_ns, "{:.3g}×"),
                       cell(r.error_vs_power[i], "{:.4g}"));
  }
  return out;
}

std::string limits_note(const Result& r) {
  return fmt::format(
      "\nlimits: compute = ops/value ÷ peak vector rate (every arithmetic, compare, select and conversion op counted "
      "as one FMA slot; loads and stores not counted, so a kernel of cheap ops can pass 100 %); memory = bytes "
      "per value (read c, write F: {} float, {} double) ÷ streaming copy bandwidth = {} ns float, {} ns double on one "
      "core. \"of limit\" = limit ÷ measured time in cache (compute); \"stream\" = the same for one core streaming, "
      "against the nearer (binding) limit. Times are the fastest of {} trials.\n",
      8, 16, cell(r.memory_limit_ns(r.rows.front(), false)),
      r.settings.doubles ? cell(r.memory_limit_ns(r.at(Family::power, Path::scalar, false), false)) : "—",
      r.settings.trials);
}

nlohmann::ordered_json measurement_json(const Result& r, const Measurement& m) {
  auto number = [](double v) -> nlohmann::ordered_json { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; };
  nlohmann::ordered_json j;
  j["evals_per_s_per_core"] = number(m.evals_per_s_per_core());
  j["max_rel_error"] = m.max_rel_error;
  j["max_abs_error"] = m.max_abs_error;
  j["ns_per_eval"] = {{"cache", number(m.cache_ns)}, {"cache_all_cores", number(m.cache_threads_ns)},
                      {"stream", number(m.stream_ns)}, {"stream_all_cores", number(m.stream_threads_ns)}};
  j["ratio_to_scalar"] = number(r.at(m.lobe, Path::scalar, m.single).cache_ns / m.cache_ns);
  j["ops_per_value"] = number(m.ops_per_value);
  j["compute_limit_ns"] = number(r.compute_limit_ns(m));
  j["memory_limit_ns"] = number(r.memory_limit_ns(m, false));
  const auto [limit, which] = nearer_limit(r, m, false);
  j["stream_nearer_limit"] = std::isfinite(m.stream_ns) && std::isfinite(limit) ? nlohmann::ordered_json(which) : nullptr;
  j["stream_share_of_limit"] = number(limit / m.stream_ns);
  j["cache_share_of_compute_limit"] = number(r.compute_limit_ns(m) / m.cache_ns);
  return j;
}

nlohmann::ordered_json lobe_json(const Result& r, std::size_t i) {
  const std::string& f = r.lobes[i];
  nlohmann::ordered_json lobe;
  lobe["user_model"] = r.at(f, Path::scalar, true).family == Family::formula;
  lobe["max_abs_error_vs_power"] = r.error_vs_power[i];
  for (const Path p : kPaths) {
    const Measurement& single = r.at(f, p, true);
    nlohmann::ordered_json tier;
    tier["evals_per_s_per_core"] = single.evals_per_s_per_core();  // in cache, float, one core
    tier["max_rel_error"] = single.max_rel_error;                   // float, against the scalar double lobe
    tier["float"] = measurement_json(r, single);
    if (r.settings.doubles) tier["double"] = measurement_json(r, r.at(f, p, false));
    lobe[to_string(p)] = std::move(tier);
  }
  return lobe;
}

}  // namespace

std::string to_table(const Result& result) {
  std::string out = machine_lines(result) + precision_table(result, true);
  if (result.settings.doubles) out += precision_table(result, false);
  return out + baselines(result) + limits_note(result);
}

std::string to_json(const Result& result) {
  const Machine& m = result.machine;
  auto number = [](double v) -> nlohmann::ordered_json { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; };
  nlohmann::ordered_json j;
  j["n"] = result.settings.n;
  j["machine"] = {{"target", m.target},
                  {"lanes_f32", m.lanes_f32},
                  {"lanes_f64", m.lanes_f64},
                  {"cores", m.threads},
                  {"peak_vector_fma_per_s", number(m.fma_per_s)},
                  {"copy_bytes_per_s", number(m.copy_bytes_per_s)},
                  {"copy_bytes_per_s_all_cores", number(m.copy_bytes_per_s_all)},
                  {"sum_bytes_per_s", number(m.sum_bytes_per_s)}};
  j["settings"] = {{"cache_bytes", result.settings.cache_bytes}, {"stream_bytes", result.settings.stream_bytes},
                   {"trial_seconds", result.settings.trial_seconds}, {"trials", result.settings.trials},
                   {"streaming", result.settings.streaming}, {"threaded", result.settings.threaded}};
  for (std::size_t i = 0; i < result.lobes.size(); ++i) j["lobes"][result.lobes[i]] = lobe_json(result, i);
  return j.dump(2) + "\n";
}

}  // namespace specula::cost
