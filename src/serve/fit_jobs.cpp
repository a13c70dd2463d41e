#include "fit_jobs.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <set>

#include "fields.h"
#include "specula/exceptions.h"
#include "specula/fit/emit.h"
#include "specula/fit/fit.h"
#include "specula/interrupt/interrupt.h"
#include "specula/serve/server.h"

namespace specula::serve {

/// One search: its inputs, fixed at start, and what the search has reported so far.
struct FitJobs::Job {
  std::int64_t id = 0;
  std::string target;
  std::string source;  ///< where the data came from, for the emitted functions' comment
  fit::Data data;
  fit::Options options;
  std::atomic<bool> cancel{false};
  std::atomic<bool> finished{false};
  std::chrono::steady_clock::time_point deadline;  ///< of its work limit: time budget + grace

  mutable std::mutex mutex;  // guards what follows and signals `ended`
  std::condition_variable ended;  ///< notified once `finished` is set
  std::string state = "running";  ///< running | done | cancelled | failed
  std::string error;
  fit::Progress progress;
  std::vector<fit::Candidate> front;
  std::optional<std::size_t> chosen;
  std::optional<fit::StopReason> stopped_by;
};

namespace {

using Json = nlohmann::ordered_json;
using Job = FitJobs::Job;

std::atomic<std::size_t> abandoned{0};

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
void read_data(const Fields& f, Job& job, const Limits& limits) {
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
void read_model(const Fields& f, Job& job, const Limits& limits) {
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
  o.snap_tolerance = f.number_or("snap_tolerance", o.snap_tolerance);
  if (!(o.snap_tolerance > 0 && o.snap_tolerance <= 1))
    fail("snap_tolerance", fmt::format("snap_tolerance {} is outside (0, 1]", o.snap_tolerance));
  o.test_fraction = f.number_or("test_fraction", 0);
  if (!(o.test_fraction >= 0 && o.test_fraction < 1))
    fail("test_fraction", fmt::format("test_fraction {} is outside [0, 1)", o.test_fraction));
  o.threads = 1;  // a job never takes more than one core from the requests
}

Json candidate_json(const fit::Candidate& c, const Job& job) {
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

std::string status_json(const Job& job) {
  const std::lock_guard lock(job.mutex);
  Json out{{"job", job.id}, {"state", job.state}, {"target", job.target},
           {"variables", job.data.variables}, {"rows", job.data.target.size()},
           {"elapsed_s", job.progress.elapsed_s}, {"time_left_s", job.progress.time_left_s},
           {"evaluations", job.progress.evaluations}, {"generations", job.progress.generations},
           {"snap", job.options.snap}, {"front", Json::array()}};
  for (const auto& c : job.front) out["front"].push_back(candidate_json(c, job));
  out["chosen"] = job.chosen ? Json(*job.chosen) : Json();
  out["stopped_by"] = job.stopped_by ? Json(fit::to_string(*job.stopped_by)) : Json();
  if (!job.error.empty()) out["error"] = job.error;
  return out.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";  // an error may echo anything
}

void run_job(Job& job) {
  try {
    const fit::Result result = fit::search(job.data, job.options, [&job](const fit::Progress& p) {
      const std::lock_guard lock(job.mutex);
      job.progress = p;
      job.progress.front = nullptr;
      job.front = *p.front;
    });
    const std::lock_guard lock(job.mutex);
    job.front = result.front;
    job.chosen = result.chosen;
    job.stopped_by = result.stopped_by;
    job.progress.elapsed_s = result.seconds;
    job.progress.evaluations = result.evaluations;
    job.progress.generations = result.generations;
    job.state = result.stopped_by == fit::StopReason::cancelled ? "cancelled" : "done";
  } catch (const Interrupted& e) {  // a library check of the job's work limit (or a signal)
    const std::lock_guard lock(job.mutex);
    if (e.reason() == Interrupted::Reason::deadline) {
      job.state = "failed";
      job.error = fmt::format("the search ran past its time budget and was stopped");
    } else {
      job.state = "cancelled";
      job.stopped_by = fit::StopReason::cancelled;
    }
  } catch (const std::exception& e) {
    const std::lock_guard lock(job.mutex);
    job.state = "failed";
    job.error = e.what();
  }
  const std::lock_guard lock(job.mutex);
  job.finished = true;
  job.ended.notify_all();
}

}  // namespace

std::size_t abandoned_fit_threads() noexcept { return abandoned.load(); }

FitJobs::~FitJobs() {
  cancel_all();
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(limits_.stop_seconds));
  const std::lock_guard lock(mutex_);
  for (auto& w : workers_) {
    bool ended = false;
    {
      std::unique_lock job_lock(w.job->mutex);
      ended = w.job->ended.wait_until(job_lock, until, [&] { return w.job->finished.load(); });
    }
    if (ended) {
      w.thread.join();
    } else {  // the thread holds its own Job (shared): it may run on, touching nothing of ours
      w.thread.detach();
      ++abandoned;
    }
  }
}

std::int64_t FitJobs::start(std::string_view body) {
  const Fields f(body, {"data", "model", "params", "form", "n", "round", "ops", "constants", "size_weights",
                        "metric", "choose", "max_size", "seed", "generations", "time", "population",
                        "islands", "enumerate_size", "test_fraction", "snap", "snap_tolerance"});
  auto job = std::make_shared<Job>();
  if (f.has("data") == f.has("model")) fail("data", "give data (columns to fit) or model (to fit its normalization), one of them");
  if (f.has("data")) {
    for (const char* key : {"params", "form", "n", "round"})
      if (f.has(key)) fail(key, fmt::format("{} goes with model, not with data", key));
    read_data(f, *job, limits_);
  } else {
    read_model(f, *job, limits_);
  }
  read_options(f, job->options, limits_);
  job->options.cancel = &job->cancel;
  job->deadline = std::chrono::steady_clock::now() +
                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>(job->options.time_limit_s + limits_.fit_grace_seconds));

