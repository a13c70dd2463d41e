// A main() for a harness without libFuzzer: runs LLVMFuzzerTestOneInput once on every file
// given, or on every file under each directory given (in sorted order), then prints how many
// it ran. This is how the GCC debug build (ctest, make test) replays the checked-in corpora:
//   replay_<name> fuzz/corpus/<name> [more files or directories]
// A harness that aborts, or a sanitizer report, ends the process non-zero; the input being run
// is named on stderr first. Exit codes: 0 all ran, 1 a harness returned non-zero, 2 bad usage.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

namespace {

// The input being run, for the report of a crash (a fixed buffer: a signal handler reads it).
char current[4096] = "";

void say(const char* text) {
  if (::write(STDERR_FILENO, text, std::strlen(text)) < 0) return;
}

void name_current() {
  say("replay: the crash above was on input ");
  say(current);
  say("\n");
}

extern "C" void on_fatal_signal(int signal) {
  name_current();
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

std::vector<std::filesystem::path> inputs(const std::vector<std::string>& arguments) {
  std::vector<std::filesystem::path> files;
  for (const auto& argument : arguments) {
    const std::filesystem::path path(argument);
    if (std::filesystem::is_directory(path)) {
      std::vector<std::filesystem::path> found;
      for (const auto& entry : std::filesystem::recursive_directory_iterator(path))
        if (entry.is_regular_file()) found.push_back(entry.path());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (std::filesystem::is_regular_file(path)) {
      files.push_back(path);
    } else {
      std::fprintf(stderr, "replay: no such file or directory: %s\n", argument.c_str());
      std::exit(2);
    }
  }
  return files;
}

std::vector<std::uint8_t> bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main(int argc, char** argv) {
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE_OR_DIRECTORY...\n", argv[0]);
    return 2;
  }
  const auto files = inputs(std::vector<std::string>(argv + 1, argv + argc));
  if (files.empty()) {
    std::fprintf(stderr, "replay: no inputs under the paths given\n");
    return 2;
  }
  for (const int s : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(s, on_fatal_signal);
#if defined(__SANITIZE_ADDRESS__)
  __sanitizer_set_death_callback(name_current);  // a sanitizer report ends the process without a signal
#endif
  const auto start = std::chrono::steady_clock::now();
  for (const auto& file : files) {
    std::snprintf(current, sizeof current, "%s", file.c_str());
    const auto data = bytes_of(file);
    // A heap block of exactly the input's size, so that AddressSanitizer catches a read past its end.
    const std::unique_ptr<std::uint8_t[]> exact(new std::uint8_t[data.size() + (data.empty() ? 1 : 0)]);
    std::copy(data.begin(), data.end(), exact.get());
    if (LLVMFuzzerTestOneInput(exact.get(), data.size()) != 0) {
      std::fprintf(stderr, "replay: the harness returned non-zero on %s\n", file.c_str());
      return 1;
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("replay: %zu inputs in %.2f s\n", files.size(), seconds);
  return 0;
}
