// SPDX-License-Identifier: GPL-3.0-or-later
// The module morphex_serve_http.so: http_backend.h's server over cpp-httplib (Debian's
// libcpp-httplib-dev). The only file that includes httplib.h; it translates requests and answers
// and sets httplib up, and decides nothing about what is served (http.cpp does).
#include <httplib.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>

#include "serve/http_backend.h"

namespace morphex::serve {
namespace {

using Handled = httplib::Server::HandlerResponse;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// What a route sees of httplib's request. The body is read by then, except before routing.
HttpRequest to_request(const httplib::Request& req) {
  HttpRequest out;
  out.method = req.method;
  out.path = req.path;
  out.body = req.body;
  for (const auto& match : req.matches) out.matches.push_back(match.str());
  for (const auto& [name, value] : req.headers) out.headers.emplace(lower(name), value);
  for (const auto& [name, value] : req.params) out.params.emplace(name, value);
  out.multipart = req.is_multipart_form_data();
  for (const auto& [field, file] : req.files)
    out.files.emplace(field, HttpRequest::File{file.filename, file.content});  // first kept
  return out;
}

void answer(const HttpResponse& from, httplib::Response& res) {
  res.status = from.status;
  if (!from.body.empty() || !from.type.empty()) res.set_content(from.body, from.type.c_str());
  for (const auto& [name, value] : from.headers) res.set_header(name.c_str(), value);
}

class Backend final : public HttpBackend {
 public:
  explicit Backend(const HttpSetup& setup) : setup_(setup) {
    const std::size_t threads = std::size_t(std::max(1, setup_.threads));
    http_.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
    http_.set_payload_max_length(setup_.max_payload);
    http_.set_read_timeout(setup_.read_timeout_seconds);
    // httplib's default sets SO_REUSEPORT, with which a second server (another index, another
    // user's program under the same uid) could bind the same port and take half the requests:
    // SO_REUSEADDR only, so that a restarted server can bind again while old connections linger.
    http_.set_socket_options([](socket_t socket) {
      const int yes = 1;
      setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    });
    httplib::Headers headers;
    for (const auto& [name, value] : setup_.default_headers) headers.emplace(name, value);
    http_.set_default_headers(headers);
    add_handlers();
    for (const HttpRoute& route : setup_.routes) add_route(route);
  }

  int bind(const std::string& host, int port) override {
    if (port == 0) return http_.bind_to_any_port(host);
    return http_.bind_to_port(host, port) ? port : -1;
  }
  void run() override { http_.listen_after_bind(); }
  void stop() override { http_.stop(); }

 private:
  void add_handlers() {
    http_.set_pre_routing_handler(httplib::Server::HandlerWithResponse(
        [this](const httplib::Request& req, httplib::Response& res) {
          if (!setup_.before) return Handled::Unhandled;
          HttpResponse out;
          if (!setup_.before(to_request(req), out)) return Handled::Unhandled;
          answer(out, res);
          return Handled::Handled;
        }));
    http_.set_error_handler(httplib::Server::HandlerWithResponse(
        [this](const httplib::Request& req, httplib::Response& res) {
          if (!res.body.empty() || !setup_.error_body) return Handled::Unhandled;
          res.set_content(setup_.error_body(res.status, req.path), "application/json");
          return Handled::Handled;
        }));
    http_.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
          res.status = 500;
          std::string message = "internal error";
          try {
            std::rethrow_exception(error);
          } catch (const std::exception& e) {
            message = e.what();
          } catch (...) {
          }
          res.set_content(nlohmann::json{{"error", message}}.dump(
                              -1, ' ', false, nlohmann::json::error_handler_t::replace),
                          "application/json");
        });
  }

  void add_route(const HttpRoute& route) {
    const HttpHandler& handler = route.handler;
    const auto call = [&handler](const httplib::Request& req, httplib::Response& res) {
      HttpResponse out;
      handler(to_request(req), out);
      answer(out, res);
    };
    if (route.method == "POST")
      http_.Post(route.pattern, call);
    else
      http_.Get(route.pattern, call);
  }

  HttpSetup setup_;
  httplib::Server http_;
};

}  // namespace
}  // namespace morphex::serve

extern "C" morphex::serve::HttpBackend* morphex_make_http_backend(
    const morphex::serve::HttpSetup& setup) {
  return new morphex::serve::Backend(setup);
}