  const std::lock_guard lock(mutex_);
  reap_finished();
  if (running() >= limits_.max_running_fits) throw TooManyFits{running()};
  // Cancelled jobs free their place at once, but their threads are not waited for: bound them
  // too, so that start-and-cancel cannot pile up threads.
  if (workers_.size() >= 2 * limits_.max_running_fits) throw TooManyFits{running(), workers_.size() - running()};
  job->id = next_id_++;
  jobs_[job->id] = job;
  workers_.push_back({job, std::thread([job] {
                        const ScopedLimit limit(WorkLimit{job->deadline, &job->cancel});
                        run_job(*job);
                      })});
  forget_oldest_done();
  return job->id;
}

std::optional<std::string> FitJobs::status(std::int64_t id) const {
  std::shared_ptr<Job> job;
  {
    const std::lock_guard lock(mutex_);
    const auto it = jobs_.find(id);
    if (it == jobs_.end()) return std::nullopt;
    job = it->second;
  }
  return status_json(*job);
}

std::optional<std::string> FitJobs::cancel(std::int64_t id) {
  std::shared_ptr<Job> job;
  {
    const std::lock_guard lock(mutex_);
    const auto it = jobs_.find(id);
    if (it == jobs_.end()) return std::nullopt;
    job = it->second;
    jobs_.erase(it);
  }
  job->cancel = true;
  {
    const std::lock_guard lock(job->mutex);
    if (job->state == "running") job->state = "cancelled";
  }
  return status_json(*job);
}

void FitJobs::cancel_all() {
  const std::lock_guard lock(mutex_);
  for (auto& w : workers_) w.job->cancel = true;
}

void FitJobs::reap_finished() {
  std::erase_if(workers_, [](Worker& w) {
    if (!w.job->finished) return false;
    w.thread.join();
    return true;
  });
}

std::size_t FitJobs::running() const {
  // A cancelled job frees its place at once, also while its thread is still winding down.
  return static_cast<std::size_t>(std::count_if(workers_.begin(), workers_.end(),
                                                [](const Worker& w) { return !w.job->finished && !w.job->cancel; }));
}

std::size_t FitJobs::running_count() const {
  const std::lock_guard lock(mutex_);
  return running();
}

void FitJobs::forget_oldest_done() {
  std::size_t done = 0;
  for (const auto& [id, job] : jobs_) done += job->finished ? 1 : 0;
  for (auto it = jobs_.begin(); it != jobs_.end() && done > limits_.max_kept_fits;) {
    if (it->second->finished) {
      it = jobs_.erase(it);
      --done;
    } else {
      ++it;
    }
  }
}

}  // namespace specula::serve
