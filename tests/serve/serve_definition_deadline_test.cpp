// The request deadline holds for definition objects (issue 23): a model sent in the request is
// made (support and kink search, quadrature normalization) and integrated under the request's
// work limit, so the issue's definitions, and ones beyond any deadline by construction, are
// answered by about the deadline on every computing route, and four at once give their places
// back. The deadline is short here (Limits::request_seconds); the bounds are generous (a loaded
// 2-core machine, the sanitizers): they tell "stopped at the deadline" from "ran to the end".
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fmt/format.h>
#include <string>
#include <thread>
#include <vector>

#include "serve_support.h"

namespace specula::serve {
namespace {

using json = nlohmann::json;
using specula::testing::Answer;
using specula::testing::post_json;
using specula::testing::seconds_since;
using specula::testing::TestServer;
using specula::testing::chain;
using specula::testing::costly_oscillating;
using specula::testing::exponent;
using specula::testing::oscillating;
using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

constexpr double kDeadline = 0.5;  // seconds
constexpr double kMargin = 3;      // seconds past the deadline an answer may take

Limits short_deadline() {
  Limits limits;
  limits.request_seconds = kDeadline;
  return limits;
}



/// The issue's 4095-character lobe c*c*…*c (its check took 80 s before, its albedo 40 s).
json long_product() { return {{"kind", "lobe"}, {"form", "rv"}, {"lobe", chain("*")}, {"normalization", "none"}}; }


/// Beyond any deadline by construction, however fast the numerics become: 584 nested max(), each
/// an argument of the kink search (2–3 s per model made, and a request makes it several times),
/// and costly_oscillating() (serve_support.h).
json nested_max() {
  std::string lobe;
  for (int i = 0; i < 584; ++i) lobe += "max(";
  lobe += "c^n";
  for (int i = 0; i < 584; ++i) lobe += ",c)";
  return {{"kind", "lobe"}, {"form", "rv"}, {"lobe", lobe}, {"normalization", "none"}, {"params", {{"n", exponent()}}}};
}


const char* const kComputingRoutes[] = {"/api/eval", "/api/normalize", "/api/albedo", "/api/check", "/api/error", "/api/glsl"};

json request_for(const std::string& route, const json& model) {
  json body{{"model", model}};
  if (route == "/api/eval") body["cos"] = {1, 0.5};
  return body;
}

struct Post {
  std::string path;
  json body;
};

/// Sends `r`; checks that the answer came within the deadline and the margin, and is either a
/// result or the deadline's 503 (a result only if `may_finish`).
void expect_answer_by_the_deadline(int port, const Post& r, bool may_finish) {
  const std::string what = r.path + " " + r.body.dump().substr(0, 70);
  const auto start = Clock::now();
  const Answer a = post_json(port, r.path, r.body);
  const double took = seconds_since(start);
  std::cout << "[ measured ] " << what << "… → " << a.status << " in " << took << " s\n";
  EXPECT_LT(took, kDeadline + kMargin) << what << " answered after " << took << " s";
  if (may_finish && a.status == 200) return;
  EXPECT_EQ(a.status, 503) << what << " → " << a.body.substr(0, 200);
  EXPECT_THAT(a.body, HasSubstr("more than")) << what;
}

TEST(ServeDefinitionDeadline, TheIssuesDefinitionsAreAnsweredByTheDeadlineOnEveryRoute) {
  TestServer server(short_deadline());
  std::vector<Post> requests{{"/api/check", {{"model", long_product()}}}, {"/api/albedo", {{"model", long_product()}}}};
  for (const std::string route : kComputingRoutes) requests.push_back({route, request_for(route, oscillating())});
  requests.push_back({"/api/normalize", {{"model", oscillating()}, {"n", "1:1e6@2000:log"}}});
  for (const Post& r : requests) expect_answer_by_the_deadline(server.port(), r, true);
}

TEST(ServeDefinitionDeadline, DefinitionsBeyondAnyDeadlineAre503AtTheDeadlineOnEveryRoute) {
  TestServer server(short_deadline());
  std::vector<Post> requests;
  for (const std::string route : kComputingRoutes) requests.push_back({route, request_for(route, nested_max())});
  requests.push_back({"/api/albedo", {{"model", costly_oscillating()}, {"theta", {40}}}});
  requests.push_back({"/api/check", {{"model", costly_oscillating()}, {"step", 40}}});
  for (const Post& r : requests) expect_answer_by_the_deadline(server.port(), r, false);
  // Control: the same server answers a light request of a definition.
  const Answer light = post_json(server.port(), "/api/eval", request_for("/api/eval", long_product()));
  EXPECT_EQ(light.status, 200) << light.body;
}

TEST(ServeDefinitionDeadline, FourAtOnceGiveTheirPlacesBackAtTheDeadline) {
  TestServer server(short_deadline());
  const Post heavy{"/api/check", {{"model", nested_max()}}};
  std::vector<std::thread> clients;
  for (std::size_t i = 0; i < Limits{}.max_busy_requests; ++i)
    clients.emplace_back([&] { expect_answer_by_the_deadline(server.port(), heavy, false); });
  for (auto& client : clients) client.join();
  // Every place is free again: a computed request is admitted and answered.
  const Answer after = post_json(server.port(), "/api/eval", {{"model", "log"}, {"cos", {1}}});
  EXPECT_EQ(after.status, 200) << after.body;
}

}  // namespace
}  // namespace specula::serve
