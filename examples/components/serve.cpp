// specula::serve: the API answering GET /api/models in-process, and the HTTP server bound to a
// free loopback port (then stopped).
#include <cstdio>

#include <specula/serve/server.h>

int main() {
  specula::serve::Api api;
  const specula::serve::Response models = api.handle({"GET", "/api/models", ""});
  specula::serve::Server server;
  const int port = server.bind("127.0.0.1", 0);
  server.stop();
  std::printf("serve: GET /api/models %d (%zu bytes), bound port %s\n", models.status, models.body.size(),
              port > 0 ? "> 0" : "0");
  return models.status == 200 && port > 0 ? 0 : 1;
}
