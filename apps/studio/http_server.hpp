#pragma once
// The studio's HTTP server behind a small interface, implemented with cpp-httplib in one plugin,
// libexemplar_http.so (http_plugin.cpp), loaded when `exemplar studio` starts: cpp-httplib links
// OpenSSL, Brotli and zlib, about 4 MiB resident before main() in every process that maps them
// (`exemplar --version` peaked at 10.9 instead of 6.7 MiB with it linked in). Both sides are
// compiled from this header by one build; kPlugin.abi_version rejects a plugin from another.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "plugin_loader.hpp"

namespace exemplar::plugin::http {

/// Raise abi_version whenever the types below change.
inline constexpr PluginSpec kPlugin{"libexemplar_http.so", "exemplar_http_entry", 2,
                                    "the studio's HTTP server"};

/// A request as a handler sees it: the path decoded, the route's regex groups in `matches`.
struct Request {
    std::string method;
    std::string path;
    std::string body;
    std::vector<std::string> matches;            ///< [0] the whole path, then the groups.
    std::map<std::string, std::string> headers;  ///< Names in lower case.
    std::multimap<std::string, std::string> params;

    /// The header's value ("" if absent); `name` in any case.
    std::string header(std::string name) const {
        for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        const auto it = headers.find(name);
        return it == headers.end() ? std::string() : it->second;
    }
    bool has_param(const std::string& name) const { return params.count(name) > 0; }
};

/// Produces a streamed body piece by piece: appends the next piece to `chunk` (may append
/// nothing and return true to be asked again) and returns false after the last one.
using Stream = std::function<bool(std::string& chunk)>;

/// The answer a handler fills in.
struct Response {
    int status = 200;
    std::string body;
    std::string content_type;
    std::vector<std::pair<std::string, std::string>> headers;
    /// Set for a streamed body (chunked transfer, e.g. server-sent events); `body` is unused.
    Stream stream;

    void set_content(std::string content, std::string type) {
        body = std::move(content);
        content_type = std::move(type);
    }
    void set_header(std::string name, std::string value) {
        headers.emplace_back(std::move(name), std::move(value));
    }
};

using Handler = std::function<void(const Request&, Response&)>;

/// Settings fixed when the server is made.
struct ServerOptions {
    std::size_t max_body_bytes = std::size_t{32} << 20;  ///< Larger bodies get 413 unread.
    int worker_threads = 32;  ///< Open connections served at once (streams hold one each).
    int keep_alive_s = 1;     ///< Idle keep-alive connections close after this (shutdown waits).
};

/// An HTTP/1.1 server.
class Server {
public:
    virtual ~Server() = default;
    /// Adds a route: `method` "GET", "POST" or "PUT", `pattern` an ECMAScript regex matched
    /// against the whole path.
    virtual void route(const std::string& method, const std::string& pattern, Handler handler) = 0;
    /// Called before routing with the request's headers (no body, no matches yet); answers
    /// itself and returns true to skip the route.
    virtual void set_gate(std::function<bool(const Request&, Response&)> gate) = 0;
    /// Binds `host`:`port` (0: any free port); the port bound, or -1.
    virtual int bind(const std::string& host, int port) = 0;
    /// Serves until `stop` (from another thread).
    virtual void listen() = 0;
    virtual void stop() = 0;
};

/// What the plugin's entry point returns; `abi_version` first (plugin_loader.hpp).
struct Entry {
    int abi_version;
    std::unique_ptr<Server> (*new_server)(const ServerOptions& options);
};

}  // namespace exemplar::plugin::http
