#include "specula/serve/server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <fmt/format.h>
#include <httplib.h>
#include <list>
#include <mutex>
#include <optional>
#include <thread>

#include "specula/exceptions.h"

namespace specula::serve {
namespace {

using Clock = std::chrono::steady_clock;

Clock::duration seconds(double s) { return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s)); }

/// How often a wait looks at the stop flag: the bound on how long stop() waits for a connection.
constexpr auto kStopPoll = std::chrono::milliseconds(50);
/// How long a closing connection reads on, waiting for the client to close its side.
constexpr auto kLinger = std::chrono::milliseconds(250);

/// One connection's socket as httplib's Stream, with deadlines httplib's own stream lacks: each
/// request must arrive whole (line, headers, body) within Limits::read_seconds of its start and
/// its answer leave within Limits::write_seconds, however slowly the client drips its bytes; and
/// every wait ends within kStopPoll of the server stopping.
class Connection final : public httplib::Stream {
 public:
  Connection(socket_t fd, const Limits& limits, const std::atomic<bool>& stopping)
      : fd_(fd), limits_(limits), stopping_(stopping) {}

  /// Waits (Limits::idle_seconds at most) for the first byte of the next request.
  bool wait_for_request() {
    if (buffered_ < filled_) return true;
    return wait(POLLIN, Clock::now() + seconds(limits_.idle_seconds)) == Wait::ready;
  }

  /// Starts the clocks of one request.
  void begin_request() {
    read_deadline_ = Clock::now() + seconds(limits_.read_seconds);
    write_deadline_.reset();
    timed_out_ = false;
    written_ = 0;
    answer.reset();
  }

  bool timed_out() const { return timed_out_; }        ///< the request did not arrive in time
  std::size_t written() const { return written_; }     ///< bytes of the current answer sent
  bool close_after = false;  ///< close once this answer is sent (the rest of the request is unread)
  std::optional<Response> answer;  ///< the current request's answer as the Api gave it

  bool is_readable() const override {
    return buffered_ < filled_ || wait(POLLIN, read_deadline_) == Wait::ready;
  }
  bool is_writable() const override { return wait(POLLOUT, write_deadline()) == Wait::ready; }

