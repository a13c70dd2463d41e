#pragma once
// `specula serve`: the Api over HTTP (cpp-httplib), on one address, until stop().
#include <memory>
#include <string>

#include "specula/serve/api.h"

namespace specula::serve {

class Server {
 public:
  explicit Server(Limits limits = {});
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  /// Binds `host`:`port` (port 0: a free port) and returns the port bound; InvalidArgument when
  /// the address cannot be bound.
  int bind(const std::string& host, int port);
  /// Serves requests until stop(); call after bind().
  void run();
  /// Stops listening, ends the connections (each within 50 ms), stops requests in flight at
  /// their next interrupt check (503) and cancels the jobs; returns at once. Safe from any
  /// thread, also before run(). run() returns once every connection has ended.
  void stop();
  /// True while run() is accepting connections.
  bool running() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Threads of fit and design jobs left running when their server was destroyed: a search that
/// had checked neither its cancel flag nor its work limit Limits::stop_seconds after the stop.
/// The CLI then exits at once rather than run static destructors under them.
std::size_t abandoned_job_threads() noexcept;

/// True for addresses only this machine can reach: localhost, 127.0.0.0/8, ::1.
bool is_loopback(const std::string& host);

/// "http://HOST:PORT/" (an IPv6 host in brackets).
std::string url_of(const std::string& host, int port);

}  // namespace specula::serve
