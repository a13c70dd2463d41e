#pragma once
// glslangValidator (Debian's glslang-tools) as the tests' GLSL (and HLSL) front end: a shader is
// valid when the reference compiler accepts it for its stage (.vert or .frag).
#include <array>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <unistd.h>

namespace specula::testing {

struct GlslCheck {
  bool ok;
  std::string log;
};

/// Runs a shell command; ok when it exits 0, log its stdout and stderr.
inline GlslCheck run_command(const std::string& command) {
  std::string log;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  std::array<char, 4096> buffer{};
  while (pipe && std::fgets(buffer.data(), buffer.size(), pipe)) log += buffer.data();
  const int status = pipe ? ::pclose(pipe) : -1;
  return {status == 0, log};
}

/// Runs glslangValidator on `source` written to a temporary file named for `stage` ("vert"/"frag"),
/// with `options` before the file (e.g. "-D -V -S frag -e main -o /dev/null" for HLSL).
inline GlslCheck validate_glsl(const std::string& source, const std::string& stage, const std::string& options = "") {
  static int counter = 0;
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     fmt::format("specula-glsl-{}-{}.{}", ::getpid(), counter++, stage);
  std::ofstream(file) << source;
  const GlslCheck check = run_command(fmt::format("'{}' {} '{}'", SPECULA_GLSLANG, options, file.string()));
  std::filesystem::remove(file);
  return check;
}

}  // namespace specula::testing
