// The designer over HTTP: a design job runs `specula design` with capped budgets, reports its
// phase and front, ships members whose definitions load as models on every route, refuses bad
// settings naming the field, and holds one place that a second job waits for.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <set>
#include <thread>

#include "serve_support.h"

namespace specula::serve {
namespace {

using json = nlohmann::json;
using specula::testing::Answer;
using specula::testing::del;
using specula::testing::get;
using specula::testing::post_json;
using specula::testing::TestServer;
using ::testing::HasSubstr;

/// Polls the design job until it is no longer running; bounded (~10 minutes under the sanitizers).
json finished(int port, std::int64_t id) {
  json status;
  for (int i = 0; i < 1200; ++i) {
    const Answer a = get(port, fmt::format("/api/design/{}", id));
    if (a.status != 200) return json{{"http_status", a.status}, {"body", a.body}};
    status = a.json();
    if (status["state"] != "running") return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  return status;
}

std::int64_t start_design(int port, const json& request) {
  const Answer a = post_json(port, "/api/design", request);
  EXPECT_EQ(a.status, 202) << a.body;
  EXPECT_THAT(a.body, HasSubstr("/api/design/"));
  return a.status == 202 ? a.json()["job"].get<std::int64_t>() : -1;
}

TEST(ServeDesign, AJobShipsMembersThatLoadAsModels) {
  TestServer server;
  // The first five shapes: the fifth is the first whose constants get laws in n (all eight: 14 s
  // under the sanitizers).
  const std::int64_t id = start_design(server.port(), {{"target", "phong"}, {"range", {1, 100}}, {"ops", "fma,mul"},
                                                {"max_cost", 2}, {"max_forms", 5}, {"time", 30}, {"timing", false}});
  const json status = finished(server.port(), id);
  ASSERT_EQ(status["state"], "done") << status.dump(2);
  EXPECT_EQ(status["final"], true);
  EXPECT_EQ(status["range"], json::array({1, 100}));
  ASSERT_FALSE(status["front"].empty()) << status.dump(2);
  std::set<std::string> references;
  for (const auto& r : status["references"]) references.insert(r["id"].get<std::string>());
  EXPECT_TRUE(references.contains("log") && references.contains("schlick")) << status["references"].dump(2);
  int passed = 0;
  for (const auto& member : status["front"]) {
    EXPECT_FALSE(member["check"].get<std::string>().empty()) << member.dump(2);  // pass, or what fails
    ASSERT_TRUE(member.contains("definition_normalized")) << member.dump(2);
    // The member's definition, as the page's "Add" sends it, on the routes a model card calls.
    const json model = member["definition_normalized"];
    const Answer eval = post_json(server.port(), "/api/eval", {{"model", model}, {"params", {{"n", 20}}}, {"cos", {1, 0.9}}});
    ASSERT_EQ(eval.status, 200) << eval.body;
    const json rows = eval.json()["rows"];  // a copy: the range of a temporary's member would dangle
    for (const auto& row : rows) EXPECT_TRUE(std::isfinite(row["value"].get<double>())) << eval.body;
    const Answer albedo = post_json(server.port(), "/api/albedo", {{"model", model}, {"params", {{"n", 20}}}, {"theta", {0}}});
    ASSERT_EQ(albedo.status, 200) << albedo.body;
    if (member["check"] != "pass") continue;
    ++passed;
    EXPECT_NEAR(albedo.json()["rows"][0]["albedo"].get<double>(), 1.0, 1e-3) << "normalized: albedo 1 at normal incidence";
  }
  EXPECT_GT(passed, 0) << status["front"].dump(2);
}

// An engine term as the target (issue 41): no range sent, the term's own is used; its references
// are the engines' approximations and the term itself; a member's definition loads as a model.
TEST(ServeDesign, AnEngineTermIsATargetWithItsEnginesReferences) {
  TestServer server;
  const std::int64_t id = start_design(server.port(), {{"target", "schlick-weight"}, {"ops", "fma,mul"}, {"max_cost", 1},
                                                       {"time", 30}, {"timing", false}});
  const json status = finished(server.port(), id);
  ASSERT_EQ(status["state"], "done") << status.dump(2);
  std::set<std::string> references;
  for (const auto& r : status["references"]) references.insert(r["id"].get<std::string>());
  EXPECT_EQ(references, (std::set<std::string>{"unreal-exp2", "exact"}));
  ASSERT_FALSE(status["front"].empty());
  const json member = status["front"].back();
  EXPECT_EQ(member["check"], "-");
  EXPECT_FALSE(member.contains("definition"));  // a function, not a lobe: no model card to add
  // The terms the page lists, from the server's own table.
  const json terms = get(server.port(), "/api/terms").json();
  ASSERT_TRUE(terms.is_array());
  std::set<std::string> ids;
  for (const auto& t : terms) ids.insert(t["id"].get<std::string>());
  EXPECT_TRUE(ids.contains("schlick-weight") && ids.contains("smith-g2-ggx")) << terms.dump();
  for (const auto& t : terms) {
    if (t["id"] == "smith-g2-ggx") {
      EXPECT_EQ(t["variables"], json::array({"NoV", "NoL"}));
    }
  }
}

TEST(ServeDesign, BadSettingsAreRefusedNamingTheField) {
  TestServer server;
  const auto refused = [&](const json& request, const std::string& field) {
    const Answer a = post_json(server.port(), "/api/design", request);
    EXPECT_EQ(a.status, 400) << request.dump() << " → " << a.body;
    if (a.status == 400) {
      EXPECT_EQ(a.json()["field"], field) << a.body;
    }
  };
  refused({{"max_cost", 6}}, "max_cost");  // the server's cap, below the CLI's
  refused({{"time", 1000}}, "time");
  refused({{"range", {0, 10}}}, "range");   // n > 0
  refused({{"range", {10, 1}}}, "range");
  refused({{"range", "1:10"}}, "range");
  refused({{"target", "lambert"}}, "target");
  refused({{"target", "nope"}}, "target");
  refused({{"ops", "nope"}}, "ops");
  refused({{"objective", "x"}}, "objective");
  refused({{"zone", 2}}, "zone");
  refused({{"params", {{"alpha", 1}}}}, "params");
  refused({{"bogus", 1}}, "bogus");
  // The control: a request within every range starts.
  const std::int64_t id = start_design(server.port(), {{"max_cost", 1}, {"ops", "fma"}, {"time", 5}, {"timing", false}});
  EXPECT_EQ(del(server.port(), fmt::format("/api/design/{}", id)).status, 200);
}

TEST(ServeDesign, OneJobRunsAtATimeAndCancellingFreesItsPlace) {
  TestServer server;
  const json heavy{{"max_cost", 5}, {"time", 120}, {"timing", false}};
  const std::int64_t id = start_design(server.port(), heavy);
  const Answer second = post_json(server.port(), "/api/design", heavy);
  EXPECT_EQ(second.status, 429) << second.body;
  EXPECT_THAT(second.body, HasSubstr("design jobs are running"));
  const Answer cancelled = del(server.port(), fmt::format("/api/design/{}", id));
  ASSERT_EQ(cancelled.status, 200);
  EXPECT_EQ(cancelled.json()["state"], "cancelled");
  EXPECT_EQ(get(server.port(), fmt::format("/api/design/{}", id)).status, 404);
  EXPECT_EQ(get(server.port(), "/api/design/x").status, 404);
  EXPECT_EQ(post_json(server.port(), "/api/design/1", json::object()).status, 405);
}

}  // namespace
}  // namespace specula::serve
