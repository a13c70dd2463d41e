// Fuzzes the server's request handling without HTTP (serve::Api::handle,
// include/specula/serve/api.h): the JSON body → Fields (src/serve/fields.cpp) → query path of
// every analysis endpoint (src/serve/endpoints.cpp) and of the fit jobs (src/serve/fit_job.cpp).
// Input: a request body, POSTed to each analysis route in turn. Tight Limits keep one input
// within milliseconds (a few values, pairs, angles; fits of a few rows for a few generations).
// Properties, each a finding when broken:
//   - every answer is 2xx or 4xx (a 500 is an internal error: an exception other than
//     InvalidArgument escaped an endpoint), its body valid JSON, an error's body
//     {"error": "...", "field": ...};
//   - handle() does not throw (it promises never to);
//   - an accepted fit (202) finishes within its time limit and does not fail: a request the API
//     accepts must not fail later in the job.
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "fuzz_support.h"
#include "specula/serve/api.h"

namespace {

using namespace specula;

serve::Limits tight_limits() {
  serve::Limits l;
  l.max_n = 4;
  l.max_strict_n = 1;
  l.max_eval_points = 32;
  l.max_albedo_angles = 2;
  l.max_monte_carlo_samples = 20'000;
  l.max_check_cases = 2;
  l.max_check_pairs = 64;
  l.max_image_side = 64;
  l.max_fit_rows = 16;
  l.max_fit_seconds = 0.05;
  l.max_fit_generations = 4;
  l.max_fit_size = 5;
  l.max_fit_population = 16;
  l.max_fit_islands = 1;
  l.max_running_fits = 1;
  l.max_kept_fits = 1;
  return l;
}

constexpr std::string_view kRoutes[] = {"/api/eval",  "/api/normalize", "/api/albedo", "/api/check",
                                        "/api/error", "/api/glsl",      "/api/fit"};

nlohmann::json checked_body(const serve::Response& r, std::string_view what) {
  const auto body = nlohmann::json::parse(r.body, nullptr, false);
  fuzz::require(!body.is_discarded(), std::string(what) + ": the answer is not JSON: " + r.body.substr(0, 200));
  return body;
}

serve::Response handled(serve::Api& api, const serve::Request& request) {
  serve::Response r;
  try {
    r = api.handle(request);
  } catch (const std::exception& e) {
    fuzz::finding(request.method + " " + request.path + ": handle() threw " + fuzz::type_name(typeid(e)) + ": " + e.what());
  } catch (...) {
    fuzz::finding(request.method + " " + request.path + ": handle() threw a non-std exception");
  }
  const std::string what = request.method + " " + request.path;
  fuzz::require(r.status != 500, what + ": 500 " + r.body);
  fuzz::require((r.status >= 200 && r.status < 300) || (r.status >= 400 && r.status < 500),
                what + ": status " + std::to_string(r.status) + " " + r.body);
  const auto body = checked_body(r, what);
  if (r.status >= 400)
    fuzz::require(body.is_object() && body.contains("error") && body["error"].is_string() && body.contains("field"),
                  what + ": an error answer without {\"error\", \"field\"}: " + r.body);
  return r;
}

// Polls an accepted fit job until it stops; it must end done (or stopped by its limits).
void follow_fit(serve::Api& api, const serve::Response& started) {
  const auto answer = checked_body(started, "POST /api/fit");
  fuzz::require(answer.contains("url") && answer["url"].is_string(), "POST /api/fit: 202 without a url");
  const serve::Request poll{"GET", answer["url"].get<std::string>(), ""};
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  for (;;) {
    const auto r = handled(api, poll);
    fuzz::require(r.status == 200, "GET " + poll.path + ": status " + std::to_string(r.status) + " " + r.body);
    const auto status = checked_body(r, "GET " + poll.path);
    const std::string state = status.value("state", "");
    if (state == "done") return;
    fuzz::require(state == "running", "an accepted fit job ended '" + state + "': " + r.body);
    fuzz::require(std::chrono::steady_clock::now() < give_up,
                  "a fit job ran 5 s, past its time limit of " + std::to_string(api.limits().max_fit_seconds) + " s");
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // SPECULA_FUZZ_SERVE_NO_FIT=1 leaves /api/fit out, to spend a campaign on the other routes
  // (each fit input costs milliseconds of search).
  static const bool no_fit = std::getenv("SPECULA_FUZZ_SERVE_NO_FIT") != nullptr;
  const std::string body(fuzz::text_of(data, size));
  serve::Api api(tight_limits());  // per input: no fit job outlives it (its destructor waits)
  for (const std::string_view route : kRoutes) {
    if (no_fit && route == "/api/fit") continue;
    const auto r = handled(api, {"POST", std::string(route), body});
    if (route == "/api/fit" && r.status == 202) follow_fit(api, r);
  }
  return 0;
}
