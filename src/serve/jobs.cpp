#include "jobs.h"

#include <algorithm>
#include <fmt/format.h>

#include "specula/interrupt/interrupt.h"
#include "specula/serve/server.h"

namespace specula::serve {

namespace {

using Json = nlohmann::ordered_json;

std::atomic<std::size_t> abandoned{0};

void run_job(Job& job) {
  std::string state, error;
  try {
    state = job.run();
  } catch (const Interrupted& e) {  // a library check of the job's work limit (or a signal)
    if (e.reason() == Interrupted::Reason::deadline) {
      state = "failed";
      error = "the job ran past its time budget and was stopped";
    } else {
      state = "cancelled";
    }
  } catch (const std::exception& e) {
    state = "failed";
    error = e.what();
  }
  const std::lock_guard lock(job.mutex);
  job.state = state;
  job.error = error;
  job.finished = true;
  job.ended.notify_all();
}

}  // namespace

std::size_t abandoned_job_threads() noexcept { return abandoned.load(); }

std::chrono::steady_clock::time_point deadline_in(double seconds) {
  return std::chrono::steady_clock::now() +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

std::string Job::status_json() const {
  const std::lock_guard lock(mutex);
  Json out{{"job", id}, {"state", state}};
  describe(out);
  if (!error.empty()) out["error"] = error;
  return out.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";  // an error may echo anything
}

Jobs::~Jobs() {
  cancel_all();
  const auto until = deadline_in(stop_seconds_);
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

std::int64_t Jobs::start(std::shared_ptr<Job> job) {
  const std::lock_guard lock(mutex_);
  reap_finished();
  if (running() >= max_running_) throw TooManyJobs{kind_, running(), max_running_};
  // Cancelled jobs free their place at once, but their threads are not waited for: bound them
  // too, so that start-and-cancel cannot pile up threads.
  if (workers_.size() >= 2 * max_running_) throw TooManyJobs{kind_, running(), max_running_, workers_.size() - running()};
  job->id = next_id_++;
  jobs_[job->id] = job;
  workers_.push_back({job, std::thread([job] {
                        const ScopedLimit limit(WorkLimit{job->deadline, &job->cancel});
                        run_job(*job);
                      })});
  forget_oldest_done();
  return job->id;
}

std::optional<std::string> Jobs::status(std::int64_t id) const {
  std::shared_ptr<Job> job;
  {
    const std::lock_guard lock(mutex_);
    const auto it = jobs_.find(id);
    if (it == jobs_.end()) return std::nullopt;
    job = it->second;
  }
  return job->status_json();
}

std::optional<std::string> Jobs::cancel(std::int64_t id) {
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
  return job->status_json();
}

void Jobs::cancel_all() {
  const std::lock_guard lock(mutex_);
  for (auto& w : workers_) w.job->cancel = true;
}

void Jobs::reap_finished() {
  std::erase_if(workers_, [](Worker& w) {
    if (!w.job->finished) return false;
    w.thread.join();
    return true;
  });
}

std::size_t Jobs::running() const {
  // A cancelled job frees its place at once, also while its thread is still winding down.
  return static_cast<std::size_t>(std::count_if(workers_.begin(), workers_.end(),
                                                [](const Worker& w) { return !w.job->finished && !w.job->cancel; }));
}

std::size_t Jobs::running_count() const {
  const std::lock_guard lock(mutex_);
  return running();
}

void Jobs::forget_oldest_done() {
  std::size_t done = 0;
  for (const auto& [id, job] : jobs_) done += job->finished ? 1 : 0;
  for (auto it = jobs_.begin(); it != jobs_.end() && done > max_kept_;) {
    if (it->second->finished) {
      it = jobs_.erase(it);
      --done;
    } else {
      ++it;
    }
  }
}

}  // namespace specula::serve
