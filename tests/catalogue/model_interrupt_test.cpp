// Making a user-defined model is interruptible (issue 23): the support and kink search of a
// formula lobe and its quadrature normalization check the thread's work limit and the stop flag
// (specula/interrupt), so a server deadline or Ctrl-C stops them within one step, as it stops the
// built-in paths. Each case pairs the stop with a control that the same model is made without one.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fmt/format.h>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "specula/interrupt/interrupt.h"
#include "specula/catalogue/model_file.h"
#include "specula/normalize/quadrature.h"

namespace specula {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// One [[model]] of kind lobe with parameter n in (0, 1e9] and the steps `lets` before its lobe.
std::shared_ptr<const ModelInfo> lobe_definition(const std::string& lobe, const std::string& normalization,
                                                 const std::vector<std::string>& lets = {}) {
  std::string let_list;
  for (const auto& let : lets) let_list += fmt::format("\"{}\",\n", let);
  const std::string text = fmt::format(
      "[[model]]\nid = \"t\"\nname = \"t\"\nkind = \"lobe\"\nform = \"rv\"\nlet = [{}]\nlobe = \"{}\"\n"
      "normalization = \"{}\"\n[model.params.n]\ndefault = 1\nmin = 0\nmin_exclusive = true\nmax = 1e9\n",
      let_list, lobe, normalization);
  return std::make_shared<const ModelInfo>(parse_model_file(text, "test.toml").front());
}

/// c op c op … c, at most `characters` long (4096 is the most a formula may have).
std::string chain(const std::string& op, std::size_t characters = 4095) {
  std::string text = "c";
  while (text.size() + op.size() + 1 <= characters) text += op + "c";
  return text;
}

/// max(max(…max(c, c)…, c), c) at the formula length limit: every max is an argument of the kink
/// search, some 340 000 operations per grid point.
std::string nested_max() {
  const std::size_t depth = (4095 - 1) / 7;
  std::string text;
  for (std::size_t i = 0; i < depth; ++i) text += "max(";
  text += "c";
  for (std::size_t i = 0; i < depth; ++i) text += ",c)";
  return text;
}

TEST(ModelInterrupt, MakingAFormulaLobeChecksTheLimit) {
  const WorkLimit expired{Clock::now() - 1s, nullptr};
  for (const std::string& lobe : {std::string("c^n"), chain("*"), nested_max()}) {
    const auto info = lobe_definition(lobe, "none");
    {
      const ScopedLimit limit(expired);
      EXPECT_THROW(make_model(info), Interrupted) << lobe.substr(0, 40);
    }
    EXPECT_NO_THROW(make_model(info)) << lobe.substr(0, 40);  // control: no limit, no stop
  }
}

TEST(ModelInterrupt, MakingAFormulaLobeChecksTheStopFlag) {
  const auto info = lobe_definition(chain("*"), "none");
  request_stop(SIGINT);
  try {
    make_model(info);
    ADD_FAILURE() << "made the model despite a stop request";
  } catch (const Interrupted& e) {
    EXPECT_EQ(e.reason(), Interrupted::Reason::signal);
    EXPECT_EQ(e.signal(), SIGINT);
  }
  clear_stop_request();
  EXPECT_NO_THROW(make_model(info));  // control
}

/// The oscillating lobe, made costly to evaluate (four lets of 4095 characters, about
/// 16 000 operations per evaluation): its quadrature normalization is seconds of one integral.
TEST(ModelInterrupt, AQuadratureNormalizationStopsInsideItsIntegral) {
  const std::vector<std::string> lets{"a = " + chain("+", 4091), "b = " + chain("+", 4091), "d = " + chain("+", 4091),
                                      "g = " + chain("+", 4091)};
  const Model model = make_model(lobe_definition("max(0, sin(1000*n*acos(c))) + 0*(a + b + d + g)", "none", lets));
  std::atomic<bool> cancel{false};
  const ScopedLimit limit(WorkLimit{Clock::time_point::max(), &cancel});
  std::thread canceller([&] {
    std::this_thread::sleep_for(200ms);  // past the check before the integral
    cancel = true;
  });
  const auto start = Clock::now();
  EXPECT_THROW(normalize::quadrature(model.lobe(), Form::rv), Interrupted);
  const double took = seconds_since(start);
  canceller.join();
  EXPECT_LT(took, 5.0) << "the cancel at 0.2 s took effect after " << took << " s";
  std::cout << "[ measured ] the quadrature stopped after " << took << " s (cancelled at 0.2 s)\n";
}

}  // namespace
}  // namespace specula
