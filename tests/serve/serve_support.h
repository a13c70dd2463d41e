#pragma once
// A `specula serve` server in the test process on a free loopback port, and HTTP helpers:
// JSON requests through httplib's client, and raw request lines that no client rewrites.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>
#include <optional>
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

/// One connection of a client that writes exactly what it is given, as slowly as it likes, and
/// reads answers with a bound on every wait (a server that holds the connection fails a test
/// rather than hanging it).
class RawConnection {
 public:
  explicit RawConnection(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  }
  ~RawConnection() { ::close(fd_); }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  bool connected() const { return connected_; }
  bool send(const std::string& text) { return ::send(fd_, text.data(), text.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(text.size()); }

  struct Response {
    int status = 0;  ///< 0: none came (closed, or nothing within the wait)
    std::string head;  ///< status line and headers
    std::string body;
    std::size_t bytes = 0;  ///< all of it, as sent
    std::string header(const std::string& name) const {
      std::string lower_head, key = "\r\n" + name + ":";
      for (const char c : head) lower_head += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      for (char& c : key) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      const auto at = lower_head.find(key);
      if (at == std::string::npos) return {};
      auto begin = at + key.size();
      while (begin < head.size() && head[begin] == ' ') ++begin;
      return head.substr(begin, head.find("\r\n", begin) - begin);
    }
  };

  /// The next answer (its Content-Length bytes of body, or all until the server closes; none for
  /// the answer to a HEAD or an interim 1xx answer), waiting at most `wait` for each piece.
  Response read(std::chrono::milliseconds wait = std::chrono::seconds(60), bool head_request = false) {
    Response r;
    std::size_t head_end;
    while ((head_end = pending_.find("\r\n\r\n")) == std::string::npos)
      if (!fill(wait)) return r;
    r.head = pending_.substr(0, head_end + 2);
    pending_.erase(0, head_end + 4);
    r.status = r.head.size() > 12 ? std::atoi(r.head.c_str() + 9) : 0;
    const std::string length = r.header("Content-Length");
    if (head_request || r.status / 100 == 1) {  // 1xx (100 Continue) has no body
    } else if (!length.empty()) {
      const std::size_t n = std::stoul(length);
      while (pending_.size() < n)
        if (!fill(wait)) break;
      r.body = pending_.substr(0, n);
      pending_.erase(0, r.body.size());
    } else {
      while (fill(wait)) {}
      r.body.swap(pending_);
    }
    r.bytes = head_end + 4 + r.body.size();
    return r;
  }

  /// Whether the server has closed the connection (EOF) within `wait`.
  bool closed_within(std::chrono::milliseconds wait) {
    const auto until = std::chrono::steady_clock::now() + wait;
    while (std::chrono::steady_clock::now() < until) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      char c;
      const ssize_t got = ::recv(fd_, &c, 1, 0);
      if (got <= 0) return true;
      pending_ += c;
    }
    return false;
  }

 private:
  bool fill(std::chrono::milliseconds wait) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(wait.count())) <= 0) return false;
    char buffer[65536];
    const ssize_t got = ::recv(fd_, buffer, sizeof buffer, 0);
    if (got <= 0) return false;
    pending_.append(buffer, static_cast<std::size_t>(got));
    return true;
  }

  int fd_;
  bool connected_ = false;
  std::string pending_;
};

/// c op c op … c, at most `characters` long (4096 is the most a formula may have).
inline std::string chain(const std::string& op, std::size_t characters = 4095) {
  std::string text = "c";
  while (text.size() + op.size() + 1 <= characters) text += op + "c";
  return text;
}

inline nlohmann::json exponent() { return {{"default", 1}, {"min", 0}, {"min_exclusive", true}, {"max", 1e9}}; }

/// An oscillating lobe with k by quadrature: some 0.1 s per k (release), 11–16 s per request on
/// every route before requests had deadlines.
inline nlohmann::json oscillating() {
  return {{"kind", "lobe"}, {"form", "rv"}, {"lobe", "max(0, sin(1000*n*acos(c)))"}, {"normalization", "quadrature"},
          {"params", {{"n", exponent()}}}};
}

/// A definition object beyond any deadline by construction, however fast the numerics become: an
/// oscillating lobe with two lets of 4091 characters (8000 operations per evaluation), whose
/// albedo at one angle is a single integral of some 10 s in a release build.
inline nlohmann::json costly_oscillating() {
  const std::string sum = chain("+", 4091);
  return {{"kind", "lobe"}, {"form", "rv"}, {"let", {"a = " + sum, "b = " + sum}},
          {"lobe", "max(0, sin(1000*acos(c))) + 0*(a + b)"}, {"normalization", "none"}};
}

/// Polls the job at `path` ("/api/fit/3") every `ms` until `done(status)` holds or the job is no
/// longer running; bounded (~5 minutes at 100 ms, room for the sanitizers).
inline nlohmann::json poll_job(int port, const std::string& path, const std::function<bool(const nlohmann::json&)>& done,
                               int ms = 100) {
  nlohmann::json status;
  for (int i = 0; i < 300'000 / ms; ++i) {
    const Answer a = get(port, path);
    if (a.status != 200) return nlohmann::json{{"http_status", a.status}, {"body", a.body}};
    status = a.json();
    if (done(status) || status["state"] != "running") return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  }
  return status;
}

/// Seconds since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// One server for a test suite: every test of the suite talks to it over HTTP.
class ServerSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = new TestServer(); }
  static void TearDownTestSuite() {
    delete server_;
    server_ = nullptr;
  }
  static int port() { return server_->port(); }

  /// POSTs `body` to `path` and returns the JSON of a 200 answer.
  static nlohmann::json ok(const std::string& path, const nlohmann::json& body) {
    const Answer a = post_json(port(), path, body);
    EXPECT_EQ(a.status, 200) << path << " " << body.dump() << " → " << a.body;
    EXPECT_EQ(a.content_type, "application/json");
    return a.status == 200 ? a.json() : nlohmann::json();
  }

 private:
  static inline TestServer* server_ = nullptr;
};

}  // namespace specula::testing
