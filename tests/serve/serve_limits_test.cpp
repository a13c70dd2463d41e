// `specula serve` against hostile or unlucky clients: no request, connection or client may hold
// the server, amplify its answers, or get a 500 for bad input (docs/serve.md, "Limits"). Each
// test pairs the refusal with a control that the same server answers normally. Time bounds are
// generous (the sanitizers and a loaded 2-core machine slow everything several times): they tell
// "bounded" from "held", not fast from slow.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fmt/format.h>
#include <functional>
#include <memory>
#include <thread>
#include <vector>

#include "../../src/serve/assets.h"
#include "serve_support.h"
#include "specula/analysis/albedo.h"
#include "specula/analysis/check.h"
#include "specula/analysis/error.h"
#include "specula/analysis/monte_carlo.h"
#include "specula/interrupt/interrupt.h"
#include "specula/catalogue/catalogue.h"
#include "specula/normalize/normalize.h"

namespace specula::serve {
namespace {

using json = nlohmann::json;
using specula::testing::Answer;
using specula::testing::get;
using specula::testing::post;
using specula::testing::RawConnection;
using specula::testing::seconds_since;
using specula::testing::TestServer;
using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

/// A request that needs far more than any deadline, however fast the numerics become: a check
/// (albedo at every angle of a 1° grid) of a model whose albedo at one angle takes some 10 s.
/// (GGX at a 0.01° step, the request this was, took 15.6 s before requests had deadlines and
/// finished within 5 s once the albedo quadrature was fast.)
const std::string kHeavyCheck = nlohmann::json{{"model", specula::testing::costly_oscillating()}, {"step", 1}}.dump();

/// The JSON error of an answer's body, or a null value if the body is not a JSON error.
json error_of(const std::string& body) {
  const json j = json::parse(body, nullptr, false);
  return j.is_object() && j.contains("error") && j["error"].is_string() ? j : json();
}

std::string with_ranges(const std::string& path, const std::string& ranges) {
  return fmt::format("GET {} HTTP/1.1\r\nHost: 127.0.0.1\r\nRange: {}\r\nConnection: close\r\n\r\n", path, ranges);
}

std::string repeated_joined(const std::string& item, int count, const std::string& separator = ",") {
  std::string list;
  for (int i = 0; i < count; ++i) list += (i ? separator : "") + item;
  return list;
}

// ---- finding 1: Range amplification ------------------------------------------------------------

TEST(ServeRanges, ManyOverlappingRangesGetTheResourceOnce) {
  TestServer server;
  const Asset* app = find_asset("/app.js");
  ASSERT_NE(app, nullptr);
  const std::string models = get(server.port(), "/api/models").body;
  ASSERT_FALSE(models.empty());
  // 1500 ranges "0-" (4.5 kB of request) were 1500 copies: 14 MB for app.js, 16.5 MB for models.
  const std::string ranges = "bytes=" + repeated_joined("0-", 1500);
  for (const auto& [path, whole] : {std::pair<std::string, std::string>{"/app.js", std::string(app->bytes)}, {"/api/models", models}}) {
    RawConnection c(server.port());
    ASSERT_TRUE(c.send(with_ranges(path, ranges)));
    const auto r = c.read();
    EXPECT_EQ(r.status, 200) << path << "\n" << r.head;
    EXPECT_TRUE(r.body == whole) << path << ": " << r.body.size() << " bytes, not the resource's " << whole.size();
    EXPECT_LE(r.bytes, whole.size() + 1024) << path << ": " << r.bytes << " bytes for a resource of " << whole.size();
    EXPECT_EQ(r.header("Content-Range"), "") << path;
    EXPECT_EQ(r.header("Accept-Ranges"), "none") << path;
  }
  // One range is not served either (docs/serve.md: Range is ignored): still the whole file.
  RawConnection one(server.port());
  ASSERT_TRUE(one.send(with_ranges("/app.js", "bytes=0-9")));
  const auto r = one.read();
  EXPECT_EQ(r.status, 200);
  EXPECT_TRUE(r.body == app->bytes) << r.body.size() << " bytes";
}

TEST(ServeRanges, AMalformedRangeIs416WithAJsonErrorOfItsOwnSize) {
  TestServer server;
  // httplib refuses a Range it cannot parse before any handler runs; valid ranges before the bad
  // one must not multiply even this error's body.
  for (const std::string& ranges : {std::string("bytes=5-1"), "bytes=" + repeated_joined("0-", 1500) + ",5-1", std::string("lines=1-2")}) {
    for (const char* path : {"/app.js", "/api/models"}) {
      RawConnection c(server.port());
      ASSERT_TRUE(c.send(with_ranges(path, ranges)));
      const auto r = c.read();
      EXPECT_EQ(r.status, 416) << path << " " << ranges.substr(0, 20) << "\n" << r.head << r.body.substr(0, 300);
      EXPECT_FALSE(error_of(r.body).is_null()) << r.body.substr(0, 300);
      EXPECT_LT(r.bytes, 1024u) << path;
    }
  }
}

// ---- finding 2: a path that is not UTF-8 -------------------------------------------------------

TEST(ServePaths, BytesThatAreNotUtf8GetA404WithValidJson) {
  TestServer server;
  for (const char* line : {"GET /%c0%ae%c0%ae/etc/passwd HTTP/1.1", "GET /api/%ff%fe HTTP/1.1", "GET /%80.js HTTP/1.1",
                           "POST /api/%c3 HTTP/1.1", "DELETE /%ed%a0%80 HTTP/1.1", "GET /api/fit/%ff HTTP/1.1"}) {
    const auto [status, text] = specula::testing::raw_request(server.port(), line);
    EXPECT_EQ(status, 404) << line << "\n" << text;
    const auto body = text.substr(std::min(text.size(), text.find("\r\n\r\n") + 4));
    const json e = error_of(body);  // json::parse rejects invalid UTF-8
    ASSERT_FALSE(e.is_null()) << line << "\n" << text;
    EXPECT_THAT(e["error"].get<std::string>(), HasSubstr("no such resource")) << line;
  }
  // Control: the same route with a valid name answers.
  EXPECT_EQ(specula::testing::raw_request(server.port(), "GET /api/models HTTP/1.1").first, 200);
}

// A request line httplib cannot parse is answered once, with JSON, and the connection closes:
// what follows it (its headers) is never read as a second request.
TEST(ServePaths, AnUnparsableRequestLineIsAnsweredOnceWithJson) {
  TestServer server;
  for (const char* line : {"GET /a b HTTP/1.1", "GET  HTTP/1.1", "FOO / HTTP/1.1", "get /api/models HTTP/1.1",
                           "GE\x01T / HTTP/1.1"}) {
    const auto [status, text] = specula::testing::raw_request(server.port(), line);
    EXPECT_EQ(status, 400) << line << "\n" << text;
    std::size_t answers = 0;
    for (auto at = text.find("HTTP/1.1 "); at != std::string::npos; at = text.find("HTTP/1.1 ", at + 1)) ++answers;
    EXPECT_EQ(answers, 1u) << line << "\n" << text;
    const auto body = text.substr(std::min(text.size(), text.find("\r\n\r\n") + 4));
    EXPECT_FALSE(error_of(body).is_null()) << line << "\n" << text;
  }
  // Control: a well-formed request on the same server is one 200.
  EXPECT_EQ(specula::testing::raw_request(server.port(), "GET /api/models HTTP/1.1").first, 200);
}

TEST(ServePaths, EveryErrorMessageIsValidJsonWhateverItEchoes) {
  for (const std::string& text : {std::string("\xc0\xae"), std::string("a\xff" "b"), std::string("\xed\xa0\x80"), std::string("ok é")}) {
    const Response r = error_response(404, "no such resource: /" + text, "fi\xfe" "ld");
    const json e = json::parse(r.body, nullptr, false);
    ASSERT_TRUE(e.is_object()) << r.body;
    EXPECT_THAT(e["error"].get<std::string>(), HasSubstr("no such resource: /"));
  }
  EXPECT_EQ(json::parse(error_response(400, "ok é").body)["error"], "ok é");  // valid text unchanged
}

// ---- HEAD --------------------------------------------------------------------------------------

TEST(ServeHead, HeadIsGetWithoutTheBody) {
  TestServer server;
  for (const char* path : {"/api/models", "/", "/app.js"}) {
    const Answer whole = get(server.port(), path);
    ASSERT_EQ(whole.status, 200);
    RawConnection c(server.port());
    ASSERT_TRUE(c.send(fmt::format("HEAD {} HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n", path)));
    const auto r = c.read(5s, true);
    EXPECT_EQ(r.status, 200) << path << "\n" << r.head;
    EXPECT_EQ(r.header("Content-Length"), std::to_string(whole.body.size())) << path;
    EXPECT_EQ(r.header("Content-Type"), whole.content_type) << path;
    // No body: the next bytes on the connection are the next answer's.
    ASSERT_TRUE(c.send("GET /api/models HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n"));
    EXPECT_EQ(c.read(5s).status, 200) << "after HEAD " << path;
  }
  const auto [status, text] = specula::testing::raw_request(server.port(), "HEAD /api/eval HTTP/1.1");
  EXPECT_EQ(status, 405) << text;
  EXPECT_THAT(text, HasSubstr("Allow: POST"));
}

// ---- finding 3: one request, or one client, holding the server -------------------------------

TEST(ServeDeadline, ARequestPastItsTimeCapIs503AndTheServerAnswersOn) {
  TestServer server;  // the default cap: Limits::request_seconds = 5
  const auto start = Clock::now();
  const Answer slow = post(server.port(), "/api/check", kHeavyCheck);
  const double took = seconds_since(start);
  EXPECT_EQ(slow.status, 503) << slow.body;
  EXPECT_EQ(slow.content_type, "application/json");
  EXPECT_THAT(error_of(slow.body).value("error", ""), HasSubstr("more than 5 s")) << slow.body;
  EXPECT_LT(took, 15) << "503 after " << took << " s";  // 5 s + the time to notice it
  std::cout << "[ measured ] the heavy check answered " << slow.status << " after " << took << " s\n";
  // Control: the same endpoint with a coarse grid is well within the cap.
  const Answer quick = post(server.port(), "/api/check", R"({"model": "ggx", "step": 15, "pairs": 100})");
  EXPECT_EQ(quick.status, 200) << quick.body;
}

TEST(ServeDeadline, EveryComputedEndpointStopsAtTheCap) {
  Limits limits;
  limits.request_seconds = 0.2;  // short, so that each endpoint's heaviest request is well past it (≥ 1 s here)
  TestServer server(limits);
  const std::string heavy_albedo = json{{"model", specula::testing::costly_oscillating()}, {"theta", "0:89@200"}}.dump();
  // 2000 k by quadrature of a lobe that takes some 0.1 s each: the start of a fit computes its data.
  const std::string heavy_fit = json{{"model", specula::testing::oscillating()}, {"n", "1:1000@2000"}}.dump();
  // The log lobe's error takes ~0.12 s (release) at 2000 n; the oscillating lobe's k, ~0.1 s each.
  const std::string heavy_error = json{{"model", specula::testing::oscillating()}, {"n", "1:1000@2000"}}.dump();
  const std::pair<const char*, const char*> heavy[] = {
      {"/api/check", kHeavyCheck.c_str()},
      {"/api/check", R"({"model": "ggx", "sweep": "alpha", "values": "0.1:0.9@50", "pairs": 100000, "step": 45})"},
      {"/api/albedo", heavy_albedo.c_str()},
      {"/api/albedo", R"({"model": "ggx", "theta": "0:80@10", "method": "monte-carlo", "samples": 1000000})"},
      {"/api/normalize", R"({"model": "gauss", "n": "1:1000@50", "condition": "strict", "step": 0.01})"},
      {"/api/error", heavy_error.c_str()},
      {"/api/fit", heavy_fit.c_str()},
  };
  for (const auto& [path, body] : heavy) {
    const auto start = Clock::now();
    const Answer a = post(server.port(), path, body);
    const double took = seconds_since(start);
    std::cout << "[ measured ] " << path << " " << std::string(body).substr(0, 40) << "… → " << a.status << " in " << took << " s " << a.body.substr(0, 120) << "\n";
    if (a.status == 400) continue;  // beyond a count limit already: refused before any work
    EXPECT_EQ(a.status, 503) << path << " " << body << " → " << a.body;
    EXPECT_LT(took, 5) << path << " " << body;
  }
}

/// What the endpoints stand on: each long loop of the library checks its thread's work limit
/// once per step, so that a deadline stops it within one step, not at its end.
TEST(ServeDeadline, TheLibrarysLongLoopsStopAtTheirThreadsLimit) {
  const Model ggx = make_model("ggx");
  const Model lobe = make_model("log-normalized", {{"n", 20}});
  analysis::CheckOptions many_pairs;
  many_pairs.reciprocity_pairs = 100'000'000;
  many_pairs.grid_step_deg = 45;
  const std::pair<const char*, std::function<void()>> loops[] = {
      {"max_albedo grid", [&] { analysis::max_albedo(ggx, 0.01); }},
      {"reciprocity pairs", [&] { analysis::check(lobe, many_pairs); }},
      {"albedo of one angle", [&] { for (int i = 0; i < 1000; ++i) analysis::albedo(ggx, 0.5); }},
      {"monte carlo blocks", [&] { analysis::albedo_monte_carlo(ggx, 0.5, 1'000'000'000, 1); }},
      {"strict normalization", [&] { for (int i = 0; i < 1000; ++i) analysis::strict_coefficient(lobe, 0.01); }},
      {"error sweeps", [&] { for (int i = 0; i < 100000; ++i) analysis::approximation_error(lobe.lobe(), make_model("phong", {{"n", 20}}).lobe()); }},
      {"normalization", [&] { for (int i = 0; i < 10'000'000; ++i) normalize::coefficient(lobe.lobe(), Form::rv, normalize::Method::quadrature); }},
  };
  for (const auto& [what, loop] : loops) {
    const ScopedLimit limit(WorkLimit::after(200ms));
    const auto start = Clock::now();
    EXPECT_THROW(loop(), Interrupted) << what;
    const double took = seconds_since(start);
    EXPECT_LT(took, 3.0) << what;  // 0.2 s and one step
    std::cout << "[ measured ] " << what << ": stopped after " << took << " s\n";
  }
  // Control: without a limit the same calls return (the cheap ones).
  EXPECT_GT(analysis::albedo(ggx, 0.5).value, 0);
  EXPECT_GT(normalize::coefficient(lobe.lobe(), Form::rv), 0);
}

/// Sends `kHeavyCheck` from `count` threads; joins them in the destructor.
class HeavyLoad {
 public:
  HeavyLoad(int port, int count) : answers_(static_cast<std::size_t>(count)) {
    for (int i = 0; i < count; ++i)
      threads_.emplace_back([this, port, i] { answers_[static_cast<std::size_t>(i)] = post(port, "/api/check", kHeavyCheck); });
  }
  ~HeavyLoad() { join(); }
  const std::vector<Answer>& join() {
    for (auto& t : threads_)
      if (t.joinable()) t.join();
    return answers_;
  }

 private:
  std::vector<Answer> answers_;
  std::vector<std::thread> threads_;
};

TEST(ServeAdmission, ModelsAndThePageAnswerWithinASecondWhileHeavyRequestsRun) {
  TestServer server;
  HeavyLoad load(server.port(), 8);  // 8 × 15 s of work: before the limits, /api/models waited 13 s
  std::this_thread::sleep_for(500ms);  // the heavy requests have started
  double slowest = 0;
  for (int i = 0; i < 6; ++i) {
    for (const char* path : {"/api/models", "/", "/app.js"}) {
      const auto start = Clock::now();
      httplib::Client client("127.0.0.1", server.port());
      client.set_read_timeout(10);
      const auto r = client.Get(path);
      const double took = seconds_since(start);
      slowest = std::max(slowest, took);
      ASSERT_TRUE(r) << path;
      EXPECT_EQ(r->status, 200) << path;
      EXPECT_LT(took, 1.0) << path << " took " << took << " s while 8 heavy requests ran";
    }
    std::this_thread::sleep_for(300ms);
  }
  std::cout << "[ measured ] slowest light answer under load: " << slowest << " s\n";
  int busy = 0, timed_out = 0;
  for (const Answer& a : load.join()) {
    ASSERT_EQ(a.status, 503) << a.body;  // none is within the cap; each is an answer, in JSON
    const std::string message = error_of(a.body).value("error", "");
    busy += message.find("busy") != std::string::npos;
    timed_out += message.find("more than") != std::string::npos;
  }
  EXPECT_EQ(busy + timed_out, 8);
  EXPECT_GE(busy, 1) << "8 heavy requests, " << Limits{}.max_busy_requests << " places: some were refused as busy";
  EXPECT_GE(timed_out, 1);
}

TEST(ServeAdmission, BeyondTheBusyLimitIs503WithRetryAfterAndAPlaceIsFreedAfter) {
  Limits limits;
  limits.max_busy_requests = 1;
  limits.busy_wait_seconds = 0.2;
  limits.request_seconds = 3;
  TestServer server(limits);
  HeavyLoad load(server.port(), 1);
  std::this_thread::sleep_for(500ms);
  const auto start = Clock::now();
  RawConnection c(server.port());
  const std::string body = R"({"model": "log", "cos": [1]})";
  ASSERT_TRUE(c.send(fmt::format("POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: {}\r\n\r\n{}", body.size(), body)));
  const auto refused = c.read(10s);
  EXPECT_EQ(refused.status, 503) << refused.head << refused.body;
  EXPECT_EQ(refused.header("Retry-After"), "1");
  EXPECT_THAT(error_of(refused.body).value("error", ""), HasSubstr("busy"));
  EXPECT_LT(seconds_since(start), 2.0);
  EXPECT_EQ(get(server.port(), "/api/models").status, 200);  // not a computed request: not limited
  EXPECT_EQ(load.join()[0].status, 503);  // the heavy one, at its 3 s cap
  EXPECT_EQ(post(server.port(), "/api/eval", body).status, 200);  // its place is free again
}

TEST(ServeSlowClients, DrippingConnectionsDoNotHoldTheServer) {
  Limits limits;
  limits.read_seconds = 3;
  TestServer server(limits);
  constexpr int kDrips = 64;  // each sends a byte of its request every 200 ms for 2.4 s
  std::vector<std::unique_ptr<RawConnection>> drips;
  for (int i = 0; i < kDrips; ++i) drips.push_back(std::make_unique<RawConnection>(server.port()));
  const std::string request = "GET /api/models HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Drip: " + std::string(200, 'a');
  struct Dripper {
    std::thread thread;
    ~Dripper() { thread.join(); }
  } dripper{std::thread([&] {
    for (std::size_t i = 0; i < 12; ++i) {
      for (auto& d : drips) d->send(std::string(1, request[i]));
      std::this_thread::sleep_for(200ms);
    }
  })};
  std::this_thread::sleep_for(500ms);
  double slowest = 0;
  for (int i = 0; i < 5; ++i) {
    const auto start = Clock::now();
    httplib::Client client("127.0.0.1", server.port());
    client.set_read_timeout(5);
    const auto r = client.Get("/api/models");
    slowest = std::max(slowest, seconds_since(start));
    ASSERT_TRUE(r) << "no answer while " << kDrips << " connections dripped";
    EXPECT_EQ(r->status, 200);
    EXPECT_LT(seconds_since(start), 1.0);
    std::this_thread::sleep_for(200ms);
  }
  std::cout << "[ measured ] slowest /api/models among " << kDrips << " dripping connections: " << slowest << " s\n";
  // Each dripping request is cut off at its read deadline with a 408 and closed.
  int timeouts = 0;
  for (auto& d : drips) {
    const auto start = Clock::now();
    const auto r = d->read(10s);
    timeouts += r.status == 408 && !error_of(r.body).is_null();
    if (r.status != 408) std::cout << "drip: " << r.status << " after " << seconds_since(start) << " s: " << r.head << r.body << "\n";
    EXPECT_TRUE(d->closed_within(2s));
  }
  EXPECT_EQ(timeouts, kDrips);
}

TEST(ServeBodies, AnOversizedContentLengthIs413AtOnceAndTheConnectionCloses) {
  TestServer server;
  for (const char* length : {"1000000000000", "65537", "18446744073709551615", "-1"}) {
    RawConnection c(server.port());
    const auto start = Clock::now();
    ASSERT_TRUE(c.send(fmt::format("POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: {}\r\n\r\n", length)));
    const auto r = c.read(10s);
    const double took = seconds_since(start);
    EXPECT_EQ(r.status, 413) << length << "\n" << r.head;
    EXPECT_EQ(error_of(r.body).value("field", ""), "body") << r.body;
    EXPECT_LT(took, 2.0) << "Content-Length " << length << ": 413 after " << took << " s";
    EXPECT_EQ(r.header("Connection"), "close");
    EXPECT_TRUE(c.closed_within(2s)) << length;
  }
  // Control: the largest allowed body is read and answered.
  const std::string body = R"({"model": "log", "cos": [)" + repeated_joined("1.0000000", 6500) + "]}";
  ASSERT_LE(body.size(), Limits{}.max_body_bytes);
  EXPECT_EQ(post(server.port(), "/api/eval", body).status, 200);
}

TEST(ServeBodies, ABodyWithoutContentLengthIs411) {
  TestServer server;
  for (const char* head : {"POST /api/eval HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n",
                           "POST /api/eval HTTP/1.1\r\nHost: x\r\n\r\n"}) {
    RawConnection c(server.port());
    const auto start = Clock::now();
    ASSERT_TRUE(c.send(head));
    const auto r = c.read(10s);
    EXPECT_EQ(r.status, 411) << head << r.head;
    EXPECT_FALSE(error_of(r.body).is_null());
    EXPECT_LT(seconds_since(start), 2.0);
  }
}

TEST(ServeBodies, ABodyThatStopsArrivingIs408) {
  Limits limits;
  limits.read_seconds = 1;
  TestServer server(limits);
  RawConnection c(server.port());
  const auto start = Clock::now();
  ASSERT_TRUE(c.send("POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: 100\r\n\r\n{\"model\""));
  const auto r = c.read(10s);
  EXPECT_EQ(r.status, 408) << r.head << r.body;
  EXPECT_FALSE(error_of(r.body).is_null()) << r.body;
  EXPECT_LT(seconds_since(start), 5.0);
  EXPECT_TRUE(c.closed_within(2s));
  // A request line that never ends is cut off the same way.
  RawConnection line(server.port());
  ASSERT_TRUE(line.send("GET /api/mod"));
  EXPECT_EQ(line.read(10s).status, 408);
}

// With "Expect: 100-continue" the server sends 100 Continue before the body; a body that then stops
// arriving still gets its 408 (the interim answer once started the answer's write clock, so the
// 408, due when the read clock ran out, found its write time spent and the connection closed
// silently).
TEST(ServeBodies, ABodyThatStopsArrivingAfter100ContinueIs408) {
  Limits limits;
  limits.read_seconds = 1;
  limits.write_seconds = 1;
  TestServer server(limits);
  RawConnection c(server.port());
  const auto start = Clock::now();
  ASSERT_TRUE(c.send("POST /api/eval HTTP/1.1\r\nHost: x\r\nExpect: 100-continue\r\nContent-Length: 100\r\n\r\n"));
  EXPECT_EQ(c.read(10s).status, 100);
  ASSERT_TRUE(c.send("{\"model\""));
  const auto r = c.read(10s);
  EXPECT_EQ(r.status, 408) << r.head << r.body;
  EXPECT_FALSE(error_of(r.body).is_null()) << r.body;
  EXPECT_LT(seconds_since(start), 5.0);
  EXPECT_TRUE(c.closed_within(2s));
  // Control: the whole body after 100 Continue is answered.
  RawConnection whole(server.port());
  const std::string body = R"({"model": "log", "cos": [0.5]})";
  ASSERT_TRUE(whole.send(fmt::format("POST /api/eval HTTP/1.1\r\nHost: x\r\nExpect: 100-continue\r\n"
                                     "Content-Length: {}\r\n\r\n", body.size())));
  EXPECT_EQ(whole.read(10s).status, 100);
  ASSERT_TRUE(whole.send(body));
  EXPECT_EQ(whole.read(10s).status, 200);
}

TEST(ServeKeepAlive, AnIdleConnectionIsClosedAfterItsTimeAndServesUntilThen) {
  Limits limits;
  limits.idle_seconds = 1;
  TestServer server(limits);
  RawConnection c(server.port());
  for (int i = 0; i < 3; ++i) {  // control: keep-alive works within the idle time
    ASSERT_TRUE(c.send("GET /api/models HTTP/1.1\r\nHost: x\r\n\r\n"));
    EXPECT_EQ(c.read(10s).status, 200) << i;
  }
  const auto start = Clock::now();
  EXPECT_TRUE(c.closed_within(10s));
  const double took = seconds_since(start);
  EXPECT_GT(took, 0.5);
  EXPECT_LT(took, 5.0);
}

TEST(ServeStop, StoppingEndsRequestsAndConnectionsInFlightWithinASecond) {
  auto server = std::make_unique<TestServer>();
  const int port = server->port();
  HeavyLoad load(port, 3);
  RawConnection idle(port), drip(port);
  ASSERT_TRUE(idle.send("GET /api/models HTTP/1.1\r\nHost: x\r\n\r\n"));
  EXPECT_EQ(idle.read(10s).status, 200);
  ASSERT_TRUE(drip.send("GET /api/mo"));
  const Answer fit = specula::testing::post_json(port, "/api/fit", {{"model", "log"}, {"generations", 100000}, {"time", 60}});
  ASSERT_EQ(fit.status, 202) << fit.body;
  std::this_thread::sleep_for(700ms);  // everything is under way
  const auto start = Clock::now();
  server.reset();  // stop, wait for the listener and every connection, join the fit job
  const double took = seconds_since(start);
  std::cout << "[ measured ] stopped in " << took << " s with 3 heavy requests, 2 connections and a fit\n";
  EXPECT_LT(took, 1.0);
  for (const Answer& a : load.join())  // a 503 "stopping", or the connection closed under it
    EXPECT_TRUE(a.status == 503 || a.status == 0) << a.status << " " << a.body;
  EXPECT_TRUE(idle.closed_within(1s));
  EXPECT_TRUE(drip.closed_within(1s));
}

}  // namespace
}  // namespace specula::serve
