#pragma once
// A minimal W3C WebDriver client for the page tests: Debian's chromedriver drives Debian's
// chromium, headless, with SwiftShader for WebGL2. Nothing is downloaded.
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <httplib.h>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace specula::testing {

/// A loopback port free at the time of asking (for programs that need one on their command line).
inline int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address);
  socklen_t length = sizeof address;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ::close(fd);
  return ntohs(address.sin_port);
}

class WebDriver {
 public:
  /// Starts chromedriver and one headless chromium session with a fresh profile.
  WebDriver(const std::string& chromedriver, const std::string& chromium, int width, int height)
      : port_(free_port()), profile_(std::filesystem::temp_directory_path() / fmt::format("specula-page-{}-{}", ::getpid(), port_)) {
    std::vector<std::string> args{chromedriver, fmt::format("--port={}", port_), "--allowed-ips=127.0.0.1"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, chromedriver.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
      throw std::runtime_error("cannot run " + chromedriver);
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    client_->set_read_timeout(120);
    for (int i = 0; i < 200 && !client_->Get("/status"); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const nlohmann::json flags{"--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                               "--disable-background-networking", "--disable-component-update", "--disable-sync",
                               "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                               fmt::format("--window-size={},{}", width, height), "--user-data-dir=" + profile_.string()};
    const nlohmann::json capabilities{{"capabilities", {{"alwaysMatch", {{"browserName", "chrome"},
        {"goog:chromeOptions", {{"binary", chromium}, {"args", flags}}}}}}}};
    session_ = command("POST", "/session", capabilities)["sessionId"].get<std::string>();
  }

  ~WebDriver() {
    if (!session_.empty()) client_->Delete("/session/" + session_);
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
    std::error_code ignored;
    std::filesystem::remove_all(profile_, ignored);
  }

  /// One WebDriver command; its "value", or throws with the driver's error.
  nlohmann::json command(const std::string& method, const std::string& path, const nlohmann::json& body = nlohmann::json::object()) {
    const auto result = method == "GET" ? client_->Get(path)
                        : method == "DELETE" ? client_->Delete(path)
                                             : client_->Post(path, body.dump(), "application/json");
    if (!result) throw std::runtime_error(fmt::format("webdriver: no answer to {} {}", method, path));
    const auto answer = nlohmann::json::parse(result->body);
    if (result->status != 200) throw std::runtime_error(fmt::format("webdriver: {} {} → {}", method, path, result->body));
    return answer["value"];
  }

  nlohmann::json session(const std::string& method, const std::string& path, const nlohmann::json& body = nlohmann::json::object()) {
    return command(method, "/session/" + session_ + path, body);
  }

  void go(const std::string& url) { session("POST", "/url", {{"url", url}}); }

  /// Runs `script` (a function body; `return` gives the result) with `args`.
  nlohmann::json run(const std::string& script, const nlohmann::json& args = nlohmann::json::array()) {
    return session("POST", "/execute/sync", {{"script", script}, {"args", args}});
  }

  /// Polls `condition` (a script returning a boolean) until true; false after `seconds`.
  bool wait_for(const std::string& condition, int seconds = 120) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    while (std::chrono::steady_clock::now() < deadline) {
      if (run(condition).get<bool>()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }

  /// The element's WebDriver reference, by CSS selector.
  std::string element(const std::string& css) {
    const auto value = session("POST", "/element", {{"using", "css selector"}, {"value", css}});
    return value.begin().value().get<std::string>();
  }

  /// Types `keys` into the focused element (WebDriver key codes, e.g. "\ue014" = ArrowRight).
  void send_keys(const std::string& css, const std::string& keys) {
    session("POST", "/element/" + element(css) + "/value", {{"text", keys}});
  }

  void click(const std::string& css) { session("POST", "/element/" + element(css) + "/click"); }

 private:
  int port_;
  std::filesystem::path profile_;
  pid_t pid_ = 0;
  std::unique_ptr<httplib::Client> client_;
  std::string session_;
};

}  // namespace specula::testing
