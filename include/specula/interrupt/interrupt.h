#pragma once
// Stopping long work early, for three reasons that share one mechanism: a signal (Ctrl-C,
// SIGTERM: process-wide), a deadline (a server request's time cap: per thread) and a cancel
// flag (a fit job: per thread). Loops that can run long call check_interrupt() once per
// iteration of their outer loop; it throws Interrupted, which unwinds the work without a result,
// so a stopped computation never produces a partial one. Work handed to other threads
// (parallel_map, the renderers' rows) carries the limit of the thread that started it
// (`carry_limit`). The cost of one check is an atomic load, plus one clock read when a deadline
// is set: call it per row, angle or batch, not per sample.
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>

namespace specula {

/// Thrown by check_interrupt(). `signal` is the signal's number for a signal, else 0.
class Interrupted : public std::runtime_error {
 public:
  enum class Reason { signal, deadline, cancelled };
  Interrupted(Reason reason, int signal);
  Reason reason() const noexcept { return reason_; }
  int signal() const noexcept { return signal_; }

 private:
  Reason reason_;
  int signal_;
};

/// Asks all work in the process to stop (async-signal-safe: call it from a signal handler).
void request_stop(int signal) noexcept;
/// The signal passed to request_stop, or 0.
int stop_requested() noexcept;
/// Clears a stop request (tests).
void clear_stop_request() noexcept;

/// A deadline and/or a cancel flag that bounds the work of the threads that carry it.
struct WorkLimit {
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  const std::atomic<bool>* cancel = nullptr;

  static WorkLimit after(std::chrono::steady_clock::duration d) {
    return {std::chrono::steady_clock::now() + d, nullptr};
  }
};

/// The limit of the current thread (no deadline, no cancel flag when none is installed).
const WorkLimit& current_limit() noexcept;

/// Installs `limit` on the current thread for the scope's lifetime (the previous one returns).
class ScopedLimit {
 public:
  explicit ScopedLimit(const WorkLimit& limit) noexcept;
  ~ScopedLimit();
  ScopedLimit(const ScopedLimit&) = delete;
  ScopedLimit& operator=(const ScopedLimit&) = delete;

 private:
  WorkLimit previous_;
};

/// Wraps `f` so that it runs under the calling thread's current limit on whichever thread calls
/// it: what parallel loops hand to their workers.
template <class F>
auto carry_limit(const F& f) {
  return [limit = current_limit(), &f](auto&&... args) {
    ScopedLimit scope(limit);
    return f(std::forward<decltype(args)>(args)...);
  };
}

/// Throws Interrupted when a stop was requested, the thread's cancel flag is set or its deadline
/// has passed (in that order).
void check_interrupt();

}  // namespace specula
