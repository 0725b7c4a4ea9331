// http_server.hpp's Server with cpp-httplib 0.11 (Debian libcpp-httplib-dev), the only binary of
// the `exemplar` command that links it (and through it OpenSSL, Brotli and zlib).

#include <httplib.h>

#include "http_server.hpp"

namespace exemplar::plugin::http {

namespace {

Request request_of(const httplib::Request& in, const std::string& method) {
    Request out;
    out.method = method;
    out.path = in.path;
    out.body = in.body;
    for (const auto& m : in.matches) out.matches.push_back(m.str());
    for (const auto& [name, value] : in.headers) {
        std::string lower = name;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        out.headers.emplace(lower, value);
    }
    for (const auto& p : in.params) out.params.insert(p);
    return out;
}

void apply(Response& answer, httplib::Response& out) {
    out.status = answer.status;
    for (const auto& [name, value] : answer.headers) out.set_header(name.c_str(), value);
    if (answer.stream) {
        out.set_chunked_content_provider(
            answer.content_type,
            [stream = std::move(answer.stream)](std::size_t, httplib::DataSink& sink) {
                std::string chunk;
                const bool more = stream(chunk);
                if (!chunk.empty() && !sink.write(chunk.data(), chunk.size())) return false;
                if (!more) sink.done();
                return true;
            });
    } else {
        out.set_content(std::move(answer.body), answer.content_type.c_str());
    }
}

class HttplibServer : public Server {
public:
    explicit HttplibServer(const ServerOptions& options) {
        const auto threads = static_cast<std::size_t>(options.worker_threads);
        server_.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
        server_.set_keep_alive_timeout(options.keep_alive_s);
        server_.set_payload_max_length(options.max_body_bytes);
        server_.set_tcp_nodelay(true);
        // httplib's default sets SO_REUSEPORT, with which a second server binds the same port
        // and the kernel shares the connections between the two. SO_REUSEADDR alone still lets
        // a restarted studio bind while the old connections linger in TIME_WAIT.
        server_.set_socket_options([](socket_t sock) {
            int yes = 1;
            setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
        });
    }

    void route(const std::string& method, const std::string& pattern, Handler handler) override {
        auto wrapped = [method, handler = std::move(handler)](const httplib::Request& in,
                                                              httplib::Response& out) {
            Response answer;
            handler(request_of(in, method), answer);
            apply(answer, out);
        };
        if (method == "GET") {
            server_.Get(pattern, wrapped);
        } else if (method == "POST") {
            server_.Post(pattern, wrapped);
        } else if (method == "PUT") {
            server_.Put(pattern, wrapped);
        }
    }

    void set_gate(std::function<bool(const Request&, Response&)> gate) override {
        server_.set_pre_routing_handler(
            [gate = std::move(gate)](const httplib::Request& in, httplib::Response& out) {
                Response answer;
                if (!gate(request_of(in, in.method), answer)) {
                    return httplib::Server::HandlerResponse::Unhandled;
                }
                apply(answer, out);
                return httplib::Server::HandlerResponse::Handled;
            });
    }

    int bind(const std::string& host, int port) override {
        if (port == 0) return server_.bind_to_any_port(host);
        return server_.bind_to_port(host, port) ? port : -1;
    }

    void listen() override { server_.listen_after_bind(); }
    void stop() override { server_.stop(); }

private:
    httplib::Server server_;
};

std::unique_ptr<Server> new_server(const ServerOptions& options) {
    return std::make_unique<HttplibServer>(options);
}

constexpr Entry kEntry{kPlugin.abi_version, &new_server};

}  // namespace

}  // namespace exemplar::plugin::http

// The plugin's one exported symbol (http::kPlugin).
extern "C" __attribute__((visibility("default"))) const exemplar::plugin::http::Entry*
exemplar_http_entry() {
    return &exemplar::plugin::http::kEntry;
}