  ssize_t read(char* ptr, size_t size) override {
    // The request is still arriving, so at most an interim answer (100 Continue) has gone out:
    // the answer's own write clock and byte count start with its first write after this.
    write_deadline_.reset();
    written_ = 0;
    while (buffered_ == filled_) {
      if (wait(POLLIN, read_deadline_) != Wait::ready) return -1;
      const ssize_t got = ::recv(fd_, buffer_, sizeof buffer_, MSG_DONTWAIT);
      if (got < 0 && (errno == EAGAIN || errno == EINTR)) continue;
      if (got <= 0) return got;  // 0: the client closed the connection
      buffered_ = 0;
      filled_ = static_cast<std::size_t>(got);
    }
    const std::size_t n = std::min(size, filled_ - buffered_);
    std::memcpy(ptr, buffer_ + buffered_, n);
    buffered_ += n;
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, size_t size) override {
    for (;;) {
      if (wait(POLLOUT, write_deadline()) != Wait::ready) return -1;
      const ssize_t sent = ::send(fd_, ptr, size, MSG_DONTWAIT | MSG_NOSIGNAL);
      if (sent < 0 && (errno == EAGAIN || errno == EINTR)) continue;
      if (sent > 0) written_ += static_cast<std::size_t>(sent);
      return sent;
    }
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override { address(::getpeername, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address(::getsockname, ip, port); }
  socket_t socket() const override { return fd_; }

 private:
  enum class Wait { ready, timeout, stopped, failed };

  /// Polls for `events` until `deadline`, in slices that look at the stop flag. Once the server
  /// stops, reads end at once and writes go out only if the socket takes them without waiting
  /// (the 503 "stopping" of a request in flight, not a slow reader's answer).
  Wait wait(short events, Clock::time_point deadline) const {
    for (;;) {
      if (stopping_) {
        pollfd p{fd_, events, 0};
        return events == POLLOUT && ::poll(&p, 1, 0) > 0 ? Wait::ready : Wait::stopped;
      }
      const auto left = deadline - Clock::now();
      if (left <= Clock::duration::zero()) {
        if (events == POLLIN) timed_out_ = true;
        return Wait::timeout;
      }
      pollfd p{fd_, events, 0};
      const auto slice = std::min<Clock::duration>(left, kStopPoll);
      const int ready = ::poll(&p, 1, static_cast<int>(std::chrono::ceil<std::chrono::milliseconds>(slice).count()));
      if (ready > 0) return Wait::ready;  // also on hang-up or error: recv/send then says which
      if (ready < 0 && errno != EINTR) return Wait::failed;
    }
  }

  Clock::time_point write_deadline() const {
    if (!write_deadline_) write_deadline_ = Clock::now() + seconds(limits_.write_seconds);
    return *write_deadline_;
  }

  template <class Name>
  void address(Name name, std::string& ip, int& port) const {
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    if (name(fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) return;
    char text[INET6_ADDRSTRLEN] = "";
    if (address.ss_family == AF_INET) {
      const auto& a = reinterpret_cast<const sockaddr_in&>(address);
      ::inet_ntop(AF_INET, &a.sin_addr, text, sizeof text);
      port = ntohs(a.sin_port);
    } else if (address.ss_family == AF_INET6) {
      const auto& a = reinterpret_cast<const sockaddr_in6&>(address);
      ::inet_ntop(AF_INET6, &a.sin6_addr, text, sizeof text);
      port = ntohs(a.sin6_port);
    }
    ip = text;
  }

  socket_t fd_;
  const Limits& limits_;
  const std::atomic<bool>& stopping_;
  Clock::time_point read_deadline_ = Clock::time_point::max();
  mutable std::optional<Clock::time_point> write_deadline_;
  mutable bool timed_out_ = false;
  std::size_t written_ = 0;
  char buffer_[4096];
  std::size_t buffered_ = 0, filled_ = 0;  ///< buffer_[buffered_, filled_) is read, not yet taken
};

/// The connection this thread serves, for httplib's handlers (which see only the request).
thread_local Connection* current_connection = nullptr;

/// httplib's task queue: a thread per connection, started on demand up to `max_threads` (more
/// connections wait for one), ended after a while idle. httplib's own pool has a fixed 8 threads
/// (CPPHTTPLIB_THREAD_POOL_COUNT), so that 8 slow clients held every other one off.
class ConnectionThreads final : public httplib::TaskQueue {
 public:
  explicit ConnectionThreads(std::size_t max_threads) : max_threads_(std::max<std::size_t>(1, max_threads)) {}
  ~ConnectionThreads() override { shutdown(); }

  void enqueue(std::function<void()> fn) override {
    const std::lock_guard lock(mutex_);
    reap();
    jobs_.push_back(std::move(fn));
    if (jobs_.size() > idle_ && threads_.size() < max_threads_) threads_.emplace_back([this] { work(); });
    else ready_.notify_one();
  }

  /// Runs what is queued (each job closes its socket), then joins every thread.
  void shutdown() override {
    {
      const std::lock_guard lock(mutex_);
      shutdown_ = true;
    }
    ready_.notify_all();
    std::list<std::thread> threads;
    {
      const std::lock_guard lock(mutex_);
      threads.swap(threads_);
      ended_.clear();
    }
    for (auto& t : threads)
      if (t.joinable()) t.join();
  }

 private:
  void work() {
    std::unique_lock lock(mutex_);
    for (;;) {
      ++idle_;
      const bool woke = ready_.wait_for(lock, std::chrono::seconds(10), [&] { return !jobs_.empty() || shutdown_; });
      --idle_;
      if (jobs_.empty()) {
        if (shutdown_ || !woke) break;
        continue;
      }
      auto fn = std::move(jobs_.front());
      jobs_.pop_front();
      lock.unlock();
      fn();
      lock.lock();
    }
    if (!shutdown_) ended_.push_back(std::this_thread::get_id());  // joined by the next enqueue
  }

  void reap() {  // caller holds mutex_
    for (const auto id : ended_) {
      const auto it = std::find_if(threads_.begin(), threads_.end(), [&](const std::thread& t) { return t.get_id() == id; });
      if (it != threads_.end()) {
        it->join();  // it has left work(): at most the end of its function is left to run
        threads_.erase(it);
      }
    }
    ended_.clear();
  }

  const std::size_t max_threads_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::list<std::function<void()>> jobs_;
  std::list<std::thread> threads_;
  std::vector<std::thread::id> ended_;
  std::size_t idle_ = 0;
  bool shutdown_ = false;
};

Request request_of(const httplib::Request& r) { return {r.method, r.path, r.body}; }

void reply(const Response& from, httplib::Response& to) {
  if (current_connection) current_connection->answer = from;
  to.status = from.status;
  for (const auto& [name, value] : from.headers) to.set_header(name, value);
  // Range requests are not served (docs/serve.md): every answer is the whole resource.
  to.set_header("Accept-Ranges", "none");
  to.set_content(from.body, from.content_type.c_str());
}

/// The raw text of a 408 written without httplib (a request line that never arrived whole).
std::string timeout_answer(const Response& r) {
  return fmt::format("HTTP/1.1 {} Request Timeout\r\nContent-Type: {}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{}",
                     r.status, r.content_type, r.body.size(), r.body);
}

/// httplib's server with connections served by Connection (see there) instead of its own loop.
class Http final : public httplib::Server {
 public:
  Http(const Limits& limits, const std::atomic<bool>& stopping) : limits_(limits), stopping_(stopping) {}

  /// httplib listens with a backlog of 5 (CPPHTTPLIB_LISTEN_BACKLOG, compiled into the library):
  /// a burst of connections beyond that was dropped or reset before it was accepted. Listening
  /// again on the bound socket only raises the backlog.
  void widen_backlog() const {
    if (svr_sock_ != INVALID_SOCKET) ::listen(svr_sock_, SOMAXCONN);
  }

  /// httplib's stop() without its "only while running" condition: a stop before or while
  /// listen starts also ends it (its accept loop runs while the socket is valid).
  void stop_listening() {
    const socket_t listener = svr_sock_.exchange(INVALID_SOCKET);
    if (listener == INVALID_SOCKET) return;
    ::shutdown(listener, SHUT_RDWR);
    ::close(listener);
  }

 private:
  bool process_and_close_socket(socket_t sock) override {
    Connection connection(sock, limits_, stopping_);
    current_connection = &connection;
    bool ok = true;
    for (std::size_t left = std::max<std::size_t>(1, limits_.max_keep_alive_requests); left > 0; --left) {
      if (stopping_ || svr_sock_ == INVALID_SOCKET || !connection.wait_for_request()) break;
      connection.begin_request();
      bool closed = false;
      // Range headers are parsed by httplib before any handler runs; dropping them here means
      // no answer is ever cut or multiplied into byte ranges (httplib would build a multipart
      // answer with one copy per range: 1500 ranges of "0-" were 1500 copies).
      const auto ignore_ranges = [](httplib::Request& req) { req.ranges.clear(); };
      ok = process_request(connection, left == 1 || stopping_, closed, ignore_ranges);
      if (!ok && connection.timed_out() && connection.written() == 0) {
        // The request line itself did not arrive in time: httplib gives up without an answer.
        const std::string text = timeout_answer(
            error_response(408, fmt::format("the request did not arrive within {} s", limits_.read_seconds)));
        for (std::size_t sent = 0; sent < text.size();) {
          const ssize_t n = connection.write(text.data() + sent, text.size() - sent);
          if (n <= 0) break;
          sent += static_cast<std::size_t>(n);
        }
      }
      if (!ok || closed || connection.close_after || connection.timed_out()) break;
    }
    current_connection = nullptr;
    close_lingering(sock);
    return ok;
  }

  /// Closes after a moment of reading what the client still sends (a refused body, its next
  /// drip): closing with unread bytes resets the connection, and the client may lose the answer.
  void close_lingering(socket_t sock) const {
    ::shutdown(sock, SHUT_WR);
    const auto until = Clock::now() + kLinger;
    char scratch[4096];
    while (!stopping_ && Clock::now() < until) {
      pollfd p{sock, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(kStopPoll.count())) <= 0) continue;
      const ssize_t got = ::recv(sock, scratch, sizeof scratch, MSG_DONTWAIT);
      if (got == 0 || (got < 0 && errno != EAGAIN && errno != EINTR)) break;  // the client closed too
    }
    ::close(sock);
  }

  const Limits& limits_;
  const std::atomic<bool>& stopping_;
};

/// An answer before the body is read (pre-routing): refusals that must not wait for the body.
std::optional<Response> refuse_before_body(const httplib::Request& req, const Limits& limits) {
  if (req.has_header("Transfer-Encoding"))
    return error_response(411, "send the body with Content-Length (no Transfer-Encoding)", "body");
  const bool has_body_method = req.method == "POST" || req.method == "PUT" || req.method == "PATCH";
  if (has_body_method && !req.has_header("Content-Length"))
    return error_response(411, "send the body with Content-Length", "body");
  if (req.has_header("Content-Length")) {
    const std::uint64_t length = req.get_header_value<std::uint64_t>("Content-Length");
    if (const std::size_t most = body_limit(limits, req.path); length > most)
      return error_response(413, fmt::format("the body has {} bytes; at most {}", length, most), "body");
  }
  return std::nullopt;
}

std::string status_message(int status) {
  switch (status) {
    case 400: return "the request is malformed";
    case 404: return "no such resource";
    case 408: return "the request did not arrive in time";
    case 413: return "the body is too large";
    case 414: return "the request line is too long";
    case 416: return "the Range header is malformed (ranges are not served; leave it out)";
    default: return fmt::format("HTTP error {}", status);
  }
}

}  // namespace

struct Server::Impl {
  explicit Impl(Limits limits) : api(limits), http(api.limits(), stopping) { configure(); }

