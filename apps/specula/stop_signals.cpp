#include "stop_signals.h"

#include <pthread.h>
#include <unistd.h>

#include "specula/interrupt/interrupt.h"

namespace specula::cli {
namespace {

constexpr timespec kPoll{0, 50'000'000};

}  // namespace

StopSignals::StopSignals(std::chrono::milliseconds grace) : grace_(grace) {
  sigemptyset(&signals_);
  sigaddset(&signals_, SIGINT);
  sigaddset(&signals_, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals_, nullptr);
  watcher_ = std::thread([this] { watch(); });
}

StopSignals::~StopSignals() {
  done_ = true;
  // Wakes the watcher now rather than at its next poll (which made every command last at least
  // 50 ms): a signal sent to that thread alone, which it takes in sigtimedwait and ignores once
  // done_ is set.
  pthread_kill(watcher_.native_handle(), SIGTERM);
  watcher_.join();
}

void StopSignals::watch() {
  int signal = 0;
  while (!done_ && signal <= 0) signal = sigtimedwait(&signals_, nullptr, &kPoll);
  if (done_) return;
  request_stop(signal);
  const auto give_up = std::chrono::steady_clock::now() + grace_;
  while (!done_ && std::chrono::steady_clock::now() < give_up)
    if (sigtimedwait(&signals_, nullptr, &kPoll) > 0) break;
  if (!done_) {
    static constexpr char kMessage[] = "specula: stopped\n";
    [[maybe_unused]] const auto written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    ::_exit(exit_code_for_signal(signal));
  }
}

}  // namespace specula::cli
