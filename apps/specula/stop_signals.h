#pragma once
// Ctrl-C (SIGINT) and SIGTERM for every command: the first asks the work to stop (request_stop:
// loops throw specula::Interrupted at their next check, main exits 130 or 143 and no output is
// written); if the program has not ended `grace` later, or a second signal comes, it exits at
// once with the same code. Outputs are never left half-written either way: files are written
// under no name until complete (io::write_file_atomically).
#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>

namespace specula::cli {

class StopSignals {
 public:
  /// Blocks SIGINT and SIGTERM in this thread and every thread started after it (call it first in
  /// main), and starts the thread that receives them.
  explicit StopSignals(std::chrono::milliseconds grace = std::chrono::milliseconds(2000));
  ~StopSignals();  ///< ends the receiving thread
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  void watch();

  sigset_t signals_;
  std::chrono::milliseconds grace_;
  std::atomic<bool> done_ = false;
  std::thread watcher_;
};

/// 128 + the signal's number: the shell's convention for a run ended by that signal.
constexpr int exit_code_for_signal(int signal) { return 128 + signal; }

}  // namespace specula::cli
