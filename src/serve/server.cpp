#include "specula/serve/server.h"

#include <arpa/inet.h>
#include <sys/socket.h>
#include <fmt/format.h>
#include <httplib.h>

#include "specula/error.h"

namespace specula::serve {
namespace {

Request request_of(const httplib::Request& r) { return {r.method, r.path, r.body}; }

void reply(const Response& from, httplib::Response& to) {
  to.status = from.status;
  for (const auto& [name, value] : from.headers) to.set_header(name, value);
  to.set_content(from.body, from.content_type.c_str());
}

}  // namespace

struct Server::Impl {
  explicit Impl(Limits limits) : api(limits) { configure(); }

  void configure() {
    http.set_payload_max_length(api.limits().max_body_bytes);
    // httplib's default sets SO_REUSEPORT, with which a second server binds the same port and
    // silently shares its connections; SO_REUSEADDR alone only allows a restart over TIME_WAIT.
    http.set_socket_options([](socket_t socket) {
      const int yes = 1;
      ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    });
    http.set_tcp_nodelay(true);  // else Nagle + delayed ACK add ~40 ms to each keep-alive answer
    http.set_read_timeout(10);
    http.set_write_timeout(10);
    const auto handle = [this](const httplib::Request& req, httplib::Response& res) { reply(api.handle(request_of(req)), res); };
    for (auto add : {&httplib::Server::Get, &httplib::Server::Post, &httplib::Server::Put,
                     &httplib::Server::Patch, &httplib::Server::Delete, &httplib::Server::Options})
      (http.*add)(".*", handle);
    // Errors httplib answers itself (413 body too large, 400 unparsable request, …) get JSON too.
    http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
      if (!res.body.empty()) return;
      const int status = res.status;
      reply(status == 413 ? error_response(413, "the body is too large", "body")
                          : error_response(status, fmt::format("HTTP error {}", status)),
            res);
    });
    http.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
      reply(error_response(500, "internal error"), res);
    });
  }

  Api api;
  httplib::Server http;
};

Server::Server(Limits limits) : impl_(std::make_unique<Impl>(limits)) {}

Server::~Server() { stop(); }

int Server::bind(const std::string& host, int port) {
  if (port < 0 || port > 65535) throw InvalidArgument(fmt::format("port {} is outside [0, 65535]", port));
  const int bound = port == 0 ? impl_->http.bind_to_any_port(host) : (impl_->http.bind_to_port(host, port) ? port : -1);
  if (bound <= 0) throw InvalidArgument(fmt::format("cannot listen on {}:{} (in use, or not an address of this machine)", host, port));
  return bound;
}

void Server::run() { impl_->http.listen_after_bind(); }

void Server::stop() {
  impl_->api.cancel_fits();
  impl_->http.stop();
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
