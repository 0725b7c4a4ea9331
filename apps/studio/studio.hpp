#pragma once
/// \file
/// `exemplar studio`'s server (docs/studio.md): the single-page app embedded in the binary and a
/// JSON API over the library's interactive verbs, confined to one workspace folder.

#include <cstddef>
#include <memory>
#include <string>

#include "exemplar/core/status.hpp"

namespace exemplar::studio {

/// Settings of a studio server.
struct StudioOptions {
    /// Address to listen on. Default 127.0.0.1: the app has no authentication.
    std::string bind = "127.0.0.1";
    /// TCP port; 0 picks a free one (StudioServer::port() tells which). Default 8642.
    int port = 8642;
    /// The folder every client path is relative to (created if missing). Default ".".
    std::string workspace = ".";
    /// Largest upload in bytes. Default 32 MiB.
    std::size_t max_upload_bytes = std::size_t{32} << 20;
    /// Jobs running at once per client. Default 2; 1..16.
    int max_jobs_per_client = 2;
    /// Threads of each library call (0 = all cores).
    int threads = 0;
    /// Finished jobs remembered (listings, late event streams); older ones are forgotten as
    /// new jobs start. Default 64; at least 1.
    std::size_t max_finished_jobs = 64;
    /// Clients (browser tabs) whose tool state (sketch, painting, brush) is kept; a new one
    /// beyond this replaces the one unused longest. Default 32; at least 1.
    std::size_t max_clients = 32;
};

/// A bound server; `run` serves until `shutdown`.
class StudioServer {
public:
    /// Opens the workspace and binds the port. IoError names the workspace or the address.
    static Result<std::unique_ptr<StudioServer>> create(const StudioOptions& options);
    ~StudioServer();
    StudioServer(const StudioServer&) = delete;
    StudioServer& operator=(const StudioServer&) = delete;

    /// The port bound (the chosen one when options.port was 0).
    int port() const;
    /// The canonical workspace folder.
    std::string workspace() const;
    /// Serves requests until `shutdown` is called (from another thread).
    void run();
    /// Refuses new requests, cancels every job and waits for their threads (a cancelled job
    /// writes nothing), ends the event streams and stops `run`. Safe to call more than once.
    void shutdown();

private:
    struct Impl;
    explicit StudioServer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace exemplar::studio
