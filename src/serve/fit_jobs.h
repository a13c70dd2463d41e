#pragma once
// Symbolic-regression jobs: `specula fit` run in the background with capped budgets, polled for
// progress and the Pareto front so far, cancelled on request or when the server stops.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "specula/serve/api.h"

namespace specula::serve {

/// Thrown by FitJobs::start when Limits::max_running_fits jobs are running (HTTP 429).
struct TooManyFits {
  std::size_t running;
};

class FitJobs {
 public:
  explicit FitJobs(const Limits& limits) : limits_(limits) {}
  ~FitJobs();  ///< cancels every job and waits for its thread
  FitJobs(const FitJobs&) = delete;
  FitJobs& operator=(const FitJobs&) = delete;

  /// Validates the request (InvalidField naming a bad field), starts the job, returns its id.
  std::int64_t start(std::string_view body);
  /// The job's progress and front as JSON; nullopt for an unknown id.
  std::optional<std::string> status(std::int64_t id) const;
  /// Cancels the job and forgets it (later lookups are unknown); its final state as JSON, or
  /// nullopt for an unknown id.
  std::optional<std::string> cancel(std::int64_t id);
  void cancel_all();

  struct Job;

 private:
  struct Worker {
    std::shared_ptr<Job> job;
    std::thread thread;
  };
  void reap_finished();      // joins finished workers; caller holds mutex_
  void forget_oldest_done();  // keeps at most max_kept_fits finished jobs; caller holds mutex_
  std::size_t running() const;  // caller holds mutex_

  const Limits& limits_;
  mutable std::mutex mutex_;
  std::int64_t next_id_ = 1;
  std::map<std::int64_t, std::shared_ptr<Job>> jobs_;
  std::vector<Worker> workers_;
};

}  // namespace specula::serve
