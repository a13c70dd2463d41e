#pragma once
// Background jobs of `specula serve` (a fit, a design): each runs on a thread of its own with
// capped budgets, is polled for its progress and its result so far, and is cancelled on request
// or when the server stops. A Jobs table holds the jobs of one kind and its limits.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace specula::serve {

/// One job: what a kind implements (run, describe) and the state every job has.
class Job {
 public:
  virtual ~Job() = default;

  /// Runs the job to its end under the job's work limit; returns the final state ("done" or
  /// "cancelled"). Throws on failure (the message is the job's error).
  virtual std::string run() = 0;
  /// Adds the kind's fields (settings, progress, result so far) to the status; called under `mutex`.
  virtual void describe(nlohmann::ordered_json& status) const = 0;

  /// The status as JSON: job, state, error, and describe's fields.
  std::string status_json() const;

  std::int64_t id = 0;
  std::atomic<bool> cancel{false};
  std::atomic<bool> finished{false};
  std::chrono::steady_clock::time_point deadline;  ///< of its work limit: time budget + grace

  mutable std::mutex mutex;  // guards what follows, the kind's progress, and signals `ended`
  std::condition_variable ended;  ///< notified once `finished` is set
  std::string state = "running";  ///< running | done | cancelled | failed, or a kind's own (stopped)
  std::string error;
};

/// Thrown by Jobs::start when the table's running limit is reached (HTTP 429).
struct TooManyJobs {
  std::string kind;  ///< "fit", "design"
  std::size_t running;
  std::size_t most;
  std::size_t winding_down = 0;  ///< cancelled jobs whose threads have not ended yet
};

/// The jobs of one kind. Each runs under a WorkLimit (specula/interrupt) with its cancel flag
/// and its deadline, so that the library's interrupt checks end it as well as its own budget.
class Jobs {
 public:
  Jobs(std::string kind, std::size_t max_running, std::size_t max_kept, double stop_seconds)
      : kind_(std::move(kind)), max_running_(max_running), max_kept_(max_kept), stop_seconds_(stop_seconds) {}
  /// Cancels every job and joins its thread, waiting stop_seconds at most: a thread that has
  /// not ended by then is left running, detached (abandoned_job_threads(), server.h).
  ~Jobs();
  Jobs(const Jobs&) = delete;
  Jobs& operator=(const Jobs&) = delete;

  /// Starts `job` (validated, its deadline set); returns its id. Throws TooManyJobs.
  std::int64_t start(std::shared_ptr<Job> job);
  /// The job's status as JSON; nullopt for an unknown id.
  std::optional<std::string> status(std::int64_t id) const;
  /// Cancels the job and forgets it (later lookups are unknown); its final state as JSON, or
  /// nullopt for an unknown id.
  std::optional<std::string> cancel(std::int64_t id);
  void cancel_all();
  /// Jobs running and not cancelled: those that count against the running limit.
  std::size_t running_count() const;
  const std::string& kind() const { return kind_; }

 private:
  struct Worker {
    std::shared_ptr<Job> job;
    std::thread thread;
  };
  void reap_finished();         // joins finished workers; caller holds mutex_
  void forget_oldest_done();    // keeps at most max_kept_ finished jobs; caller holds mutex_
  std::size_t running() const;  // running and not cancelled; caller holds mutex_

  const std::string kind_;
  const std::size_t max_running_, max_kept_;
  const double stop_seconds_;
  mutable std::mutex mutex_;
  std::int64_t next_id_ = 1;
  std::map<std::int64_t, std::shared_ptr<Job>> jobs_;
  std::vector<Worker> workers_;
};

/// The deadline `seconds` from now.
std::chrono::steady_clock::time_point deadline_in(double seconds);

}  // namespace specula::serve
