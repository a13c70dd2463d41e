// The designer's native kernels: the generated Highway code computes the formula it was written
// from (to float accuracy), counts its operations, and fails loudly where it cannot compile.
#include <filesystem>
#include <gtest/gtest.h>
#include <unistd.h>

#include "design/native.h"
#include "design/spirv.h"

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
  EXPECT_THROW(NativeKernels({lobe("c")}, dir_, [] { return true; }), std::runtime_error);
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
