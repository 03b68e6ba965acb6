// SPDX-License-Identifier: GPL-3.0-or-later
// The HTTP side of `morphex serve` (cpp-httplib, Debian's libcpp-httplib-dev): routes, request
// checks and error answers. The only file that includes httplib.h, which is heavy. What each route
// answers is api.cpp's.
#include <httplib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "api.h"
#include "assets.h"
#include "morphex/error.h"
#include "morphex/server.h"

#ifndef MORPHEX_THREE_JS_DIR
#define MORPHEX_THREE_JS_DIR "/usr/share/javascript/three"
#endif

namespace morphex {
namespace {

namespace fs = std::filesystem;
using Handled = httplib::Server::HandlerResponse;

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

void send_json(httplib::Response& res, const nlohmann::json& value) {
  res.set_content(value.dump(), "application/json");
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
  void add_routes();
  void add_checks();
  // Runs `answer` and sends what it returns, or the refusal it throws as {"error": ...}.
  void respond(httplib::Response& res, const std::function<void()>& answer);

  ServerOptions options;
  serve::IndexApi api;
  httplib::Server http;
  std::map<std::string, std::string> three;  // route -> the file's content
  int port = -1;
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

void IndexServer::Impl::respond(httplib::Response& res, const std::function<void()>& answer) {
  try {
    answer();
  } catch (const serve::RequestError& e) {
    res.status = e.status();
    res.set_content(error_json(e.what()), "application/json");
    if (e.status() == 503) res.set_header("Retry-After", "2");
  } catch (const Error& e) {  // a morphex input error that api.cpp did not classify
    res.status = 400;
    res.set_content(error_json(e.what()), "application/json");
  } catch (const std::bad_alloc&) {
    res.status = 500;
    res.set_content(error_json("out of memory"), "application/json");
  }
}

// Checks before any route or body is read: the Host of a server on this machine only, the
// Origin of an upload, a declared length for a body.
void IndexServer::Impl::add_checks() {
  const bool local = is_loopback(options.host);
  http.set_pre_routing_handler(httplib::Server::HandlerWithResponse(
      [this, local](const httplib::Request& req, httplib::Response& res) {
        const auto refuse = [&](int status, const std::string& message) {
          res.status = status;
          res.set_content(error_json(message), "application/json");
          return Handled::Handled;
        };
        if (req.method != "GET" && req.method != "HEAD" && req.method != "POST")
          return refuse(405, req.method + " is not served (GET and POST only)");
        // A page of another site that resolves its own name to 127.0.0.1 (DNS rebinding) would
        // send its name as Host: a server for this machine answers only to its own names.
        const std::string host = req.get_header_value("Host");
        const std::string suffix = ":" + std::to_string(port);
        if (local && host != "localhost" + suffix && host != "127.0.0.1" + suffix &&
            host != "[::1]" + suffix && host != options.host + suffix)
          return refuse(403, "unexpected Host '" + host + "' for a server on this machine only");
        if (req.method != "POST") return Handled::Unhandled;
        // Browsers name the page that sends a POST: only this server's own page may upload.
        const std::string origin = req.get_header_value("Origin");
        if (!origin.empty() && origin != "http://" + host)
          return refuse(403, "uploads are accepted from this server's page only");
        // httplib bounds a body by its declared length only: a chunked or undelimited one would
        // be read whole.
        if (req.has_header("Transfer-Encoding") || !req.has_header("Content-Length"))
          return refuse(411, "an upload needs a Content-Length (no chunked transfer)");
        return Handled::Unhandled;
      }));
  http.set_error_handler(httplib::Server::HandlerWithResponse(
      [this](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return Handled::Unhandled;
        std::string message = default_message(res.status, options);
        if (res.status == 404) message += ": " + req.path.substr(0, 200);
        res.set_content(error_json(message), "application/json");
        return Handled::Handled;
      }));
  http.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
        res.status = 500;
        std::string message = "internal error";
        try {
          std::rethrow_exception(error);
        } catch (const std::exception& e) {
          message = e.what();
        } catch (...) {
        }
        res.set_content(error_json(message), "application/json");
      });
}

void IndexServer::Impl::add_routes() {
  for (const serve::WebAsset& asset : serve::web_assets())
    http.Get(asset.route, [&asset](const httplib::Request&, httplib::Response& res) {
      res.set_content(reinterpret_cast<const char*>(asset.data), asset.size, asset.type);
      res.set_header("Cache-Control", "no-cache");
    });
  for (const auto& [route, file] : kThreeFiles) {
    const std::string& content = three.at(route);
    http.Get(route, [&content](const httplib::Request&, httplib::Response& res) {
      res.set_content(content, "text/javascript; charset=utf-8");
      res.set_header("Cache-Control", "max-age=3600");
    });
  }
  const auto json_route = [this](const std::string& pattern,
                                 std::function<nlohmann::json(const httplib::Request&)> answer) {
    http.Get(pattern, [this, answer](const httplib::Request& req, httplib::Response& res) {
      respond(res, [&] { send_json(res, answer(req)); });
    });
  };
  json_route("/api/info", [this](const httplib::Request&) { return api.info(); });
  json_route("/api/meshes", [this](const httplib::Request&) { return api.meshes(); });
  json_route("/api/failures", [this](const httplib::Request&) { return api.failures(); });
  // Ids are digits only, so that nothing else in a path (.., %2e, /) reaches a route.
  json_route(R"(/api/mesh/(\d{1,18}))",
             [this](const httplib::Request& req) { return api.mesh(std::stoll(req.matches[1])); });
  const auto params = [](const httplib::Request& req) {
    serve::Params out;
    for (const auto& [name, value] : req.params) out.emplace(name, value);  // the first of each
    return out;
  };
  json_route("/api/query", [this, params](const httplib::Request& req) {
    return api.query_indexed(params(req));
  });
  http.Get(R"(/api/mesh/(\d{1,18})\.glb)",
           [this](const httplib::Request& req, httplib::Response& res) {
             respond(res, [&] {
               res.set_content(api.glb(std::stoll(req.matches[1])), "model/gltf-binary");
               res.set_header("Cache-Control", "private, max-age=60");
             });
           });
  http.Get(R"(/api/thumb/(\d{1,18})\.png)",
           [this](const httplib::Request& req, httplib::Response& res) {
             respond(res, [&] {
               res.set_content(api.thumbnail(std::stoll(req.matches[1])), "image/png");
               res.set_header("Cache-Control", "private, max-age=60");
             });
           });
  // An upload: a multipart form with the file in the field "mesh" (the page), or the file as the
  // body with its name in ?filename= (curl --data-binary).
  http.Post("/api/query", [this, params](const httplib::Request& req, httplib::Response& res) {
    respond(res, [&] {
      if (req.is_multipart_form_data()) {
        if (!req.has_file("mesh"))
          throw serve::RequestError(400, "expected the mesh file in the form field 'mesh'");
        const httplib::MultipartFormData file = req.get_file_value("mesh");
        send_json(res, api.query_upload(file.filename, file.content, params(req)));
      } else {
        if (!req.has_param("filename"))
          throw serve::RequestError(400, "expected ?filename=NAME.off (or a multipart form)");
        send_json(res, api.query_upload(req.get_param_value("filename"), req.body, params(req)));
      }
    });
  });
}

IndexServer::IndexServer(const std::string& index_path, ServerOptions options)
    : impl_(std::make_unique<Impl>(index_path, std::move(options))) {
  impl_->load_three();
  Impl& s = *impl_;
  const int threads = std::max(1, s.options.threads);
  s.http.new_task_queue = [threads] { return new httplib::ThreadPool(std::size_t(threads)); };
  // Room for the multipart form around the file; the file itself is checked against the limit.
  s.http.set_payload_max_length(std::size_t(s.options.max_upload_bytes) + (std::size_t(1) << 20));
  s.http.set_read_timeout(30);
  // httplib's default sets SO_REUSEPORT, with which a second server (another index, another
  // user's program under the same uid) could bind the same port and take half the requests:
  // SO_REUSEADDR only, so that a restarted server can bind again while old connections linger.
  s.http.set_socket_options([](socket_t socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  s.http.set_default_headers({
      {"X-Content-Type-Options", "nosniff"},
      {"Referrer-Policy", "no-referrer"},
      {"Cache-Control", "no-store"},
      // The page's own files only; thumbnails of uploads come as data: URLs.
      {"Content-Security-Policy",
       "default-src 'self'; img-src 'self' data:; object-src 'none'; frame-ancestors 'none'"},
  });
  s.add_checks();
  s.add_routes();
}

IndexServer::~IndexServer() = default;

int IndexServer::bind() {
  Impl& s = *impl_;
  errno = 0;
  const std::string where = s.options.host + ":" + std::to_string(s.options.port);
  if (s.options.port == 0) {
    s.port = s.http.bind_to_any_port(s.options.host);
  } else {
    s.port = s.http.bind_to_port(s.options.host, s.options.port) ? s.options.port : -1;
  }
  if (s.port < 0)
    throw std::runtime_error("cannot listen on " + where +
                             (errno ? std::string(": ") + std::strerror(errno) : std::string()) +
                             " (another server on that port? --port 0 picks a free one)");
  return s.port;
}

void IndexServer::run() {
  impl_->http.listen_after_bind();
}

void IndexServer::stop() {
  impl_->http.stop();
}

std::size_t IndexServer::meshes() const {
  return impl_->api.count(false);
}

std::size_t IndexServer::failed() const {
  return impl_->api.count(true);
}

}  // namespace morphex
