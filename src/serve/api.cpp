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
#include "design_job.h"
#include "environment_job.h"
#include "fit_job.h"
#include "jobs.h"
#include "uploads.h"
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

constexpr std::string_view kUploadObj = "/api/upload/obj", kUploadProbe = "/api/upload/probe";

/// The analysis endpoints, each a POST of a JSON object, and the uploads, each a POST of a file.
std::vector<Route> analysis_routes(const Limits& limits, Uploads& uploads) {
  using Endpoint = std::string (*)(std::string_view, const Limits&);
  const std::pair<std::string_view, Endpoint> endpoints[] = {
      {"/api/eval", eval_endpoint},   {"/api/slice", slice_endpoint}, {"/api/normalize", normalize_endpoint},
      {"/api/albedo", albedo_endpoint}, {"/api/check", check_endpoint}, {"/api/error", error_endpoint},
      {"/api/glsl", glsl_endpoint}, {"/api/sampling", sampling_endpoint},
      {"/api/hemisphere", hemisphere_endpoint}, {"/api/compensation", compensation_endpoint}};
  std::vector<Route> routes{{"GET", "/api/models", [](const Request&) { return json(models_endpoint()); }},
                            {"GET", "/api/terms", [](const Request&) { return json(terms_endpoint()); }}};
  for (const auto& [path, endpoint] : endpoints)
    routes.push_back({"POST", path, [endpoint, &limits](const Request& r) { return json(endpoint(r.body, limits)); }, true});
  routes.push_back({"POST", kUploadObj, [&uploads](const Request& r) { return json(uploads.add_obj(r.body), 201); }, true});
  routes.push_back({"POST", kUploadProbe, [&uploads](const Request& r) { return json(uploads.add_probe(r.body), 201); }, true});
  return routes;
}

/// "/api/fit/17" → 17 (prefix "/api/fit/"); nullopt for anything else under the prefix.
std::optional<std::int64_t> job_id(std::string_view path, std::string_view prefix) {
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

/// A kind of job: POST /api/KIND starts one, GET and DELETE /api/KIND/{id} poll and cancel it.
struct JobRoutes {
  std::string path;  ///< "/api/fit"
  std::function<std::shared_ptr<Job>(std::string_view body)> make;
  Jobs jobs;
};

Response job_request(JobRoutes& kind, const Request& r) {
  const auto id = job_id(r.path, kind.path + "/");
  if (!id) return not_found(r);
  if (r.method != "GET" && r.method != "DELETE") return method_not_allowed(r, "GET, DELETE");
  const auto answer = r.method == "GET" ? kind.jobs.status(*id) : kind.jobs.cancel(*id);
  if (!answer)
    return error_response(404, fmt::format("no {} job {} (finished jobs are kept a while; cancelled ones are gone)",
                                           kind.jobs.kind(), *id));
  return json(*answer);
}

Response start_job(JobRoutes& kind, const Request& r) {
  const std::int64_t id = kind.jobs.start(kind.make(r.body));
  const std::string url = fmt::format("{}/{}", kind.path, id);
  Response response = json(nlohmann::ordered_json{{"job", id}, {"url", url}}.dump() + "\n", 202);
  response.headers.emplace_back("Location", url);
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
      : limits(l),
        uploads(limits),
        fits{"/api/fit", [this](std::string_view body) { return fit_job(body, limits); },
             Jobs("fit", limits.max_running_fits, limits.max_kept_fits, limits.stop_seconds)},
        designs{"/api/design", [this](std::string_view body) { return design_job(body, limits); },
                Jobs("design", limits.max_running_designs, limits.max_kept_designs, limits.stop_seconds)},
        environments{"/api/environment", [this](std::string_view body) { return environment_job(body, limits, uploads); },
                     Jobs("render", limits.max_running_environments, limits.max_kept_environments, limits.stop_seconds)},
        routes(analysis_routes(limits, uploads)),
        admission(limits.max_busy_requests) {}
  const Limits limits;
  Uploads uploads;
  JobRoutes fits, designs, environments;
  const std::vector<Route> routes;  ///< fixed routes; the jobs' routes are matched in route()
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
  if (const std::size_t most = body_limit(state.limits, r.path); r.body.size() > most)
    return error_response(413, fmt::format("the body has {} bytes; at most {}", r.body.size(), most), "body");
  for (JobRoutes* kind : {&state.fits, &state.designs, &state.environments}) {
    if (r.path == kind->path) {
      if (r.method != "POST") return method_not_allowed(request, "POST");
      return admitted(state, [&] { return start_job(*kind, r); });
    }
    if (r.path.starts_with(kind->path + "/")) return job_request(*kind, r);
  }
  const auto same_path = [&](const Route& route) { return route.path == r.path; };
  const auto match = std::find_if(routes.begin(), routes.end(), same_path);
  if (match == routes.end()) return r.path.starts_with("/api/") || r.path == "/api" ? not_found(r) : asset(r);
  if (r.method != match->method) return method_not_allowed(request, std::string(match->method));
  if (match->computed) return admitted(state, [&] { return match->handler(r); });
  return match->handler(r);
}

}  // namespace

std::size_t body_limit(const Limits& limits, std::string_view path) {
  return path == kUploadObj || path == kUploadProbe ? limits.max_upload_bytes : limits.max_body_bytes;
}

Response error_response(int status, const std::string& message, const std::string& field) {
  const nlohmann::ordered_json body{{"error", message}, {"field", field.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(field)}};
  // The message may echo the request (a path, a name): bytes that are not UTF-8 become U+FFFD
  // rather than an exception, so that an answer about bad input is never a 500.
  return json(body.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n", status);
}

Api::Api(Limits limits) : state_(std::make_unique<State>(limits)) {}

Api::~Api() = default;

const Limits& Api::limits() const noexcept { return state_->limits; }

void Api::cancel_jobs() {
  state_->fits.jobs.cancel_all();
  state_->designs.jobs.cancel_all();
  state_->environments.jobs.cancel_all();
}

void Api::stop() {
  state_->stopping = true;
  cancel_jobs();
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
  } catch (const TooManyJobs& e) {
    if (e.winding_down > 0 && e.running < e.most)
      return error_response(429, fmt::format("{} cancelled {} jobs are still ending: retry in a moment", e.winding_down, e.kind));
    return error_response(429, fmt::format("{} {} jobs are running, the most at once: wait for one or cancel it", e.running, e.kind));
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
