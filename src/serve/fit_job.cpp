#include "fit_job.h"

#include <cmath>
#include <fmt/format.h>
#include <set>

#include "fields.h"
#include "specula/exceptions.h"
#include "specula/fit/emit.h"
#include "specula/fit/fit.h"
#include "specula/interrupt/interrupt.h"

namespace specula::serve {

namespace {

using Json = nlohmann::ordered_json;

/// One search: its inputs, fixed at start, and what the search has reported so far.
struct FitJob final : Job {
  std::string target;
  std::string source;  ///< where the data came from, for the emitted functions' comment
  fit::Data data;
  fit::Options options;
  // Guarded by `mutex`:
  fit::Progress progress;
  std::vector<fit::Candidate> front;
  std::optional<std::size_t> chosen;
  std::optional<fit::StopReason> stopped_by;

  std::string run() override;
  void describe(Json& out) const override;
};

[[noreturn]] void fail(std::string_view field, const std::string& message) {
  throw InvalidField(std::string(field), message);
}

/// The rules fit::search applies (an expression's variable: an identifier, not a function name)
/// and those of emitting C++ and GLSL, checked before the job starts so that a bad name is a 400.
void require_identifier(std::string_view field, const std::string& name) {
  try {
    expr::Expression({{expr::Op::variable, 0, 0}}, {name});
  } catch (const InvalidArgument& e) {
    fail(field, fmt::format("{}: use letters, digits and _, not a function name", e.what()));
  }
  for (const char* language : {"cpp", "glsl"}) {
    try {
      fit::check_emittable({name}, language);
    } catch (const InvalidArgument& e) {
      fail(field, e.what());
    }
  }
}

std::vector<double> column(const Fields& columns, const std::string& name, const Limits& limits) {
  return columns.values(name, limits.max_fit_rows);
}

/// {"data": {"columns": {name: [numbers]}, "target": name, "vars": [names]}}
void read_data(const Fields& f, FitJob& job, const Limits& limits) {
  const Fields d = f.object("data", {"columns", "target", "vars"});
  const auto& raw_columns = d.raw("columns");
  if (!raw_columns.is_object() || raw_columns.empty())
    fail("data.columns", "data.columns must be an object of named columns, such as {\"n\": [1, 2], \"coef\": [0.48, 0.66]}");
  std::set<std::string, std::less<>> names;
  for (const auto& [name, values] : raw_columns.items()) names.insert(name);
  const Fields columns = d.object("columns", names);
  job.target = d.text("target");
  if (!names.contains(job.target)) fail("data.target", fmt::format("data.target '{}' is not a column", job.target));
  std::vector<std::string> vars;
  if (d.has("vars")) {
    vars = d.names("vars");
  } else {
    for (const auto& name : names)
      if (name != job.target) vars.push_back(name);
  }
  if (vars.empty()) fail("data.vars", "no variable columns besides the target");
  job.data.target = column(columns, job.target, limits);
  for (const auto& name : vars) {
    if (!names.contains(name)) fail("data.vars", fmt::format("data.vars: '{}' is not a column", name));
    if (name == job.target) fail("data.vars", fmt::format("'{}' is both the target and a variable", name));
    require_identifier("data.vars", name);
    job.data.variables.push_back(name);
    job.data.columns.push_back(column(columns, name, limits));
    if (job.data.columns.back().size() != job.data.target.size())
      fail("data.columns", fmt::format("data.columns: '{}' has {} values, '{}' has {}", name,
                                       job.data.columns.back().size(), job.target, job.data.target.size()));
  }
  job.source = "data";
}

/// {"model": id, "params": {…}, "form": …, "n": range, "round": digits}: the model's exact
/// coefficient k(n) (as `specula normalize` prints it) to fit as a function of n.
void read_model(const Fields& f, FitJob& job, const Limits& limits) {
  const queries::ModelSpec spec = f.model(false);
  const auto ns = f.values_or("n", "paper50", limits.max_n);
  const std::int64_t digits = f.integer_or("round", -1, 0, 17);  // -1: not rounded
  job.target = "coef";
  job.data = queries::normalization_data(spec, ns, digits < 0 ? std::nullopt : std::optional<int>(int(digits)),
                                         queries::Spelling::key);
  job.source = fmt::format("{} normalization", spec.model.name());
}

template <class Parse>
auto parsed(const Fields& f, std::string_view key, std::string_view fallback, Parse parse) {
  const std::string text = f.text_or(key, std::string(fallback));
  try {
    return parse(text);
  } catch (const InvalidArgument& e) {
    fail(key, fmt::format("{}: {}", key, e.what()));
  }
}

void read_options(const Fields& f, fit::Options& o, const Limits& limits) {
  o.operators = parsed(f, "ops", "+,*,/", fit::parse_operators);
  o.constants = parsed(f, "constants", "fitted", fit::parse_constants);
  o.weights = parsed(f, "size_weights", "default", fit::SizeWeights::parse);
  o.metric = parsed(f, "metric", "rms", fit::parse_metric);
  o.choice = parsed(f, "choose", "parsimonious", fit::parse_choice);
  o.max_size = static_cast<int>(f.integer_or("max_size", o.max_size, 1, limits.max_fit_size));
  o.seed = static_cast<std::uint64_t>(f.integer_or("seed", 1, 0, std::int64_t{1} << 53));
  o.max_generations = f.integer_or("generations", 200, 0, limits.max_fit_generations);
  o.time_limit_s = f.number_or("time", limits.max_fit_seconds);
  if (!(o.time_limit_s > 0 && o.time_limit_s <= limits.max_fit_seconds))
    fail("time", fmt::format("time {} is outside (0, {}] seconds", o.time_limit_s, limits.max_fit_seconds));
  o.population = static_cast<int>(f.integer_or("population", o.population, 4, limits.max_fit_population));
  o.islands = static_cast<int>(f.integer_or("islands", o.islands, 1, limits.max_fit_islands));
  o.enumerate_max_size = static_cast<int>(f.integer_or("enumerate_size", o.enumerate_max_size, 0, 15));
  o.snap = f.flag_or("snap", true);
  if (f.has("snap_tolerance")) {
    const double tolerance = f.number_or("snap_tolerance", 0);
    if (!(tolerance > 0 && tolerance <= 1)) fail("snap_tolerance", fmt::format("snap_tolerance {} is outside (0, 1]", tolerance));
    o.snap_tolerance = tolerance;
  }
  o.test_fraction = f.number_or("test_fraction", 0);
  if (!(o.test_fraction >= 0 && o.test_fraction < 1))
    fail("test_fraction", fmt::format("test_fraction {} is outside [0, 1)", o.test_fraction));
  o.threads = 1;  // a job never takes more than one core from the requests
}

Json candidate_json(const fit::Candidate& c, const FitJob& job) {
  const std::string origin = fmt::format("specula fit: {} from {}, size {}, train {} {:.6g}", job.target,
                                         job.source, c.size, fit::metric_name(job.options.metric), c.train_error);
  return Json{{"size", c.size},
              {"train_error", std::isfinite(c.train_error) ? Json(c.train_error) : Json()},
              {"test_error", c.test_error && std::isfinite(*c.test_error) ? Json(*c.test_error) : Json()},
              {"formula", expr::to_infix(c.formula)},
              {"display", expr::to_infix(fit::rounded(c.formula, 6))},
              {"cpp", fit::emit_function(c.formula, "cpp", job.target, origin)},
              {"glsl", fit::emit_function(c.formula, "glsl", job.target, origin)}};
}

void FitJob::describe(Json& out) const {
  out["target"] = target;
  out["variables"] = data.variables;
  out["rows"] = data.target.size();
  out["elapsed_s"] = progress.elapsed_s;
  out["time_left_s"] = progress.time_left_s;
  out["evaluations"] = progress.evaluations;
  out["generations"] = progress.generations;
  out["snap"] = options.snap;
  out["front"] = Json::array();
  for (const auto& c : front) out["front"].push_back(candidate_json(c, *this));
  out["chosen"] = chosen ? Json(*chosen) : Json();
  out["stopped_by"] = stopped_by ? Json(fit::to_string(*stopped_by)) : Json();
}

std::string FitJob::run() {
  try {
    const fit::Result result = fit::search(data, options, [this](const fit::Progress& p) {
      const std::lock_guard lock(mutex);
      progress = p;
      progress.front = nullptr;
      front = *p.front;
    });
    const std::lock_guard lock(mutex);
    front = result.front;
    chosen = result.chosen;
    stopped_by = result.stopped_by;
    progress.elapsed_s = result.seconds;
    progress.evaluations = result.evaluations;
    progress.generations = result.generations;
    return result.stopped_by == fit::StopReason::cancelled ? "cancelled" : "done";
  } catch (const Interrupted& e) {
    if (e.reason() != Interrupted::Reason::deadline) {
      const std::lock_guard lock(mutex);
      stopped_by = fit::StopReason::cancelled;
    }
    throw;
  }
}

}  // namespace

std::shared_ptr<Job> fit_job(std::string_view body, const Limits& limits) {
  const Fields f(body, {"data", "model", "params", "form", "n", "round", "ops", "constants", "size_weights",
                        "metric", "choose", "max_size", "seed", "generations", "time", "population",
                        "islands", "enumerate_size", "test_fraction", "snap", "snap_tolerance"});
  auto job = std::make_shared<FitJob>();
  if (f.has("data") == f.has("model")) fail("data", "give data (columns to fit) or model (to fit its normalization), one of them");
  if (f.has("data")) {
    for (const char* key : {"params", "form", "n", "round"})
      if (f.has(key)) fail(key, fmt::format("{} goes with model, not with data", key));
    read_data(f, *job, limits);
  } else {
    read_model(f, *job, limits);
  }
  read_options(f, job->options, limits);
  job->options.cancel = &job->cancel;
  job->deadline = deadline_in(job->options.time_limit_s + limits.fit_grace_seconds);
  return job;
}

}  // namespace specula::serve
