// SPDX-License-Identifier: GPL-3.0-or-later
// The HTTP side of `morphex serve`: routes, request checks and error answers, over the server the
// module morphex_serve_http.so runs (http_backend.h: cpp-httplib, loaded only by `serve`). What
// each route answers is api.cpp's.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "api.h"
#include "assets.h"
#include "morphex/error.h"
#include "morphex/internal/modules.h"
#include "morphex/server.h"
#include "serve/http_backend.h"

#ifndef MORPHEX_THREE_JS_DIR
#define MORPHEX_THREE_JS_DIR "/usr/share/javascript/three"
#endif

namespace morphex {
namespace {

namespace fs = std::filesystem;
using serve::HttpRequest;
using serve::HttpResponse;

// The three.js files the page loads (non-module builds that define the global THREE), by route
// and by path under libjs-three's folder. Only these are served from there.
const std::pair<const char*, const char*> kThreeFiles[] = {
    {"/three/three.min.js", "build/three.min.js"},
    {"/three/GLTFLoader.js", "examples/js/loaders/GLTFLoader.js"},
    {"/three/OrbitControls.js", "examples/js/controls/OrbitControls.js"},
};

std::string error_json(const std::string& message) {
  return nlohmann::json{{"error", message}}.dump();
}

void send_json(HttpResponse& res, const nlohmann::json& value) {
  res.set(value.dump(), "application/json");
}

bool is_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

// The reason given for a status when a handler did not give one (httplib's own refusals).
std::string default_message(int status, const ServerOptions& options) {
  switch (status) {
    case 400:
      return "malformed request";
    case 404:
      return "no such route";
    case 413:
      return "the upload is larger than the limit of " + std::to_string(options.max_upload_bytes) +
             " bytes (morphex serve --max-upload-mb)";
    case 414:
      return "the request line is too long";
    case 416:
      return "malformed Range header";
    default:
      return "HTTP error " + std::to_string(status);
  }
}

}  // namespace

struct IndexServer::Impl {
  Impl(const std::string& index_path, ServerOptions opts)
      : options(std::move(opts)), api(index_path, options) {}
  void load_three();
  void add_routes(serve::HttpSetup& setup);
  void add_checks(serve::HttpSetup& setup);
  // Runs `answer` and sends what it returns, or the refusal it throws as {"error": ...}.
  void respond(HttpResponse& res, const std::function<void()>& answer);

