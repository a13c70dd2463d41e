// specula serve: the library's JSON API and the interactive page over HTTP (src/serve/).
#include <fmt/format.h>
#include <cstdlib>
#include <iostream>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>

#include "cli.h"
#include "specula/interrupt/interrupt.h"
#include "specula/serve/server.h"

extern char** environ;

namespace specula::cli {
namespace {

struct ServeOptions {
  std::string host = "127.0.0.1";
  int port = 8080;
  bool open = false;
};

/// Stops the server once main's StopSignals has seen SIGINT or SIGTERM (request_stop); returns
/// then or when `done` is set.
void stop_on_signal(serve::Server& server, const std::atomic<bool>& done) {
  while (!done && !stop_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (!done) server.stop();
}

/// Opens the page in the desktop's browser, if there is one (xdg-open); never fails the server.
void open_in_browser(const std::string& url) {
  const char* argv[] = {"xdg-open", url.c_str(), nullptr};
  pid_t pid = 0;
  if (posix_spawnp(&pid, "xdg-open", nullptr, nullptr, const_cast<char* const*>(argv), environ) != 0)
    std::cerr << "specula serve: cannot run xdg-open; open " << url << " yourself\n";
  else
    std::thread([pid] { waitpid(pid, nullptr, 0); }).detach();
}

void run(serve::Server& server, const ServeOptions& o) {
  const int port = server.bind(o.host, o.port);
  if (!serve::is_loopback(o.host))
    std::cerr << fmt::format("specula serve: warning: listening on {}, which other machines may reach; the API "
                             "has no authentication\n", o.host);
  const std::string url = serve::url_of(o.host, port);
  std::cout << "serving " << url << std::endl;
  if (o.open) open_in_browser(url);
  std::atomic<bool> done = false;
  std::thread watcher([&] { stop_on_signal(server, done); });
  server.run();
  done = true;
  watcher.join();
}

void serve(const ServeOptions& o) {
  {
    serve::Server server;
    run(server, o);
  }  // the server's destructor joins its jobs, waiting Limits::stop_seconds at most
  if (const std::size_t left = serve::abandoned_job_threads()) {
    // A search that ignores its cancel flag and work limit still runs: it must not hold the
    // exit, and static destructors must not run under it.
    std::cerr << fmt::format("specula serve: {} job(s) did not stop; exiting without them\n", left);
    std::cout.flush();
    std::_Exit(0);
  }
}

}  // namespace

void add_serve_command(CLI::App& app) {
  auto o = std::make_shared<ServeOptions>();
  auto* cmd = app.add_subcommand("serve", "The interactive lab: a local web page and a JSON API over the library");
  cmd->add_option("--host", o->host, "Address to listen on (loopback by default; others warn)")->capture_default_str();
  cmd->add_option("--port", o->port, "Port; 0 picks a free one (the URL is printed)")
      ->capture_default_str()->check(CLI::Range(0, 65535));
  cmd->add_flag("--open", o->open, "Open the page in the desktop's browser (xdg-open)");
  cmd->footer(
      "Prints \"serving http://HOST:PORT/\" once listening; stops cleanly on Ctrl-C (SIGINT) or SIGTERM,\n"
      "cancelling running fit jobs. The API is documented in docs/serve.md. Examples:\n"
      "  specula serve --open\n"
      "  specula serve --port 0          # a free port\n"
      "  curl -s localhost:8080/api/normalize -d '{\"model\": \"log\", \"n\": [1, 2, 5]}'");
  cmd->callback([o] { serve(*o); });
}

}  // namespace specula::cli
