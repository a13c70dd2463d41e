#pragma once
// What the harnesses in fuzz/ share: the rule for what counts as a finding and how one is told.
// Bad input must end in specula::InvalidArgument (the library's one exception for bad input);
// any other exception, a broken property or a sanitizer report is a finding: the harness prints
// one line "specula fuzz finding: …" and aborts, which libFuzzer (and fuzz/replay_main.cpp)
// turns into a crash with the input saved.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cxxabi.h>
#include <exception>
#include <memory>
#include <string>
#include <string_view>
#include <typeinfo>

#include "specula/exceptions.h"

namespace specula::fuzz {

/// Prints "specula fuzz finding: <what>" (the first 1000 characters) and aborts.
[[noreturn]] inline void finding(std::string_view what) {
  constexpr std::size_t kShown = 1000;
  std::fprintf(stderr, "\nspecula fuzz finding: %.*s%s\n", static_cast<int>(std::min(what.size(), kShown)), what.data(),
               what.size() > kShown ? "… (cut)" : "");
  std::fflush(stderr);
  std::abort();
}

inline void require(bool ok, std::string_view what) {
  if (!ok) finding(what);
}

inline std::string type_name(const std::type_info& type) {
  int status = 0;
  const std::unique_ptr<char, decltype(&std::free)> name(
      abi::__cxa_demangle(type.name(), nullptr, nullptr, &status), &std::free);
  return status == 0 && name ? name.get() : type.name();
}

/// Runs f(): true when it returns, false when it throws InvalidArgument (bad input, rejected as
/// documented); any other exception is a finding named by `stage`.
template <class F>
bool accepted(std::string_view stage, F&& f) {
  try {
    f();
    return true;
  } catch (const InvalidArgument&) {
    return false;
  } catch (const std::exception& e) {
    finding(std::string(stage) + ": unexpected exception " + type_name(typeid(e)) + ": " + e.what());
  } catch (...) {
    finding(std::string(stage) + ": an exception that is not a std::exception");
  }
}

inline std::string_view text_of(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace specula::fuzz
