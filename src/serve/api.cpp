#include "specula/serve/api.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <fmt/format.h>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>

#include "assets.h"
#include "endpoints.h"
#include "fit_jobs.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::serve {

namespace {

using Handler = std::function<Response(const Request&)>;
using Clock = std::chrono::steady_clock;

Clock::duration seconds(double s) { return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s)); }

Response json(std::string body, int status = 200) { return {status, "application/json", std::move(body), {}}; }

struct Route {
  std::string_view method;
  std::string_view path;
  Handler handler;
  bool computed = false;  ///< runs library work: takes a place of Limits::max_busy_requests
};

/// The analysis endpoints, each a POST of a JSON object.
std::vector<Route> analysis_routes(const Limits& limits) {
  using Endpoint = std::string (*)(std::string_view, const Limits&);
  const std::pair<std::string_view, Endpoint> endpoints[] = {
      {"/api/eval", eval_endpoint},   {"/api/normalize", normalize_endpoint}, {"/api/albedo", albedo_endpoint},
      {"/api/check", check_endpoint}, {"/api/error", error_endpoint},         {"/api/glsl", glsl_endpoint}};
  std::vector<Route> routes{{"GET", "/api/models", [](const Request&) { return json(models_endpoint()); }}};
  for (const auto& [path, endpoint] : endpoints)
    routes.push_back({"POST", path, [endpoint, &limits](const Request& r) { return json(endpoint(r.body, limits)); }, true});
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

/// A counting semaphore for the computed requests: at most `capacity` run at once.
class Admission {
 public:
  explicit Admission(std::size_t capacity) : capacity_(capacity) {}

  /// Takes a place, waiting until `until` at the latest; false when none came in time or the
  /// server stops.
  bool enter(Clock::time_point until, const std::atomic<bool>& stopping) {
    std::unique_lock lock(mutex_);
    while (busy_ >= capacity_) {
      if (stopping || Clock::now() >= until) return false;
      freed_.wait_until(lock, std::min(until, Clock::now() + std::chrono::milliseconds(50)));
    }
    ++busy_;
    return true;
  }
  void leave() {
    {
      const std::lock_guard lock(mutex_);
      --busy_;
    }
    freed_.notify_one();
  }
  std::size_t capacity() const { return capacity_; }

 private:
  const std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable freed_;
  std::size_t busy_ = 0;
};

}  // namespace

struct Api::State {
  explicit State(const Limits& l)
      : limits(l), fits(limits), routes(analysis_routes(limits)), admission(limits.max_busy_requests) {}
  const Limits limits;
  FitJobs fits;
  const std::vector<Route> routes;  ///< fixed routes; /api/fit and /api/fit/{id} are matched in route()
  Admission admission;
  std::atomic<bool> stopping{false};  ///< the cancel flag of every request's work limit
};

namespace {

Response busy(const Api::State& state) {
  Response response = error_response(
      503, fmt::format("the server is busy: {} requests are being computed, the most at once; retry in a moment",
                       state.admission.capacity()));
  response.headers.emplace_back("Retry-After", "1");
  return response;
}

/// Runs `work` in a place of the admission limit, or answers 503 busy.
template <class Work>
Response admitted(Api::State& state, Work&& work) {
  const Clock::time_point until = std::min(Clock::now() + seconds(state.limits.busy_wait_seconds), current_limit().deadline);
  if (!state.admission.enter(until, state.stopping)) {
    check_interrupt();  // stopping: say so rather than busy
    return busy(state);
  }
  struct Leave {
    Admission& admission;
    ~Leave() { admission.leave(); }
  } leave{state.admission};
  return work();
}

Response route(Api::State& state, const Request& request) {
  const auto& routes = state.routes;
  // HEAD is GET without the body (the transport drops it; the headers are GET's).
  Request get_for_head;
  if (request.method == "HEAD") get_for_head = {"GET", request.path, request.body};
  const Request& r = request.method == "HEAD" ? get_for_head : request;
  if (r.body.size() > state.limits.max_body_bytes)
    return error_response(413, fmt::format("the body has {} bytes; at most {}", r.body.size(), state.limits.max_body_bytes), "body");
  if (r.path == "/api/fit") {
    if (r.method != "POST") return method_not_allowed(request, "POST");
    return admitted(state, [&] { return start_fit(state.fits, r); });
  }
  if (r.path.starts_with("/api/fit/")) return fit_job(state.fits, r);
  const auto same_path = [&](const Route& route) { return route.path == r.path; };
  const auto match = std::find_if(routes.begin(), routes.end(), same_path);
  if (match == routes.end()) return r.path.starts_with("/api/") || r.path == "/api" ? not_found(r) : asset(r);
  if (r.method != match->method) return method_not_allowed(request, std::string(match->method));
  if (match->computed) return admitted(state, [&] { return match->handler(r); });
  return match->handler(r);
}

}  // namespace

Response error_response(int status, const std::string& message, const std::string& field) {
  const nlohmann::ordered_json body{{"error", message}, {"field", field.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(field)}};
  // The message may echo the request (a path, a name): bytes that are not UTF-8 become U+FFFD
  // rather than an exception, so that an answer about bad input is never a 500.
  return json(body.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n", status);
}

Api::Api(Limits limits) : state_(std::make_unique<State>(limits)) {}

Api::~Api() = default;

const Limits& Api::limits() const noexcept { return state_->limits; }

void Api::cancel_fits() { state_->fits.cancel_all(); }

void Api::stop() {
  state_->stopping = true;
  state_->fits.cancel_all();
}

Response Api::handle(const Request& request) {
  // Every request's work stops at its deadline or when the server stops: the library's loops
  // check this limit (check_interrupt) and throw Interrupted, answered 503 below.
  const ScopedLimit limit(WorkLimit{Clock::now() + seconds(state_->limits.request_seconds), &state_->stopping});
  try {
    return route(*state_, request);
  } catch (const InvalidField& e) {
    return error_response(400, e.what(), e.field());
  } catch (const InvalidArgument& e) {
    return error_response(400, e.what(), "body");
  } catch (const TooManyFits& e) {
    if (e.winding_down > 0 && e.running < state_->limits.max_running_fits)
      return error_response(429, fmt::format("{} cancelled fit jobs are still ending: retry in a moment", e.winding_down));
    return error_response(429, fmt::format("{} fit jobs are running, the most at once: wait for one or cancel it", e.running));
  } catch (const Interrupted& e) {
    if (e.reason() == Interrupted::Reason::deadline)
      return error_response(503, fmt::format("the request needs more than {} s of work, the most one may take: ask for less "
                                             "(fewer values, a coarser step, fewer pairs or samples)",
                                             state_->limits.request_seconds));
    return error_response(503, "the server is stopping");
  } catch (const std::exception& e) {
    return error_response(500, fmt::format("internal error: {}", e.what()));
  }
}

}  // namespace specula::serve
