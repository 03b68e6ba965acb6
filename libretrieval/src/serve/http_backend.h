// SPDX-License-Identifier: GPL-3.0-or-later
// The HTTP server under `morphex serve`, as a loadable module (morphex_serve_http.so, built from
// http_backend.cpp). cpp-httplib brings OpenSSL and brotli, whose loading took about 9 ms of every
// command's start; only `serve` needs them, so they are loaded with this module when it starts.
//
// The module knows nothing of morphex: routes, checks and answers are http.cpp's, given here as
// values and std::function, so that nothing crosses the boundary but the standard library's types
// (both sides are built together, by one compiler, against one libstdc++). Handlers must not let
// morphex's own exceptions escape: the module catches std::exception only.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace morphex::serve {

// A request as a route sees it. Header names are lower case; params keep every value of a name
// in order; files are a multipart form's, by field name (the first of each).
struct HttpRequest {
  struct File {
    std::string filename, content;
  };
  std::string method, path, body;
  std::vector<std::string> matches;  // the route's pattern: [0] the whole path, then its groups
  std::multimap<std::string, std::string> headers;
  std::multimap<std::string, std::string> params;
  bool multipart = false;
  std::map<std::string, File> files;

  // The first value of a header ("" when absent), by its name in any case.
  std::string header(const std::string& name) const;
  bool has_header(const std::string& name) const;
};

struct HttpResponse {
  int status = 200;
  std::string body, type;
  std::vector<std::pair<std::string, std::string>> headers;
  void set(std::string content, std::string content_type) {
    body = std::move(content);
    type = std::move(content_type);
  }
};

using HttpHandler = std::function<void(const HttpRequest&, HttpResponse&)>;

struct HttpRoute {
  std::string method;   // GET or POST
  std::string pattern;  // an ECMAScript regular expression the whole path must match
  HttpHandler handler;
};

struct HttpSetup {
  int threads = 8;              // request threads
  std::size_t max_payload = 0;  // bytes of a body, beyond which 413 is answered
  int read_timeout_seconds = 30;
  std::vector<std::pair<std::string, std::string>> default_headers;  // on every answer
  std::vector<HttpRoute> routes;
  // Before routing, when only the request line and headers are read: true when it answered.
  std::function<bool(const HttpRequest&, HttpResponse&)> before;
  // The body of an error answer that has none (httplib's own refusals: 404, 413, ...).
  std::function<std::string(int status, const std::string& path)> error_body;
};

class HttpBackend {
 public:
  virtual ~HttpBackend() = default;
  // Binds host:port (port 0: a free one) and returns the port, or -1 with errno set.
  virtual int bind(const std::string& host, int port) = 0;
  virtual void run() = 0;   // serves until stop()
  virtual void stop() = 0;  // from any thread
};

// The module's entry point, looked up by this name; the server is the caller's to delete.
using MakeHttpBackend = HttpBackend* (*)(const HttpSetup& setup);
inline constexpr const char* kHttpModule = "morphex_serve_http.so";
inline constexpr const char* kMakeHttpBackend = "morphex_make_http_backend";

// Loads the module (once) and makes a server; ModuleError (morphex/internal/modules.h) saying why
// when it cannot.
std::unique_ptr<HttpBackend> make_http_backend(const HttpSetup& setup);

}  // namespace morphex::serve
