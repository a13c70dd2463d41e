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
  std::size_t winding_down = 0;  ///< cancelled jobs whose threads have not ended yet
};

/// Each job runs on a thread of its own under a WorkLimit (specula/interrupt) with its cancel
/// flag and a deadline of its time budget + Limits::fit_grace_seconds, so that the library's
/// interrupt checks end it as well as the search's own budget checks.
class FitJobs {
 public:
  explicit FitJobs(const Limits& limits) : limits_(limits) {}
  /// Cancels every job and joins its thread, waiting Limits::stop_seconds at most: a thread that
  /// has not ended by then is left running, detached (abandoned_fit_threads(), server.h).
  ~FitJobs();
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
  /// Jobs running and not cancelled: those that count against Limits::max_running_fits.
  std::size_t running_count() const;

  struct Job;

 private:
  struct Worker {
    std::shared_ptr<Job> job;
    std::thread thread;
  };
  void reap_finished();      // joins finished workers; caller holds mutex_
  void forget_oldest_done();  // keeps at most max_kept_fits finished jobs; caller holds mutex_
  std::size_t running() const;  // running and not cancelled; caller holds mutex_

  const Limits& limits_;
  mutable std::mutex mutex_;
  std::int64_t next_id_ = 1;
  std::map<std::int64_t, std::shared_ptr<Job>> jobs_;
  std::vector<Worker> workers_;
};

}  // namespace specula::serve
