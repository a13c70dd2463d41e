#pragma once
// What `specula --version` prints, for bug reports: the version (CMake's project(VERSION)), the
// git commit it was built from and the SIMD target Highway dispatches to on this machine.
#include <string>
#include <string_view>

namespace specula::cli {

/// "0.1.0": project(VERSION) of CMakeLists.txt.
std::string_view build_version() noexcept;
/// `git rev-parse --short HEAD` at build time, or "unknown" (no git, not a git checkout).
std::string_view build_commit() noexcept;

/// "specula 0.1.0 (commit abc1234), SIMD: AVX2".
std::string version_line();

}  // namespace specula::cli