  ServerOptions options;
  serve::IndexApi api;
  std::map<std::string, std::string> three;  // route -> the file's content
  int port = -1;
  std::unique_ptr<serve::HttpBackend> http;  // last: its threads call the members above
};

void IndexServer::Impl::load_three() {
  const std::string dir = options.three_dir.empty() ? MORPHEX_THREE_JS_DIR : options.three_dir;
  for (const auto& [route, file] : kThreeFiles) {
    const fs::path path = fs::path(dir) / file;
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw InputError(path.string(),
                       "three.js is missing, which the page's 3D view needs: install Debian's "
                       "libjs-three (scripts/setup does)");
    std::ostringstream content;
    content << in.rdbuf();
    three[route] = std::move(content).str();
  }
}

void IndexServer::Impl::respond(HttpResponse& res, const std::function<void()>& answer) {
  try {
    answer();
  } catch (const serve::RequestError& e) {
    res = {};
    res.status = e.status();
    res.set(error_json(e.what()), "application/json");
    if (e.status() == 503) res.headers.emplace_back("Retry-After", "2");
  } catch (const Error& e) {  // a morphex input error that api.cpp did not classify
    res = {};
    res.status = 400;
    res.set(error_json(e.what()), "application/json");
  } catch (const std::bad_alloc&) {
    res = {};
    res.status = 500;
    res.set(error_json("out of memory"), "application/json");
  } catch (const std::exception& e) {  // the module catches these too, but knows less
    res = {};
    res.status = 500;
    res.set(error_json(e.what()), "application/json");
  }
}

// Checks before any route or body is read: the Host of a server on this machine only, the
// Origin of an upload, a declared length for a body.
void IndexServer::Impl::add_checks(serve::HttpSetup& setup) {
  const bool local = is_loopback(options.host);
  setup.before = [this, local](const HttpRequest& req, HttpResponse& res) {
    const auto refuse = [&](int status, const std::string& message) {
      res.status = status;
      res.set(error_json(message), "application/json");
      return true;
    };
    if (req.method != "GET" && req.method != "HEAD" && req.method != "POST")
      return refuse(405, req.method + " is not served (GET and POST only)");
    // A page of another site that resolves its own name to 127.0.0.1 (DNS rebinding) would
    // send its name as Host: a server for this machine answers only to its own names.
    const std::string host = req.header("Host");
    const std::string suffix = ":" + std::to_string(port);
    if (local && host != "localhost" + suffix && host != "127.0.0.1" + suffix &&
        host != "[::1]" + suffix && host != options.host + suffix)
      return refuse(403, "unexpected Host '" + host + "' for a server on this machine only");
    if (req.method != "POST") return false;
    // Browsers name the page that sends a POST: only this server's own page may upload.
    const std::string origin = req.header("Origin");
    if (!origin.empty() && origin != "http://" + host)
      return refuse(403, "uploads are accepted from this server's page only");
    // httplib bounds a body by its declared length only: a chunked or undelimited one would
    // be read whole.
    if (req.has_header("Transfer-Encoding") || !req.has_header("Content-Length"))
      return refuse(411, "an upload needs a Content-Length (no chunked transfer)");
    return false;
  };
  setup.error_body = [this](int status, const std::string& path) {
    std::string message = default_message(status, options);
    if (status == 404) message += ": " + path.substr(0, 200);
    return error_json(message);
  };
}

void IndexServer::Impl::add_routes(serve::HttpSetup& setup) {
  const auto get = [&setup](std::string pattern, serve::HttpHandler handler) {
    setup.routes.push_back({"GET", std::move(pattern), std::move(handler)});
  };
  for (const serve::WebAsset& asset : serve::web_assets())
    get(asset.route, [&asset](const HttpRequest&, HttpResponse& res) {
      res.set(std::string(reinterpret_cast<const char*>(asset.data), asset.size), asset.type);
      res.headers.emplace_back("Cache-Control", "no-cache");
    });
  for (const auto& [route, file] : kThreeFiles) {
    const std::string& content = three.at(route);
    get(route, [&content](const HttpRequest&, HttpResponse& res) {
      res.set(content, "text/javascript; charset=utf-8");
      res.headers.emplace_back("Cache-Control", "max-age=3600");
    });
  }
  const auto json_route = [this, &get](const std::string& pattern,
                                       std::function<nlohmann::json(const HttpRequest&)> answer) {
    get(pattern, [this, answer](const HttpRequest& req, HttpResponse& res) {
      respond(res, [&] { send_json(res, answer(req)); });
    });
  };
  json_route("/api/info", [this](const HttpRequest&) { return api.info(); });
  json_route("/api/meshes", [this](const HttpRequest&) { return api.meshes(); });
  json_route("/api/failures", [this](const HttpRequest&) { return api.failures(); });
  // Ids are digits only, so that nothing else in a path (.., %2e, /) reaches a route.
  json_route(R"(/api/mesh/(\d{1,18}))",
             [this](const HttpRequest& req) { return api.mesh(std::stoll(req.matches[1])); });
  const auto params = [](const HttpRequest& req) {
    serve::Params out;
    for (const auto& [name, value] : req.params) out.emplace(name, value);  // the first of each
    return out;
  };
  json_route("/api/query",
             [this, params](const HttpRequest& req) { return api.query_indexed(params(req)); });
  get(R"(/api/mesh/(\d{1,18})\.glb)", [this](const HttpRequest& req, HttpResponse& res) {
    respond(res, [&] {
      res.set(api.glb(std::stoll(req.matches[1])), "model/gltf-binary");
      res.headers.emplace_back("Cache-Control", "private, max-age=60");
    });
  });
  get(R"(/api/thumb/(\d{1,18})\.png)", [this](const HttpRequest& req, HttpResponse& res) {
    respond(res, [&] {
      res.set(api.thumbnail(std::stoll(req.matches[1])), "image/png");
      res.headers.emplace_back("Cache-Control", "private, max-age=60");
    });
  });
  // An upload: a multipart form with the file in the field "mesh" (the page), or the file as the
  // body with its name in ?filename= (curl --data-binary).
  setup.routes.push_back(
      {"POST", "/api/query", [this, params](const HttpRequest& req, HttpResponse& res) {
         respond(res, [&] {
           if (req.multipart) {
             const auto file = req.files.find("mesh");
             if (file == req.files.end())
               throw serve::RequestError(400, "expected the mesh file in the form field 'mesh'");
             send_json(res,
                       api.query_upload(file->second.filename, file->second.content, params(req)));
           } else {
             const auto name = req.params.lower_bound("filename");  // first
             if (name == req.params.end() || name->first != "filename")
               throw serve::RequestError(400, "expected ?filename=NAME.off (or a multipart form)");
             send_json(res, api.query_upload(name->second, req.body, params(req)));
           }
         });
       }});
}

IndexServer::IndexServer(const std::string& index_path, ServerOptions options)
    : impl_(std::make_unique<Impl>(index_path, std::move(options))) {
  impl_->load_three();
  Impl& s = *impl_;
  serve::HttpSetup setup;
  setup.threads = std::max(1, s.options.threads);
  // Room for the multipart form around the file; the file itself is checked against the limit.
  setup.max_payload = std::size_t(s.options.max_upload_bytes) + (std::size_t(1) << 20);
  setup.read_timeout_seconds = 30;
  setup.default_headers = {
      {"X-Content-Type-Options", "nosniff"},
      {"Referrer-Policy", "no-referrer"},
      {"Cache-Control", "no-store"},
      // The page's own files only; thumbnails of uploads come as data: URLs.
      {"Content-Security-Policy",
       "default-src 'self'; img-src 'self' data:; object-src 'none'; frame-ancestors 'none'"},
  };
  s.add_checks(setup);
  s.add_routes(setup);
  s.http = serve::make_http_backend(setup);
}

IndexServer::~IndexServer() = default;

int IndexServer::bind() {
  Impl& s = *impl_;
  errno = 0;
  const std::string where = s.options.host + ":" + std::to_string(s.options.port);
  s.port = s.http->bind(s.options.host, s.options.port);
  if (s.port < 0)
    throw std::runtime_error("cannot listen on " + where +
                             (errno ? std::string(": ") + std::strerror(errno) : std::string()) +
                             " (another server on that port? --port 0 picks a free one)");
  return s.port;
}

void IndexServer::run() {
  impl_->http->run();
}

void IndexServer::stop() {
  impl_->http->stop();
}

std::size_t IndexServer::meshes() const {
  return impl_->api.count(false);
}

std::size_t IndexServer::failed() const {
  return impl_->api.count(true);
}

}  // namespace morphex

namespace morphex::serve {

namespace {
// Header names arrive in lower case (http_backend.cpp): a name asked for is looked up so.
std::string lower_case(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return name;
}
}  // namespace

std::string HttpRequest::header(const std::string& name) const {
  const auto found = headers.find(lower_case(name));
  return found == headers.end() ? std::string() : found->second;
}

bool HttpRequest::has_header(const std::string& name) const {
  return headers.count(lower_case(name)) > 0;
}

std::unique_ptr<HttpBackend> make_http_backend(const HttpSetup& setup) {
  // Opened once: a second server in the process (tests) finds it loaded.
  static const LoadedModule module = open_module(kHttpModule, false);
  const auto make = reinterpret_cast<MakeHttpBackend>(module_symbol(module, kMakeHttpBackend));
  if (!make)
    throw ModuleError(kHttpModule, "morphex serve cannot start its HTTP server: " +
                                       (module.error.empty()
                                            ? std::string("the module has no ") + kMakeHttpBackend
                                            : module.error));
  return std::unique_ptr<HttpBackend>(make(setup));
}

}  // namespace morphex::serve
