#include "tirpol/live/live_server.h"

#include <httplib.h>
#include <sys/socket.h>

#include <map>
#include <optional>

#include "tirpol/core/error.h"
#include "tirpol/core/utf8.h"
#include "tirpol/live/access.h"
#include "tirpol/live/api_request.h"

namespace tirpol::live {

std::string_view embedded_file(std::string_view name);  // generated from web/ (cmake/EmbedFiles.cmake)

namespace {
/// How long a request for a newer image waits before answering 204: short enough that a page whose
/// camera stalled still refreshes its status, long enough not to spin.
constexpr std::chrono::milliseconds kLongPoll{1000};
/// Each open page holds a few connections (image, status, Stokes); two dozen threads serve several pages.
constexpr std::size_t kServerThreads = 24;

constexpr const char* kTokenCookie = "tirpol_token";

void send_json(httplib::Response& res, const nlohmann::json& j) {
    res.status = 200;
    res.set_content(json_text(j), "application/json");
}

void send_error(httplib::Response& res, const Error& e) {
    res.status = 400;
    res.set_content(error_body(e.what()), "application/json");
}

std::optional<std::string> param(const httplib::Request& req, const char* name) {
    if (!req.has_param(name)) return std::nullopt;
    return req.get_param_value(name);
}

void send_image(httplib::Response& res, const EncodedImage& image) {
    if (!image.bytes) {
        res.status = 204;
        return;
    }
    res.set_header("X-Sequence", std::to_string(image.sequence));
    res.set_header("Cache-Control", "no-store");
    // The shared buffer stays alive until the provider has written it (one copy per frame in total).
    const auto bytes = image.bytes;
    res.set_content_provider(bytes->size(), "application/octet-stream",
                             [bytes](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                                 return sink.write(bytes->data() + offset, length);
                             });
}

/// Serves an image stream: the frame after ?after=SEQ from `next`, or 400 for a bad sequence number.
template <typename Next>
auto image_handler(Next next) {
    return [next](const httplib::Request& req, httplib::Response& res) {
        std::uint64_t after = 0;
        try {
            after = parse_after(param(req, "after"));
        } catch (const Error& e) {
            send_error(res, e);
            return;
        }
        send_image(res, next(after));
    };
}
}  // namespace

struct LiveServer::Impl {
    httplib::Server server;
    std::mutex observations_mutex;
    std::map<std::string, nlohmann::json> observations;
};

LiveServer::LiveServer(LiveView& view, const ServerOptions& options)
    : m_impl(std::make_unique<Impl>()), m_bind_address(options.bind_address) {
    if (!is_loopback_address(options.bind_address)) m_token = make_access_token();
    auto& server = m_impl->server;
    server.new_task_queue = [] { return new httplib::ThreadPool(kServerThreads); };
    // httplib's default also sets SO_REUSEPORT, which lets a second `tirpol live` bind the same port and
    // silently share its connections; SO_REUSEADDR alone still allows a quick restart.
    server.set_socket_options([](socket_t sock) {
        const int yes = 1;
        ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });

    server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
        if (m_token.empty()) return httplib::Server::HandlerResponse::Unhandled;
        if (token_matches(req.get_param_value("token"), m_token)) {
            // The page's own files (<script src>, <link href>) carry no query: the cookie covers them.
            res.set_header("Set-Cookie",
                           std::string(kTokenCookie) + "=" + m_token + "; HttpOnly; SameSite=Strict; Path=/");
            return httplib::Server::HandlerResponse::Unhandled;
        }
        if (request_authorised(m_token, "", req.get_header_value("X-Tirpol-Token"), req.get_header_value("Cookie"),
                               kTokenCookie))
            return httplib::Server::HandlerResponse::Unhandled;
        res.status = 401;
        res.set_content("tirpol live: this page needs the access token printed when the server started (?token=...)\n",
                        "text/plain");
        return httplib::Server::HandlerResponse::Handled;
    });

    auto serve_file = [](const std::string& name, const char* type) {
        return [name, type](const httplib::Request&, httplib::Response& res) {
            res.set_content(std::string(embedded_file(name)), type);
        };
    };
    server.Get("/", serve_file("index.html", "text/html; charset=utf-8"));
    server.Get("/live.js", serve_file("live.js", "text/javascript; charset=utf-8"));
    server.Get("/live.css", serve_file("live.css", "text/css; charset=utf-8"));

    server.Get("/api/describe",
               [&view](const httplib::Request&, httplib::Response& res) { send_json(res, view.describe()); });
    server.Get("/api/status",
               [&view](const httplib::Request&, httplib::Response& res) { send_json(res, view.status()); });
    server.Get("/api/frame", image_handler([&view](std::uint64_t after) { return view.frame_after(after, kLongPoll); }));
    server.Get("/api/stokes",
               image_handler([&view](std::uint64_t after) { return view.stokes_after(after, kLongPoll); }));
    server.Post("/api/capture/start", [&view](const httplib::Request& req, httplib::Response& res) {
        try {
            view.capture().start(parse_capture_request(req.body));
            send_json(res, view.status());
        } catch (const Error& e) {
            send_error(res, e);
        }
    });
    server.Post("/api/capture/stop", [&view](const httplib::Request&, httplib::Response& res) {
        try {
            view.capture().stop();
            send_json(res, view.status());
        } catch (const Error& e) {
            send_error(res, e);
        }
    });
    server.Post("/api/observations", [this](const httplib::Request& req, httplib::Response& res) {
        nlohmann::json body;
        try {
            body = parse_observation(param(req, "client"), req.body);
        } catch (const Error& e) {
            send_error(res, e);
            return;
        }
        std::lock_guard lock(m_impl->observations_mutex);
        m_impl->observations[req.get_param_value("client")] = std::move(body);
        send_json(res, {{"ok", true}});
    });
    server.Get("/api/observations", [this](const httplib::Request&, httplib::Response& res) {
        std::lock_guard lock(m_impl->observations_mutex);
        send_json(res, nlohmann::json(m_impl->observations));
    });

    m_port = options.port == 0 ? server.bind_to_any_port(options.bind_address)
                               : (server.bind_to_port(options.bind_address, options.port) ? options.port : -1);
    if (m_port <= 0)
        fail("live view: cannot listen on {} port {} (in use, or not an address of this machine)", options.bind_address,
             options.port);
}

LiveServer::~LiveServer() { stop(); }

std::string LiveServer::url() const {
    const std::string host =
        m_bind_address.find(':') != std::string::npos ? "[" + m_bind_address + "]" : m_bind_address;
    std::string url = "http://" + host + ":" + std::to_string(m_port) + "/";
    if (!m_token.empty()) url += "?token=" + m_token;
    return url;
}

void LiveServer::run() { m_impl->server.listen_after_bind(); }

void LiveServer::stop() { m_impl->server.stop(); }

}  // namespace tirpol::live
