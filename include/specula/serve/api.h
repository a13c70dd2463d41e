#pragma once
// The JSON API of `specula serve` without the HTTP transport: a request (method, path, body) in,
// a response (status, content type, body) out. Every /api response is JSON; errors are
// {"error": "...", "field": "..."} with 400 (bad field), 404 (unknown route or job), 405 (wrong
// method), 413 (body too large), 429 (too many fit, design or render jobs) or 503 (busy, past the request's time
// cap, or stopping). Any other path is one of the page's assets compiled into the binary, or 404.
// See docs/serve.md.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace specula::serve {

/// The work one request may ask for. Requests beyond a limit get 400 naming the field.
struct Limits {
  std::size_t max_body_bytes = 64 * 1024;
  std::size_t max_n = 2000;               ///< n values (normalize, error, fit from a model)
  std::size_t max_strict_n = 50;          ///< n values with the strict condition (each a search)
  std::size_t max_eval_points = 10'000;   ///< cosines or viewer angles
  std::size_t max_albedo_angles = 200;
  std::uint64_t max_monte_carlo_samples = 10'000'000;  ///< samples × angles
  std::size_t max_sampling_samples = 1'000'000;        ///< /api/sampling: its χ² test's samples
  std::size_t max_check_cases = 50;
  std::int64_t max_walk_paths = 1 << 17;  ///< /api/compensation: the random walk's paths per μ
  std::size_t max_check_pairs = 100'000;
  int max_image_side = 2048;              ///< the scene shader's uniforms (glsl with shader: true)
  std::size_t max_fit_rows = 2000;
  double max_fit_seconds = 60;
  std::int64_t max_fit_generations = 100'000;
  int max_fit_size = 40;
  int max_fit_population = 1000;
  int max_fit_islands = 8;
  std::size_t max_running_fits = 2;
  std::size_t max_kept_fits = 16;         ///< finished jobs kept for polling; older ones are dropped
  double fit_grace_seconds = 5;           ///< past its time, a job's library calls stop (Interrupted)
  double max_design_seconds = 120;        ///< a design job's screening
  int max_design_cost = 5;                ///< a design job's max_cost (the CLI goes to 24)
  std::size_t max_running_designs = 1;
  std::size_t max_kept_designs = 4;
  double design_grace_seconds = 300;      ///< past its screening: finishing, timing, checks (one core)
  // The lit-object view: uploads (POST /api/upload/obj, /api/upload/probe) and its render jobs.
  std::size_t max_upload_bytes = 8 * 1024 * 1024;  ///< the body of an upload (others: max_body_bytes)
  std::size_t max_upload_triangles = 200'000;
  std::uint64_t max_probe_pixels = 2048 * 1024;
  std::size_t max_kept_uploads = 8;       ///< meshes and probes each; older ones are dropped
  int max_environment_side = 256;         ///< the image's width and height
  int max_environment_samples = 1024;     ///< per pixel, the job's target
  std::size_t max_running_environments = 2;
  std::size_t max_kept_environments = 4;
  double environment_seconds = 120;       ///< a render job's work limit

  // Time and concurrency: no request, connection or client holds the server.
  double request_seconds = 5;             ///< the work of one request; then 503 and its thread is free
  std::size_t max_busy_requests = 4;      ///< computed requests (POST /api/...) running at once
  double busy_wait_seconds = 1;           ///< one more waits this long for a place, then 503 "busy"
  double read_seconds = 5;                ///< to receive a request (line, headers, body) once begun; then 408
  double idle_seconds = 5;                ///< an idle keep-alive connection is closed after this
  std::size_t max_keep_alive_requests = 100;  ///< requests on one connection
  double write_seconds = 5;               ///< to send one response
  std::size_t max_connections = 256;      ///< served at once, one thread each; more wait to be accepted
  double stop_seconds = 0.5;              ///< on stop, how long running fit jobs get to end
};

struct Request {
  std::string method;  ///< GET, POST, DELETE, …
  std::string path;    ///< decoded, without the query string
  std::string body;
};

struct Response {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;
};

/// The most bytes a request's body to `path` may have: max_upload_bytes for the uploads, else
/// max_body_bytes.
std::size_t body_limit(const Limits& limits, std::string_view path);

/// {"error": message, "field": field} (field left out when empty) with `status`.
Response error_response(int status, const std::string& message, const std::string& field = {});

class Api {
 public:
  explicit Api(Limits limits = {});
  ~Api();  ///< cancels the fit and design jobs and waits for them
  Api(const Api&) = delete;
  Api& operator=(const Api&) = delete;

  /// Routes one request; thread-safe, never throws (an unexpected exception is a 500).
  Response handle(const Request& request);

  /// Asks every running fit and design job to stop (they finish within one budget check).
  void cancel_jobs();
  /// Stops for good: requests in flight and later ones end with 503 "stopping" at their next
  /// interrupt check, and every job is cancelled. Returns at once.
  void stop();

  const Limits& limits() const noexcept;

  struct State;  ///< the routes and the jobs (src/serve/api.cpp)

 private:
  std::unique_ptr<State> state_;
};

}  // namespace specula::serve
