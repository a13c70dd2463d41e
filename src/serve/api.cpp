#include "specula/serve/api.h"

#include <algorithm>
#include <charconv>
#include <fmt/format.h>
#include <functional>
#include <nlohmann/json.hpp>

#include "assets.h"
#include "endpoints.h"
#include "fit_jobs.h"
#include "specula/error.h"
#include "specula/interrupt/interrupt.h"

namespace specula::serve {

namespace {

using Handler = std::function<Response(const Request&)>;

Response json(std::string body, int status = 200) { return {status, "application/json", std::move(body), {}}; }

struct Route {
  std::string_view method;
  std::string_view path;
  Handler handler;
};

/// The analysis endpoints, each a POST of a JSON object.
std::vector<Route> analysis_routes(const Limits& limits) {
  using Endpoint = std::string (*)(std::string_view, const Limits&);
  const std::pair<std::string_view, Endpoint> endpoints[] = {
      {"/api/eval", eval_endpoint},   {"/api/normalize", normalize_endpoint}, {"/api/albedo", albedo_endpoint},
      {"/api/check", check_endpoint}, {"/api/error", error_endpoint},         {"/api/glsl", glsl_endpoint}};
  std::vector<Route> routes{{"GET", "/api/models", [](const Request&) { return json(models_endpoint()); }}};
  for (const auto& [path, endpoint] : endpoints)
    routes.push_back({"POST", path, [endpoint, &limits](const Request& r) { return json(endpoint(r.body, limits)); }});
  return routes;
}

/// "/api/fit/17" → 17; nullopt for anything else under /api/fit/.
std::optional<std::int64_t> job_id(std::string_view path) {
  constexpr std::string_view prefix = "/api/fit/";
  if (!path.starts_with(prefix)) return std::nullopt;
  const std::string_view digits = path.substr(prefix.size());
  std::int64_t id = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), id);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || id < 1) return std::nullopt;
  return id;
}

Response method_not_allowed(const Request& r, std::string allowed) {
  Response response = error_response(405, fmt::format("{} is not allowed on {}; use {}", r.method, r.path, allowed));
  response.headers.emplace_back("Allow", std::move(allowed));
  return response;
}

Response not_found(const Request& r) { return error_response(404, fmt::format("no such resource: {}", r.path)); }

Response fit_job(FitJobs& fits, const Request& r) {
  const auto id = job_id(r.path);
  if (!id) return not_found(r);
  if (r.method != "GET" && r.method != "DELETE") return method_not_allowed(r, "GET, DELETE");
  const auto answer = r.method == "GET" ? fits.status(*id) : fits.cancel(*id);
  if (!answer) return error_response(404, fmt::format("no fit job {} (finished jobs are kept a while; cancelled ones are gone)", *id));
  return json(*answer);
}

Response start_fit(FitJobs& fits, const Request& r) {
  const std::int64_t id = fits.start(r.body);
  Response response = json(nlohmann::ordered_json{{"job", id}, {"url", fmt::format("/api/fit/{}", id)}}.dump() + "\n", 202);
  response.headers.emplace_back("Location", fmt::format("/api/fit/{}", id));
  return response;
}

Response asset(const Request& r) {
  const Asset* file = find_asset(r.path);
  if (!file) return not_found(r);
  if (r.method != "GET" && r.method != "HEAD") return method_not_allowed(r, "GET");
  return {200, std::string(file->content_type), std::string(file->bytes), {{"Cache-Control", "no-cache"}}};
}

}  // namespace

struct Api::State {
  explicit State(const Limits& l) : limits(l), fits(limits), routes(analysis_routes(limits)) {}
  const Limits limits;
  FitJobs fits;
  const std::vector<Route> routes;  ///< fixed routes; /api/fit and /api/fit/{id} are matched in route()
};

namespace {

Response route(Api::State& state, const Request& r) {
  const auto& routes = state.routes;
  if (r.body.size() > state.limits.max_body_bytes)
    return error_response(413, fmt::format("the body has {} bytes; at most {}", r.body.size(), state.limits.max_body_bytes), "body");
  if (r.path == "/api/fit") {
    if (r.method != "POST") return method_not_allowed(r, "POST");
    return start_fit(state.fits, r);
  }
  if (r.path.starts_with("/api/fit/")) return fit_job(state.fits, r);
  const auto same_path = [&](const Route& route) { return route.path == r.path; };
  const auto match = std::find_if(routes.begin(), routes.end(), same_path);
  if (match == routes.end()) return r.path.starts_with("/api/") || r.path == "/api" ? not_found(r) : asset(r);
  if (r.method != match->method) return method_not_allowed(r, std::string(match->method));
  return match->handler(r);
}

}  // namespace

Response error_response(int status, const std::string& message, const std::string& field) {
  const nlohmann::ordered_json body{{"error", message}, {"field", field.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(field)}};
  return json(body.dump() + "\n", status);
}

Api::Api(Limits limits) : state_(std::make_unique<State>(limits)) {}

Api::~Api() = default;

const Limits& Api::limits() const noexcept { return state_->limits; }

void Api::cancel_fits() { state_->fits.cancel_all(); }

Response Api::handle(const Request& request) {
  try {
    return route(*state_, request);
  } catch (const InvalidField& e) {
    return error_response(400, e.what(), e.field());
  } catch (const InvalidArgument& e) {
    return error_response(400, e.what(), "body");
  } catch (const TooManyFits& e) {
    return error_response(429, fmt::format("{} fit jobs are running, the most at once: wait for one or cancel it", e.running));
  } catch (const Interrupted& e) {
    return error_response(503, e.signal() ? "the server is stopping" : fmt::format("the request was stopped: {}", e.what()));
  } catch (const std::exception& e) {
    return error_response(500, fmt::format("internal error: {}", e.what()));
  }
}

}  // namespace specula::serve
