#include "tirpol/live/live_server.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>

#include <map>
#include <optional>

#include "access.h"
#include "api_request.h"
#include "guarded_server.h"
#include "httplib_after_eigen.h"
#include "live_view.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/utf8.h"

namespace tirpol::live {

std::string_view embedded_file(
    std::string_view name);  // generated from web/ (cmake/EmbedFiles.cmake)

namespace {
/// How long a request for a newer image waits before answering 204: short enough that a page whose
/// camera stalled still refreshes its status, long enough not to spin.
constexpr std::chrono::milliseconds kLongPoll{1000};
constexpr const char* kTokenCookie = "tirpol_token";

void send_json(httplib::Response& res, const nlohmann::json& j) {
    res.status = 200;
    res.set_content(json_text(j), "application/json");
}

void send_error(httplib::Response& res, const Error& e, int status = 400) {
    res.status = status;
    res.set_content(error_body(e.what()), "application/json");
}

void send_refusal(httplib::Response& res, const Refusal& refusal) {
    res.status = refusal.status;
    res.set_content(error_body(refusal.message), "application/json");
    detail::GuardedServer::close_after_this_request();
}

/// The body of a POST, read with at most `max_bytes` (a chunked body is cut off as it streams in);
/// nullopt after answering 413 or 400.
std::optional<std::string> read_body(const httplib::ContentReader& reader, httplib::Response& res,
                                     std::size_t max_bytes) {
    std::string body;
    bool too_large = false;
    const bool complete = reader([&](const char* data, std::size_t length) {
        if (body.size() + length > max_bytes) {
            too_large = true;
            return false;
        }
        body.append(data, length);
        return true;
    });
    if (too_large) {
        send_refusal(res,
                     {413, fmt::format("request body exceeds the limit of {} bytes", max_bytes)});
        return std::nullopt;
    }
    if (!complete) {
        send_refusal(
            res,
            {400, "the request body could not be read (malformed chunks, or the client stopped)"});
        return std::nullopt;
    }
    return body;
}

RequestFacts facts_of(const httplib::Request& req, const std::string& token,
                      const char* cookie_name) {
    RequestFacts f;
    f.method = req.method;
    f.host = req.get_header_value("Host");
    f.origin = req.get_header_value("Origin");
    f.content_type = req.get_header_value("Content-Type");
    f.transfer_encoding = req.get_header_value("Transfer-Encoding");
    if (req.has_header("Content-Length")) f.content_length = req.get_header_value("Content-Length");
    if (!token.empty()) {
        f.explicit_token = token_matches(req.get_param_value("token"), token) ||
                           token_matches(req.get_header_value("X-Tirpol-Token"), token);
        f.cookie_token =
            token_matches(cookie_value(req.get_header_value("Cookie"), cookie_name), token);
    }
    return f;
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
    // The shared buffer stays alive until the provider has written it (one copy per frame in
    // total).
    const auto bytes = image.bytes;
    res.set_content_provider(
        bytes->size(), "application/octet-stream",
        [bytes](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
            return sink.write(bytes->data() + offset, length);
        });
}

/// Serves an image stream: the frame after ?after=SEQ from `next`, or 400 for a bad sequence
/// number.
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

void validate(const ServerOptions& options) {
    if (options.port < 0 || options.port > 65535)
        fail("--port: expected a TCP port 1–65535 (or 0 for a free one), got {}", options.port);
    if (options.bind_address.empty())
        fail("--bind: expected an address (127.0.0.1, 0.0.0.0, ::1, …), got ''");
    const RequestLimits& l = options.limits;
    if (l.max_body_bytes == 0 || l.max_head_bytes == 0 || l.max_connections == 0 ||
        l.idle_timeout.count() <= 0 || l.head_timeout.count() <= 0 ||
        l.request_timeout.count() <= 0)
        fail("live view: every request limit must be positive");
}

struct LiveServer::Impl {
    explicit Impl(const RequestLimits& limits) : server(limits) {}
    detail::GuardedServer server;
    std::optional<RequestPolicy> policy;  // set once the port is known, before run()
    std::mutex observations_mutex;
    std::map<std::string, nlohmann::json> observations;
};

LiveServer::LiveServer(const LiveViewOptions& view_options, const ServerOptions& options)
    : LiveServer((validate(options), std::make_unique<LiveView>(view_options)), options) {}

LiveServer::LiveServer(std::unique_ptr<LiveView> owned_view, const ServerOptions& options)
    : m_owned_view(std::move(owned_view)) {
    serve(*m_owned_view, options);
}

LiveServer::LiveServer(LiveView& view, const ServerOptions& options) { serve(view, options); }

void LiveServer::serve(LiveView& view, const ServerOptions& options) {
    validate(options);
    m_bind_address = options.bind_address;
    m_impl = std::make_unique<Impl>(options.limits);
    if (!is_loopback_address(options.bind_address)) m_token = make_access_token();
    auto& server = m_impl->server;
    // httplib's default also sets SO_REUSEPORT, which lets a second `tirpol live` bind the same
    // port and silently share its connections; SO_REUSEADDR alone still allows a quick restart.
    server.set_socket_options([](socket_t sock) {
        const int yes = 1;
        ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });

    // Every request passes the policy on its line and headers, before any body is read; the same
    // check answers "Expect: 100-continue", so a refused client never sends its body.
    auto refusal_of = [this](const httplib::Request& req) {
        return m_impl->policy->check(facts_of(req, m_token, kTokenCookie));
    };
    server.set_pre_routing_handler(
        [this, refusal_of](const httplib::Request& req, httplib::Response& res) {
            if (const auto refusal = refusal_of(req)) {
                send_refusal(res, *refusal);
                return httplib::Server::HandlerResponse::Handled;
            }
            if (!m_token.empty() && token_matches(req.get_param_value("token"), m_token)) {
                // The page's own files (<script src>, <link href>) carry no query: the cookie
                // covers them.
                res.set_header("Set-Cookie", std::string(kTokenCookie) + "=" + m_token +
                                                 "; HttpOnly; SameSite=Strict; Path=/");
            }
            return httplib::Server::HandlerResponse::Unhandled;
        });
    server.set_expect_100_continue_handler(
        [refusal_of](const httplib::Request& req, httplib::Response& res) {
            if (const auto refusal = refusal_of(req)) {
                send_refusal(res, *refusal);
                return refusal->status;
            }
            return 100;
        });
    // An exception that is not a tirpol::Error is a bug: its text goes to the operator's terminal,
    // never to the client (httplib's default puts it in a response header).
    server.set_exception_handler([](const httplib::Request& req, httplib::Response& res,
                                    std::exception_ptr ep) {
        std::string what = "unknown exception";
        try {
            std::rethrow_exception(ep);
        } catch (const std::exception& e) {
            what = e.what();
        } catch (...) {
        }
        spdlog::error("live view: {} {} failed: {}", req.method, req.path, what);
        res.status = 500;
        res.set_content(error_body("internal error (details in the terminal running tirpol live)"),
                        "application/json");
    });

    auto serve_file = [](const std::string& name, const char* type) {
        return [name, type](const httplib::Request&, httplib::Response& res) {
            res.set_content(std::string(embedded_file(name)), type);
        };
    };
    server.Get("/", serve_file("index.html", "text/html; charset=utf-8"));
    server.Get("/live.js", serve_file("live.js", "text/javascript; charset=utf-8"));
    server.Get("/live.css", serve_file("live.css", "text/css; charset=utf-8"));

    server.Get("/api/describe", [&view](const httplib::Request&, httplib::Response& res) {
        send_json(res, view.describe());
    });
    server.Get("/api/status", [&view](const httplib::Request&, httplib::Response& res) {
        send_json(res, view.status());
    });
    server.Get("/api/frame", image_handler([&view](std::uint64_t after) {
                   return view.frame_after(after, kLongPoll);
               }));
    server.Get("/api/stokes", image_handler([&view](std::uint64_t after) {
                   return view.stokes_after(after, kLongPoll);
               }));
    server.Get("/api/region", [&view](const httplib::Request& req, httplib::Response& res) {
        try {
            const RegionRequest r =
                parse_region_request(param(req, "x0"), param(req, "y0"), param(req, "x1"),
                                     param(req, "y1"), param(req, "dolp_min"));
            send_json(res, view.region(r.region, r.dolp_min));
        } catch (const Error& e) {
            send_error(res, e);
        }
    });
    const std::size_t max_body = options.limits.max_body_bytes;
    server.Post("/api/capture/start",
                [&view, max_body](const httplib::Request&, httplib::Response& res,
                                  const httplib::ContentReader& reader) {
                    const auto body = read_body(reader, res, max_body);
                    if (!body) return;
                    try {
                        view.capture().start(parse_capture_request(*body));
                        send_json(res, view.status());
                    } catch (const Error& e) {
                        send_error(res, e);
                    }
                });
    server.Post("/api/capture/stop",
                [&view, max_body](const httplib::Request&, httplib::Response& res,
                                  const httplib::ContentReader& reader) {
                    if (!read_body(reader, res, max_body)) return;
                    try {
                        view.capture().stop();
                        send_json(res, view.status());
                    } catch (const Error& e) {
                        send_error(res, e);
                    }
                });
    server.Post("/api/snapshot", [&view, max_body](const httplib::Request&, httplib::Response& res,
                                                   const httplib::ContentReader& reader) {
        if (!read_body(reader, res, max_body)) return;
        try {
            send_json(res, view.snapshot());
        } catch (const Error& e) {
            send_error(res, e);
        }
    });
    const std::size_t max_clients = options.limits.max_observation_clients;
    server.Post("/api/observations", [this, max_body, max_clients](
                                         const httplib::Request& req, httplib::Response& res,
                                         const httplib::ContentReader& reader) {
        const auto text = read_body(reader, res, max_body);
        if (!text) return;
        nlohmann::json body;
        try {
            body = parse_observation(param(req, "client"), *text);
        } catch (const Error& e) {
            send_error(res, e);
            return;
        }
        std::lock_guard lock(m_impl->observations_mutex);
        const std::string client = req.get_param_value("client");
        if (!m_impl->observations.count(client) && m_impl->observations.size() >= max_clients) {
            send_refusal(
                res, {429, fmt::format("observations: {} clients already report; no more are kept",
                                       max_clients)});
            return;
        }
        m_impl->observations[client] = std::move(body);
        send_json(res, {{"ok", true}});
    });
    server.Get("/api/observations", [this](const httplib::Request&, httplib::Response& res) {
        std::lock_guard lock(m_impl->observations_mutex);
        send_json(res, nlohmann::json(m_impl->observations));
    });

    m_port = options.port == 0
                 ? server.bind_to_any_port(options.bind_address)
                 : (server.bind_to_port(options.bind_address, options.port) ? options.port : -1);
    if (m_port <= 0)
        fail("live view: cannot listen on {} port {} (in use, or not an address of this machine)",
             options.bind_address, options.port);
    server.set_listen_backlog(static_cast<int>(options.limits.max_connections) * 2);
    m_impl->policy.emplace(allowed_hosts(options.bind_address, m_port), m_token, options.limits);
}

LiveServer::~LiveServer() { stop(); }

std::string LiveServer::url() const { return urls().front(); }

std::vector<std::string> LiveServer::urls() const {
    std::vector<std::string> urls;
    for (const std::string& address : reachable_addresses(m_bind_address)) {
        const std::string host =
            address.find(':') != std::string::npos ? "[" + address + "]" : address;
        std::string url = "http://" + host + ":" + std::to_string(m_port) + "/";
        if (!m_token.empty()) url += "?token=" + m_token;
        urls.push_back(std::move(url));
    }
    return urls;
}

void LiveServer::run() { m_impl->server.listen_after_bind(); }

void LiveServer::stop() { m_impl->server.stop(); }

void LiveServer::run_until_interrupted() {
    const InterruptSignals interrupt;
    const InterruptWatcher watcher(interrupt.flag(),
                                   [this] {
                                       stop();
                                       return true;
                                   },
                                   {});
    run();
}

std::string LiveServer::listening_text() const {
    const std::vector<std::string> addresses = urls();
    std::string text = fmt::format("tirpol live: open {}\n", addresses.front());
    for (std::size_t i = 1; i < addresses.size(); ++i)
        text += fmt::format("tirpol live: or, from another network of this machine, {}\n",
                            addresses[i]);
    if (!m_token.empty())
        text += fmt::format("tirpol live: bound to {}: every request needs the access token {}\n",
                            m_bind_address, m_token);
    return text;
}

std::size_t LiveServer::open_connections() const { return m_impl->server.open_connections(); }

}  // namespace tirpol::live
