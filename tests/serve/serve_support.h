#pragma once
// A `specula serve` server in the test process on a free loopback port, and HTTP helpers:
// JSON requests through httplib's client, and raw request lines that no client rewrites.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <httplib.h>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "specula/serve/server.h"

namespace specula::testing {

/// The server on 127.0.0.1 and a free port, running in a thread until destroyed.
class TestServer {
 public:
  explicit TestServer(serve::Limits limits = {}) : server_(limits), port_(server_.bind("127.0.0.1", 0)) {
    thread_ = std::thread([this] { server_.run(); });
    while (!server_.running()) std::this_thread::yield();
  }
  ~TestServer() {
    server_.stop();
    thread_.join();
  }
  int port() const { return port_; }
  serve::Server& server() { return server_; }

 private:
  serve::Server server_;
  int port_;
  std::thread thread_;
};

struct Answer {
  int status = 0;  ///< 0: no answer (connection failed)
  std::string content_type;
  std::string body;
  std::string allow;  ///< the Allow header

  nlohmann::json json() const { return nlohmann::json::parse(body); }
};

inline Answer answer_of(const httplib::Result& r) {
  if (!r) return {};
  return {r->status, r->get_header_value("Content-Type"), r->body, r->get_header_value("Allow")};
}

/// A client with room for slow answers (the sanitizers slow the server several times).
inline httplib::Client client_for(int port) {
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(120);
  return client;
}

inline Answer get(int port, const std::string& path) {
  auto client = client_for(port);
  return answer_of(client.Get(path));
}

inline Answer post(int port, const std::string& path, const std::string& body) {
  auto client = client_for(port);
  return answer_of(client.Post(path, body, "application/json"));
}

inline Answer post_json(int port, const std::string& path, const nlohmann::json& body) {
  return post(port, path, body.dump());
}

inline Answer del(int port, const std::string& path) {
  auto client = client_for(port);
  return answer_of(client.Delete(path));
}

/// Sends `request_line` ("GET /../x HTTP/1.1") exactly as written; returns the status code and
/// the whole response text.
inline std::pair<int, std::string> raw_request(int port, const std::string& request_line) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    return {0, ""};
  }
  const std::string request = request_line + "\r\nHost: 127.0.0.1\r\nContent-Length: 0\r\nConnection: close\r\n\r\n";
  (void)!::write(fd, request.data(), request.size());
  std::string response;
  char buffer[4096];
  for (ssize_t got; (got = ::read(fd, buffer, sizeof buffer)) > 0;) response.append(buffer, static_cast<std::size_t>(got));
  ::close(fd);
  const auto space = response.find(' ');
  return {space == std::string::npos ? 0 : std::atoi(response.c_str() + space + 1), response};
}

}  // namespace specula::testing
