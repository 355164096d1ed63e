#include "tirpol/live/live_server.h"

#include <httplib.h>
#include <sys/socket.h>

#include <map>

#include "tirpol/core/error.h"
#include "tirpol/live/access.h"

namespace tirpol::live {

std::string_view embedded_file(std::string_view name);  // generated from web/ (cmake/EmbedFiles.cmake)

namespace {
/// How long a request for a newer image waits before answering 204: short enough that a page whose
/// camera stalled still refreshes its status, long enough not to spin.
constexpr std::chrono::milliseconds kLongPoll{1000};
/// Each open page holds a few connections (image, status, Stokes); two dozen threads serve several pages.
constexpr std::size_t kServerThreads = 24;

constexpr const char* kTokenCookie = "tirpol_token";

/// The value of cookie `name` in a Cookie header ("a=1; b=2"), or "".
std::string cookie_value(const std::string& header, const std::string& name) {
    std::size_t at = 0;
    while (at < header.size()) {
        const std::size_t end = std::min(header.find(';', at), header.size());
        std::size_t start = at;
        while (start < end && header[start] == ' ') ++start;
        if (header.compare(start, name.size() + 1, name + "=") == 0)
            return header.substr(start + name.size() + 1, end - start - name.size() - 1);
        at = end + 1;
    }
    return "";
}

void send_json(httplib::Response& res, const nlohmann::json& j, int status = 200) {
    res.status = status;
    res.set_content(j.dump(), "application/json");
}

std::uint64_t after_param(const httplib::Request& req) {
    if (!req.has_param("after")) return 0;
    try {
        return std::stoull(req.get_param_value("after"));
    } catch (const std::exception&) {
        return 0;
    }
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
        if (token_matches(req.get_header_value("X-Tirpol-Token"), m_token) ||
            token_matches(cookie_value(req.get_header_value("Cookie"), kTokenCookie), m_token))
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
    server.Get("/api/frame", [&view](const httplib::Request& req, httplib::Response& res) {
        send_image(res, view.frame_after(after_param(req), kLongPoll));
    });
    server.Get("/api/stokes", [&view](const httplib::Request& req, httplib::Response& res) {
        send_image(res, view.stokes_after(after_param(req), kLongPoll));
    });
    server.Post("/api/capture/start", [&view](const httplib::Request& req, httplib::Response& res) {
        try {
            const auto body = nlohmann::json::parse(req.body);
            CaptureRequest request;
            request.plan = body.at("plan").get<std::string>();
            request.output = body.at("output").get<std::string>();
            request.resume = body.value("resume", false);
            view.capture().start(request);
            send_json(res, view.status());
        } catch (const nlohmann::json::exception& e) {
            send_json(res, {{"error", std::string("capture request: expected {plan, output, resume}: ") + e.what()}},
                      400);
        } catch (const Error& e) {
            send_json(res, {{"error", e.what()}}, 400);
        }
    });
    server.Post("/api/capture/stop", [&view](const httplib::Request&, httplib::Response& res) {
        try {
            view.capture().stop();
            send_json(res, view.status());
        } catch (const Error& e) {
            send_json(res, {{"error", e.what()}}, 400);
        }
    });
    server.Post("/api/observations", [this](const httplib::Request& req, httplib::Response& res) {
        const auto body = nlohmann::json::parse(req.body, nullptr, false);
        if (body.is_discarded() || !req.has_param("client")) {
            send_json(res, {{"error", "observations: expected ?client=ID and a JSON body"}}, 400);
            return;
        }
        std::lock_guard lock(m_impl->observations_mutex);
        m_impl->observations[req.get_param_value("client")] = body;
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
