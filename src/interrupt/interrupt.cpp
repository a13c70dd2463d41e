#include "specula/interrupt/interrupt.h"

#include <fmt/format.h>

namespace specula {
namespace {

std::atomic<int> stop_signal{0};
thread_local WorkLimit thread_limit;

std::string message(Interrupted::Reason reason, int signal) {
  switch (reason) {
    case Interrupted::Reason::signal: return fmt::format("interrupted by signal {}", signal);
    case Interrupted::Reason::deadline: return "the time limit was reached";
    case Interrupted::Reason::cancelled: return "cancelled";
  }
  return "interrupted";
}

}  // namespace

Interrupted::Interrupted(Reason reason, int signal)
    : std::runtime_error(message(reason, signal)), reason_(reason), signal_(signal) {}

static_assert(std::atomic<int>::is_always_lock_free, "request_stop must be async-signal-safe");

void request_stop(int signal) noexcept { stop_signal.store(signal, std::memory_order_relaxed); }

int stop_requested() noexcept { return stop_signal.load(std::memory_order_relaxed); }

void clear_stop_request() noexcept { stop_signal.store(0, std::memory_order_relaxed); }

const WorkLimit& current_limit() noexcept { return thread_limit; }

ScopedLimit::ScopedLimit(const WorkLimit& limit) noexcept : previous_(thread_limit) { thread_limit = limit; }

ScopedLimit::~ScopedLimit() { thread_limit = previous_; }

void check_interrupt() {
  if (const int signal = stop_requested()) throw Interrupted(Interrupted::Reason::signal, signal);
  if (thread_limit.cancel && thread_limit.cancel->load(std::memory_order_relaxed))
    throw Interrupted(Interrupted::Reason::cancelled, 0);
  if (thread_limit.deadline != std::chrono::steady_clock::time_point::max() &&
      std::chrono::steady_clock::now() >= thread_limit.deadline)
    throw Interrupted(Interrupted::Reason::deadline, 0);
}

}  // namespace specula
