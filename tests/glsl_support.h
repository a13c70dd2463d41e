#pragma once
// glslangValidator (Debian's glslang-tools) as the tests' GLSL front end: a shader is valid when
// the reference compiler accepts it for its stage (.vert or .frag).
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

/// Runs glslangValidator on `source` written to a temporary file named for `stage` ("vert"/"frag").
inline GlslCheck validate_glsl(const std::string& source, const std::string& stage) {
  static int counter = 0;
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     fmt::format("specula-glsl-{}-{}.{}", ::getpid(), counter++, stage);
  std::ofstream(file) << source;
  const std::string command = fmt::format("'{}' '{}' 2>&1", SPECULA_GLSLANG, file.string());
  std::string log;
  FILE* pipe = ::popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  while (pipe && std::fgets(buffer.data(), buffer.size(), pipe)) log += buffer.data();
  const int status = pipe ? ::pclose(pipe) : -1;
  std::filesystem::remove(file);
  return {status == 0, log};
}

}  // namespace specula::testing
