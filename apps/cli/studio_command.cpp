// `exemplar studio`: flags, the signal wait and the exit; the server is apps/studio.

#include <pthread.h>
#include <signal.h>

#include <cmath>
#include <thread>

#include "commands.hpp"

namespace exemplar::cli {

StudioCommand::StudioCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "studio", "Local web app: sketch with suggestions, paint, run jobs (docs/studio.md)");
    app_->footer(
        "Open the printed address in a browser; Ctrl-C stops the server (running jobs are "
        "cancelled, nothing half-written is left).\nExample: exemplar studio --workspace "
        "~/paintings");
    app_->add_option("--port", options_.port, "TCP port (0..65535; 0 picks a free one)")
        ->capture_default_str();
    app_->add_option("--bind", options_.bind,
                     "Address to listen on; the app has no login, so any other address than "
                     "127.0.0.1 lets that network read and write the workspace")
        ->capture_default_str();
    app_->add_option("--workspace", options_.workspace,
                     "Folder the app reads and writes (created if missing); nothing outside it "
                     "is reachable")
        ->capture_default_str();
    app_->add_option("--max-upload-mb", max_upload_mib_, "Largest upload in MiB (0.001..1024)")
        ->capture_default_str();
    app_->add_option("--max-jobs", options_.max_jobs_per_client,
                     "Jobs running at once per browser tab (1..16)")
        ->capture_default_str();
    app_->add_option("--threads", options_.threads, "Threads per library call (0 = all cores)")
        ->capture_default_str();
}

Status StudioCommand::run(const Streams& streams) const {
    if (!(max_upload_mib_ >= 0.001 && max_upload_mib_ <= 1024.0)) {
        return invalid_argument("--max-upload-mb: " + std::to_string(max_upload_mib_) +
                                " is invalid (must be 0.001..1024)");
    }
    studio::StudioOptions options = options_;
    options.max_upload_bytes = static_cast<std::size_t>(std::llround(max_upload_mib_ * 1048576.0));
    // SIGINT and SIGTERM are blocked before any thread starts (threads inherit the mask) and
    // taken by sigwait below, so no handler runs inside a request and shutdown is ordinary code.
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    sigset_t previous;
    pthread_sigmask(SIG_BLOCK, &signals, &previous);
    auto server = studio::StudioServer::create(options);
    if (!server.ok()) {
        pthread_sigmask(SIG_SETMASK, &previous, nullptr);
        return server.status();
    }
    std::thread serving([&] { (*server)->run(); });
    streams.out << "exemplar studio: http://" << options.bind << ":" << (*server)->port()
                << "/ (workspace " << (*server)->workspace() << ")" << std::endl;
    int signal_number = 0;
    sigwait(&signals, &signal_number);
    streams.err << "exemplar studio: stopping (" << (signal_number == SIGINT ? "SIGINT" : "SIGTERM")
                << ")" << std::endl;
    (*server)->shutdown();
    serving.join();
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
    return Status::ok();
}

}  // namespace exemplar::cli