  void configure() {
    const Limits& limits = api.limits();
    http.set_payload_max_length(std::max(limits.max_body_bytes, limits.max_upload_bytes));
    // httplib's default sets SO_REUSEPORT, with which a second server binds the same port and
    // silently shares its connections; SO_REUSEADDR alone only allows a restart over TIME_WAIT.
    http.set_socket_options([](socket_t socket) {
      const int yes = 1;
      ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    });
    http.set_tcp_nodelay(true);  // else Nagle + delayed ACK add ~40 ms to each keep-alive answer
    // Connection enforces the read, write and idle limits itself; these are httplib's socket
    // timeouts (SO_RCVTIMEO, SO_SNDTIMEO), a backstop only.
    http.set_read_timeout(std::chrono::duration<double>(limits.read_seconds));
    http.set_write_timeout(std::chrono::duration<double>(limits.write_seconds));
    http.set_keep_alive_timeout(static_cast<time_t>(std::ceil(limits.idle_seconds)));
    http.set_keep_alive_max_count(std::max<std::size_t>(1, limits.max_keep_alive_requests));
    http.new_task_queue = [max = limits.max_connections] { return new ConnectionThreads(max); };

    http.set_expect_100_continue_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (const auto refusal = refuse_before_body(req, api.limits())) {
        refuse(*refusal, res);
        return refusal->status;
      }
      return 100;
    });
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      const auto refusal = refuse_before_body(req, api.limits());
      if (!refusal) return httplib::Server::HandlerResponse::Unhandled;
      refuse(*refusal, res);
      return httplib::Server::HandlerResponse::Handled;
    });
    const auto handle = [this](const httplib::Request& req, httplib::Response& res) { reply(api.handle(request_of(req)), res); };
    for (auto add : {&httplib::Server::Get, &httplib::Server::Post, &httplib::Server::Put,
                     &httplib::Server::Patch, &httplib::Server::Delete, &httplib::Server::Options})
      (http.*add)(".*", handle);
    // Errors httplib answers itself (400 unparsable request, 414, 416, …) get JSON too; so does
    // a request that stopped arriving (408).
    http.set_error_handler([this](const httplib::Request&, httplib::Response& res) {
      if (current_connection && current_connection->timed_out()) {
        res.headers.clear();
        reply(error_response(408, fmt::format("the request did not arrive within {} s", api.limits().read_seconds)), res);
        return;
      }
      if (!res.body.empty()) return;
      // httplib's own refusals (400 unparsable request line or headers, 414, …) leave the rest of
      // the request unread: the connection closes, or that rest would be read as another request
      // and answered a second time.
      if (current_connection) current_connection->close_after = true;
      reply(error_response(res.status, status_message(res.status)), res);
    });
    http.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
      reply(error_response(500, "internal error"), res);
    });
    // After httplib has prepared the answer, before it is sent.
    http.set_post_routing_handler([](const httplib::Request& req, httplib::Response& res) {
      if (!current_connection) return;
      Connection& c = *current_connection;
      // Ranges are dropped before routing, except where httplib could not parse the Range
      // header: it answers 416 then, keeping the ranges it had parsed, and cuts or multiplies
      // even that error's body by them (1500 ranges: 312 kB). The answer goes out as given.
      if (!req.ranges.empty() && c.answer) {
        for (const char* header : {"Content-Range", "Content-Type", "Content-Length"}) res.headers.erase(header);
        res.status = c.answer->status;
        res.body = c.answer->body;
        res.set_header("Content-Type", c.answer->content_type);
        res.set_header("Content-Length", std::to_string(res.body.size()));
      }
      // A refused request closes its connection (its body, if any, is unread): say so.
      if (c.close_after || c.timed_out()) {
        res.headers.erase("Keep-Alive");
        res.headers.erase("Connection");
        res.set_header("Connection", "close");
      }
    });
  }

  void refuse(const Response& refusal, httplib::Response& res) {
    if (current_connection) current_connection->close_after = true;
    reply(refusal, res);
  }

  std::atomic<bool> stopping{false};  // before http, which refers to it
  Api api;
  Http http;
};

