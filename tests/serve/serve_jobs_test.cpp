// `specula serve` under load and over time: many clients at once get the answers one client gets
// alone; fit jobs start, report a growing front, finish or are cancelled, and stop with the server.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <functional>
#include <memory>
#include <thread>

#include "serve_support.h"
#include "specula/expr/expr.h"

namespace specula::serve {
namespace {

using json = nlohmann::json;
using specula::testing::Answer;
using specula::testing::del;
using specula::testing::get;
using specula::testing::post;
using specula::testing::TestServer;
using ::testing::HasSubstr;

struct Call {
  std::string path;
  std::string body;  ///< empty: GET
};

Answer send(int port, const Call& c) { return c.body.empty() ? get(port, c.path) : post(port, c.path, c.body); }

const std::vector<Call>& mixed_calls() {
  static const std::vector<Call> calls{
      {"/api/models", ""},
      {"/api/normalize", R"({"model": "log", "n": "1:1000@20:log", "method": "both"})"},
      {"/api/eval", R"({"model": "log-normalized", "params": {"n": 50}, "cos": "0.9:1@50"})"},
      {"/api/eval", R"({"model": "ggx", "theta_i": 45, "theta_o": "0:89@30", "phi_o": 180})"},
      {"/api/albedo", R"({"model": "log-normalized", "params": {"n": 20}, "theta": [0, 45, 80]})"},
      {"/api/error", R"({"model": "schlick", "n": [2, 20, 200]})"},
      {"/api/glsl", R"({"model": "ward"})"},
      {"/api/check", R"({"model": "phong-normalized", "pairs": 200, "step": 5})"},
      {"/api/normalize", R"({"model": "log", "n": [0]})"},  // an error answer is an answer too
      {"/api/nope", ""},
  };
  return calls;
}

TEST(ServeConcurrency, ParallelClientsGetTheSequentialAnswers) {
  TestServer server;
  const auto& calls = mixed_calls();
  std::vector<Answer> expected;
  for (const auto& c : calls) expected.push_back(send(server.port(), c));
  for (const auto& a : expected) ASSERT_NE(a.status, 0);

  constexpr int kThreads = 8, kRequests = 50;
  std::vector<std::vector<std::pair<std::size_t, Answer>>> seen(kThreads);
  std::vector<std::thread> clients;
  for (int t = 0; t < kThreads; ++t)
    clients.emplace_back([&, t] {
      for (int i = 0; i < kRequests; ++i) {
        const std::size_t which = static_cast<std::size_t>(t * 7 + i * 3) % calls.size();
        seen[static_cast<std::size_t>(t)].emplace_back(which, send(server.port(), calls[which]));
      }
    });
  for (auto& c : clients) c.join();
  std::size_t compared = 0;
  for (const auto& answers : seen)
    for (const auto& [which, a] : answers) {
      EXPECT_EQ(a.status, expected[which].status) << calls[which].path;
      EXPECT_EQ(a.body, expected[which].body) << calls[which].path;
      ++compared;
    }
  EXPECT_EQ(compared, std::size_t{kThreads * kRequests});
}

json poll(int port, std::int64_t id, const std::function<bool(const json&)>& done) {
  return specula::testing::poll_job(port, fmt::format("/api/fit/{}", id), done);
}

std::int64_t start_fit(int port, const json& request) {
  const Answer a = specula::testing::post_json(port, "/api/fit", request);
  EXPECT_EQ(a.status, 202) << a.body;
  return a.status == 202 ? a.json()["job"].get<std::int64_t>() : -1;
}

TEST(ServeFit, AJobGrowsItsFrontAndIsGoneOnceCancelled) {
  TestServer server;
  // The paper's Fig. 5 table to 3 decimals, fitted with a budget far beyond this test's patience.
  const std::int64_t id = start_fit(server.port(), {{"model", "log"}, {"n", "paper50"}, {"round", 3},
                                                {"generations", 100000}, {"time", 60}});
  const json status = poll(server.port(), id, [](const json& s) { return s["front"].size() >= 3; });
  ASSERT_EQ(status["state"], "running") << status.dump(2);
  ASSERT_GE(status["front"].size(), 3u);
  EXPECT_EQ(status["variables"], json::array({"n"}));
  EXPECT_EQ(status["rows"], 50);
  for (const auto& c : status["front"]) {
    const auto formula = expr::parse(c["formula"].get<std::string>());
    const double k1000 = expr::evaluate(formula, std::vector<double>(formula.variables().size(), 1000.0));
    if (c["size"].get<int>() >= 3) {
      EXPECT_NEAR(k1000, 197.5, 197.5 * 0.05) << c.dump(2);
    }
    EXPECT_THAT(c["cpp"].get<std::string>(), HasSubstr("inline double fitted_coef("));
    EXPECT_THAT(c["glsl"].get<std::string>(), HasSubstr("float fitted_coef("));
  }
  const Answer cancelled = del(server.port(), fmt::format("/api/fit/{}", id));
  ASSERT_EQ(cancelled.status, 200);
  EXPECT_EQ(cancelled.json()["state"], "cancelled");
  EXPECT_EQ(get(server.port(), fmt::format("/api/fit/{}", id)).status, 404);
  EXPECT_EQ(del(server.port(), fmt::format("/api/fit/{}", id)).status, 404);
}

TEST(ServeFit, AJobOnColumnsFindsTheExactFormula) {
  TestServer server;
  json columns{{"x", json::array()}, {"y", json::array()}};
  for (int i = 1; i <= 20; ++i) {
    columns["x"].push_back(i);
    columns["y"].push_back(2.5 * i + 1);
  }
  // The smallest search that finds it (enumeration to size 5, one island of 20): the default's
  // enumeration of 20 000 forms was 14 s under the sanitizers.
  const std::int64_t id = start_fit(server.port(), {{"data", {{"columns", columns}, {"target", "y"}}}, {"generations", 2},
                                                    {"islands", 1}, {"population", 20}, {"enumerate_size", 5}});
  const json status = poll(server.port(), id, [](const json&) { return false; });
  ASSERT_EQ(status["state"], "done") << status.dump(2);
  EXPECT_EQ(status["stopped_by"], "generations");
  const json& chosen = status["front"][status["chosen"].get<std::size_t>()];
  EXPECT_LT(chosen["train_error"].get<double>(), 1e-9) << chosen.dump(2);
  EXPECT_THAT(chosen["cpp"].get<std::string>(), HasSubstr("inline double fitted_y(double x)"));
}

// "ops" and "size_weights" take expm1, log1p and asin, the ops added last, and every size on the
// front is positive and within "max_size" (the weight table once ended before them).
TEST(ServeFit, TheLastOperatorsHaveSizesAndWeights) {
  TestServer server;
  json columns{{"x", json::array()}, {"y", json::array()}};
  for (int i = 1; i <= 20; ++i) {
    columns["x"].push_back(0.05 * i);
    columns["y"].push_back(std::asin(0.05 * i) + std::log1p(0.05 * i));
  }
  const std::int64_t id = start_fit(server.port(), {{"data", {{"columns", columns}, {"target", "y"}}},
                                                {"ops", "+,*,asin,expm1,log1p"},
                                                {"size_weights", "asin=2,expm1=3,log1p=2"},
                                                {"max_size", 10},
                                                {"generations", 3}});
  const json status = poll(server.port(), id, [](const json&) { return false; });
  ASSERT_EQ(status["state"], "done") << status.dump(2);
  ASSERT_FALSE(status["front"].empty());
  for (const auto& c : status["front"]) {
    EXPECT_GE(c["size"].get<int>(), 1) << c.dump(2);
    EXPECT_LE(c["size"].get<int>(), 10) << c.dump(2);
  }
  EXPECT_LT(status["front"].back()["train_error"].get<double>(), 1e-9) << status.dump(2);
}

TEST(ServeFit, RunsAtMostTheLimitOfJobsAtOnce) {
  Limits limits;
  limits.max_running_fits = 1;
  TestServer server(limits);
  const json endless{{"model", "log"}, {"generations", 100000}, {"time", 60}};
  const std::int64_t first = start_fit(server.port(), endless);
  const Answer second = specula::testing::post_json(server.port(), "/api/fit", endless);
  EXPECT_EQ(second.status, 429) << second.body;
  EXPECT_THAT(second.body, HasSubstr("\"error\""));
  EXPECT_EQ(del(server.port(), fmt::format("/api/fit/{}", first)).status, 200);
}

TEST(ServeFit, StoppingTheServerCancelsItsJobs) {
  Api api;  // what Server::stop() calls, without the transport
  const Response started = api.handle({"POST", "/api/fit", R"({"model": "log", "generations": 100000, "time": 60})"});
  ASSERT_EQ(started.status, 202) << started.body;
  api.cancel_jobs();
  json status;
  for (int i = 0; i < 3000; ++i) {  // bounded: a cancelled job stops within one budget check
    status = json::parse(api.handle({"GET", "/api/fit/1", ""}).body);
    if (status["state"] != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(status["state"], "cancelled") << status.dump(2);
  EXPECT_EQ(status["stopped_by"], "cancelled");
  EXPECT_FALSE(status["front"].empty());
}

TEST(ServeFit, DestroyingTheServerWithAJobRunningReturns) {
  auto server = std::make_unique<TestServer>();
  const std::int64_t id = start_fit(server->port(), {{"model", "log"}, {"generations", 100000}, {"time", 60}});
  EXPECT_EQ(get(server->port(), fmt::format("/api/fit/{}", id)).json()["state"], "running");
  server.reset();  // stops listening, cancels the job and joins its thread (a hang fails by timeout)
}

/// A fit whose formula space (x and one constant, size 1) is smaller than its population: the
/// search filled the population for ever (src/fit/search.cpp, Island::populate), kept a core busy
/// after DELETE said "cancelled", held its place (later fits got 429) and stopped the server from
/// stopping.
const json& tiny_space() {
  static const json request{{"data", {{"columns", {{"x", {1, 2, 3, 4}}, {"y", {2, 4, 6, 8}}}}, {"target", "y"}}},
                            {"ops", "+"}, {"max_size", 1}, {"time", 2}};
  return request;
}

/// Runs `f` on a thread of its own and says whether it returned within `limit`. If it did not,
/// the test has failed and cannot go on (`f` holds what it uses): the process ends here, failing,
/// rather than hang until ctest's timeout.
bool returns_within(std::function<void()> f, std::chrono::seconds limit, const char* what) {
  auto done = std::make_shared<std::atomic<bool>>(false);
  std::thread([f = std::move(f), done] {
    f();
    *done = true;
  }).detach();
  const auto until = std::chrono::steady_clock::now() + limit;
  while (!*done && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (*done) return true;
  std::cerr << "FAILED: " << what << " did not return within " << limit.count() << " s\n";
  std::cout.flush();
  std::_Exit(1);
}

TEST(ServeFit, ASearchOfATinyFormulaSpaceEndsWithinItsTime) {
  auto server = std::make_unique<TestServer>();
  const std::int64_t id = start_fit(server->port(), tiny_space());
  json status;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);  // "time": 2
  while (std::chrono::steady_clock::now() < until) {
    status = get(server->port(), fmt::format("/api/fit/{}", id)).json();
    if (status["state"] != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(status["state"], "done") << "30 s after a start with \"time\": 2\n" << status.dump(2);
  EXPECT_TRUE(returns_within([&] { server.reset(); }, std::chrono::seconds(10), "stopping the server"));
}

TEST(ServeFit, ACancelledJobFreesItsPlaceAtOnceAndTheServerStillStops) {
  Limits limits;
  limits.max_running_fits = 1;
  auto server = std::make_unique<TestServer>(limits);
  const int port = server->port();
  const std::int64_t first = start_fit(port, tiny_space());
  ASSERT_GT(first, 0);
  std::this_thread::sleep_for(std::chrono::seconds(1));  // well into its search (a cancel at once came before it looped)
  EXPECT_EQ(del(port, fmt::format("/api/fit/{}", first)).status, 200);
  // Its place is free, whether or not its search has noticed the cancel yet.
  const json endless{{"model", "log"}, {"generations", 100000}, {"time", 60}};
  const std::int64_t second = start_fit(port, endless);
  EXPECT_GT(second, 0);
  // Control: the limit holds for jobs that run.
  EXPECT_EQ(specula::testing::post_json(port, "/api/fit", endless).status, 429);
  const auto stopping = std::chrono::steady_clock::now();
  EXPECT_TRUE(returns_within([&] { server.reset(); }, std::chrono::seconds(10), "stopping the server"));
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - stopping).count();
  std::cout << "[ measured ] stopped in " << took << " s with a cancelled tiny-space job and a running one\n";
  EXPECT_LT(took, 1.0);
}

TEST(ServeAddresses, LoopbackAndUrls) {
  for (const char* host : {"127.0.0.1", "127.3.2.1", "localhost", "::1"}) EXPECT_TRUE(is_loopback(host)) << host;
  for (const char* host : {"0.0.0.0", "192.168.1.2", "::", "example.org", "128.0.0.1"}) EXPECT_FALSE(is_loopback(host)) << host;
  EXPECT_EQ(url_of("127.0.0.1", 8080), "http://127.0.0.1:8080/");
  EXPECT_EQ(url_of("::1", 80), "http://[::1]:80/");
}

}  // namespace
}  // namespace specula::serve
