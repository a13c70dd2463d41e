// The designer's native kernels: the generated Highway code computes the formula it was written
// from (to float accuracy), counts its operations, and fails loudly where it cannot compile.
#include <atomic>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "design/native.h"
#include "design/process.h"
#include "design/spirv.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

#include <cstring>

namespace specula::design {
namespace {

class NativeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // The build's compiler is always there for the tests: none found is a fault, not a skip.
    ASSERT_FALSE(native_compiler().empty()) << "no C++ compiler to build kernels with";
    dir_ = std::filesystem::temp_directory_path() / ("specula-native-test-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

NativeLobe lobe(const char* text, double n = 20) { return {expr::parse(text, {"c", "n"}), n}; }

TEST_F(NativeTest, KernelsComputeTheirFormulas) {
  const std::vector<NativeLobe> lobes = {
      lobe("max(c * (0.3235 * n + 0.27) + (0.697 - 0.3235 * n), 0) ^ 2"),
      lobe("c * max(c * (0.3235 * (n - 14 / 9 / n / (n + 0.2485)) + 0.2215) + (0.2435 / (n - 5 / 11) - 0.3235 * (n - 2.749)), 0) ^ 2"),
      lobe("exp(n * c - n)"),
      lobe("max(0, 1 - 0.5 * log2(1 - n * log2(c)))"),
      lobe("c / (n - n * c + c)"),
      lobe("sqrt(c) * c ^ 5 / (1 + c)"),
      lobe("c ^ n", 7),
  };
  const NativeKernels kernels(lobes, dir_, [] { return false; });
  ASSERT_EQ(kernels.kernels().size(), lobes.size());
  for (std::size_t i = 0; i < lobes.size(); ++i)
    EXPECT_LT(kernel_deviation(kernels.kernels()[i], lobes[i]), 2e-6) << expr::to_infix(lobes[i].formula);
  // a·x + b is one FMA; x² one product; the parameter's subexpressions are free.
  EXPECT_EQ(kernels.operations()[0], 3);  // FMA, max, square
  EXPECT_EQ(kernels.operations()[2], 2);  // FMA (n·c − n), exp
}

// The parameter's subexpressions are a material's uniforms: written into specula_uniforms_<i>, run
// once per material, never into the timed kernel; each distinct one once, and plain numbers stay
// numbers the compiler folds and shares (the exact Fresnel repeats its square roots: loaded as
// uniforms, they cost 2.5 times as much).
TEST_F(NativeTest, TheParametersSubexpressionsAreComputedOnceOutsideTheKernel) {
  const NativeSource source = native_source({lobe("c * log(log(n) + 2) + log(log(n) + 2) * c ^ 2 + 0.5 * c")});
  const auto kernel = source.text.find("specula_lobe_0");
  ASSERT_NE(kernel, std::string::npos);
  EXPECT_NE(source.text.find("std::log"), std::string::npos);
  EXPECT_LT(source.text.find("std::log"), kernel);  // in the uniforms' function, before the kernel
  EXPECT_EQ(source.text.find("std::log", kernel), std::string::npos);
  EXPECT_EQ(source.uniforms.at(0), 1u);  // log(log(n) + 2) once; 0.5 a number
  EXPECT_EQ(native_source({lobe("c * 0.5 + 0.25")}).uniforms.at(0), 0u);  // the control: no parameter, no uniform
  const NativeKernels kernels({lobe("c * log(log(n) + 2) + log(log(n) + 2) * c ^ 2 + 0.5 * c", 3)}, dir_, [] { return false; });
  EXPECT_LT(kernel_deviation(kernels.kernels()[0], lobe("c * log(log(n) + 2) + log(log(n) + 2) * c ^ 2 + 0.5 * c", 3)), 2e-6);
}

// Several per-pixel variables (issue 41): one input array each, the parameter a uniform; checked at
// each variable's values as variable_value gives them (the cosines in other orders). The control:
// the formula with NoV and NoL swapped in one place deviates.
TEST_F(NativeTest, KernelsOfSeveralVariablesComputeTheirFormulas) {
  const auto smith = [](const char* text) {
    return NativeLobe{expr::parse(text, {"NoV", "NoL", "alpha"}), 0.4, 2};
  };
  const std::vector<NativeLobe> lobes = {
      smith("2*NoV*NoL/(NoV*(NoL*(1 - alpha) + alpha) + NoL*(NoV*(1 - alpha) + alpha))"),
      smith("2*NoV*NoL/(NoL*sqrt(NoV^2*(1 - alpha^2) + alpha^2) + NoV*sqrt(NoL^2*(1 - alpha^2) + alpha^2))"),
      NativeLobe{expr::parse("x * y + z", {"x", "y", "z"}), 0, 3},
  };
  const NativeKernels kernels(lobes, dir_, [] { return false; });
  for (std::size_t i = 0; i < lobes.size(); ++i)
    EXPECT_LT(kernel_deviation(kernels.kernels()[i], lobes[i]), 2e-6) << expr::to_infix(lobes[i].formula);
  const NativeLobe swapped = smith("2*NoV*NoL/(NoV*(NoV*(1 - alpha) + alpha) + NoL*(NoV*(1 - alpha) + alpha))");
  EXPECT_GT(kernel_deviation(kernels.kernels()[0], swapped), 1e-3);
  EXPECT_FALSE(std::isnan(cost::time_in_cache({kernels.kernels().begin(), 1}, cost::Settings::quick()).at(0)));
}

TEST_F(NativeTest, ADifferentFormulaDeviates) {  // the negative control of the check above
  const std::vector<NativeLobe> lobes = {lobe("c ^ 2")};
  const NativeKernels kernels(lobes, dir_, [] { return false; });
  EXPECT_GT(kernel_deviation(kernels.kernels()[0], lobe("c ^ 2 * 1.001")), 5e-4);
}

TEST_F(NativeTest, AFailedCompileSaysSo) {
  setenv("SPECULA_CXX", "/bin/false", 1);
  EXPECT_THROW(NativeKernels({lobe("c")}, dir_, [] { return false; }), std::runtime_error);
  unsetenv("SPECULA_CXX");
}

TEST_F(NativeTest, AStopEndsTheCompile) {
  EXPECT_THROW(NativeKernels({lobe("c")}, dir_, [] { return true; }), Interrupted);
}

TEST_F(NativeTest, ACompilerTheUserNamesIsUsedOrRefusedNeverReplaced) {
  setenv("SPECULA_CXX", "/nonexistent/c++", 1);
  EXPECT_THROW(native_compiler(), InvalidArgument);
  setenv("SPECULA_CXX", "sh", 1);  // a name is looked up in PATH
  EXPECT_EQ(std::filesystem::path(native_compiler()).filename(), "sh");
  unsetenv("SPECULA_CXX");
  EXPECT_EQ(native_compiler(), SPECULA_CXX);
  for (const char* bad : {"0", "-1", "3601", "2x", " 5", "1e2"}) {
    setenv("SPECULA_COMPILE_TIMEOUT", bad, 1);
    EXPECT_THROW(compile_limit(), InvalidArgument) << bad;
  }
  setenv("SPECULA_COMPILE_TIMEOUT", "7", 1);  // the control
  EXPECT_EQ(compile_limit(), std::chrono::seconds(7));
  unsetenv("SPECULA_COMPILE_TIMEOUT");
  EXPECT_EQ(compile_limit(), kDefaultCompileLimit);
}

// ---- Child processes: bounded, stoppable, and never outliving specula -------------------------

bool alive(pid_t pid) {  // running, not a zombie waiting for its reaper
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), {});
  const auto state = text.find(") ");
  return state != std::string::npos && text[state + 2] != 'Z';
}

bool dies_within(pid_t pid, std::chrono::milliseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (alive(pid) && std::chrono::steady_clock::now() < end) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return !alive(pid);
}

/// A tool that starts a child of its own (as a compiler driver starts cc1plus) and waits: their
/// pids in `pids`, one per line.
std::string tool_with_a_child(const std::filesystem::path& dir) {
  const auto script = dir / "tool.sh", pids = dir / "pids";
  std::ofstream(script) << "#!/bin/sh\nsleep 300 &\necho $! > '" << pids.string() << ".tmp'\necho $$ >> '" << pids.string()
                        << ".tmp'\nmv '" << pids.string() << ".tmp' '" << pids.string() << "'\nwait\n";
  std::filesystem::permissions(script, std::filesystem::perms::owner_all);
  return script.string();
}

std::vector<pid_t> wait_for_pids(const std::filesystem::path& file) {
  for (int i = 0; i < 1000 && !std::filesystem::exists(file); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::ifstream in(file);
  std::vector<pid_t> pids;
  for (pid_t pid = 0; in >> pid;) pids.push_back(pid);
  return pids;
}

TEST_F(NativeTest, AStoppedToolIsKilledWithTheProcessesItStarted) {
  std::atomic<bool> stop = false;
  std::vector<pid_t> pids;
  std::thread stopper([&] {
    pids = wait_for_pids(dir_ / "pids");
    for (pid_t pid : pids) EXPECT_TRUE(alive(pid)) << pid;  // the control: both run until the stop
    stop = true;
  });
  EXPECT_THROW(run_process({tool_with_a_child(dir_)}, dir_ / "log", [&] { return stop.load(); }, std::chrono::seconds(60)),
               Interrupted);
  stopper.join();
  ASSERT_EQ(pids.size(), 2u);
  for (pid_t pid : pids) EXPECT_TRUE(dies_within(pid, std::chrono::milliseconds(2000))) << pid;
}

TEST_F(NativeTest, AToolOutlivesNoSpeculaKilledBySigkill) {
  const pid_t specula = ::fork();
  ASSERT_GE(specula, 0);
  if (specula == 0) {
    try {
      run_process({tool_with_a_child(dir_)}, dir_ / "log", [] { return false; }, std::chrono::seconds(60));
    } catch (...) {
    }
    ::_exit(0);
  }
  const std::vector<pid_t> pids = wait_for_pids(dir_ / "pids");
  ASSERT_EQ(pids.size(), 2u);
  for (pid_t pid : pids) EXPECT_TRUE(alive(pid)) << pid;  // the control
  ::kill(specula, SIGKILL);
  int status = 0;
  ::waitpid(specula, &status, 0);
  for (pid_t pid : pids) EXPECT_TRUE(dies_within(pid, std::chrono::milliseconds(2000))) << pid;
}

TEST_F(NativeTest, AToolPastItsLimitIsKilledAndAMissingOneSaysSo) {
  const auto start = std::chrono::steady_clock::now();
  try {
    run_process({"sleep", "30"}, dir_ / "log", [] { return false; }, std::chrono::seconds(1));
    ADD_FAILURE() << "no time-out";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("took over 1 s"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  EXPECT_EQ(run_process({"sh", "-c", "exit 3"}, dir_ / "log", [] { return false; }, std::chrono::seconds(30)), 3);
  EXPECT_THROW(run_process({"/nonexistent/tool"}, dir_ / "log", [] { return false; }, std::chrono::seconds(1)),
               std::runtime_error);
}

TEST(ScratchDirectory, GoesWithItsOwnerAndTakesThoseOfEndedProcesses) {
  const auto temp = std::filesystem::temp_directory_path();
  const pid_t ended = ::fork();
  if (ended == 0) ::_exit(0);
  ::waitpid(ended, nullptr, 0);
  const auto stale = temp / fmt::format("{}spirv-{}-0", kScratchPrefix, ended);
  const auto old_style = temp / fmt::format("{}{}", kScratchPrefix, ended);
  const auto living = temp / fmt::format("{}{}-0", kScratchPrefix, ::getppid());  // the control: its owner runs
  for (const auto& dir : {stale, old_style, living}) std::filesystem::create_directories(dir / "sub");
  std::filesystem::path mine;
  {
    const ScratchDirectory scratch("spirv");
    mine = scratch.path();
    EXPECT_TRUE(std::filesystem::is_directory(mine));
    EXPECT_FALSE(std::filesystem::exists(stale));
    EXPECT_FALSE(std::filesystem::exists(old_style));
    EXPECT_TRUE(std::filesystem::exists(living));
    std::ofstream(mine / "lobes.cpp") << "int x;\n";
  }
  EXPECT_FALSE(std::filesystem::exists(mine));
  std::filesystem::remove_all(living);
}

}  // namespace
}  // namespace specula::design

namespace specula::design {
namespace {

// A SPIR-V module as words: the header, then instructions (word count << 16 | opcode).
std::string spirv(std::vector<std::uint32_t> words) {
  std::string out(words.size() * 4, '\0');
  std::memcpy(out.data(), words.data(), out.size());
  return out;
}

TEST(Spirv, CountsTheInstructionsOfFunctionBodies) {
  const std::uint32_t header[] = {0x07230203, 0x00010000, 0, 10, 0};
  std::vector<std::uint32_t> words(std::begin(header), std::end(header));
  const auto add = [&](std::uint32_t opcode, std::uint32_t length) {
    words.push_back(length << 16 | opcode);
    for (std::uint32_t i = 1; i < length; ++i) words.push_back(0);
  };
  add(17, 2);   // OpCapability: outside any function
  add(54, 5);   // OpFunction
  add(248, 2);  // OpLabel
  add(129, 5);  // OpFAdd
  add(253, 1);  // OpReturn
  add(56, 1);   // OpFunctionEnd
  EXPECT_EQ(spirv_function_instructions(spirv(words)), 5);
  words[0] = 0x12345678;  // the control: not SPIR-V
  EXPECT_FALSE(spirv_function_instructions(spirv(words)));
  words[0] = 0x07230203;
  words.back() = 9u << 16 | 56;  // an instruction running past the end
  EXPECT_FALSE(spirv_function_instructions(spirv(words)));
}

}  // namespace
}  // namespace specula::design