Server::Server(Limits limits) : impl_(std::make_unique<Impl>(limits)) {}

Server::~Server() { stop(); }

int Server::bind(const std::string& host, int port) {
  if (port < 0 || port > 65535) throw InvalidArgument(fmt::format("port {} is outside [0, 65535]", port));
  const int bound = port == 0 ? impl_->http.bind_to_any_port(host) : (impl_->http.bind_to_port(host, port) ? port : -1);
  if (bound <= 0) throw InvalidArgument(fmt::format("cannot listen on {}:{} (in use, or not an address of this machine)", host, port));
  impl_->http.widen_backlog();
  return bound;
}

void Server::run() { impl_->http.listen_after_bind(); }

void Server::stop() {
  impl_->stopping = true;
  impl_->api.stop();
  impl_->http.stop_listening();
}

bool Server::running() const { return impl_->http.is_running(); }

bool is_loopback(const std::string& host) {
  if (host == "localhost" || host == "::1") return true;
  in_addr address{};
  return ::inet_pton(AF_INET, host.c_str(), &address) == 1 && (ntohl(address.s_addr) >> 24) == 127;
}

std::string url_of(const std::string& host, int port) {
  return host.find(':') != std::string::npos ? fmt::format("http://[{}]:{}/", host, port)
                                             : fmt::format("http://{}:{}/", host, port);
}

}  // namespace specula::serve
