#pragma once
/// \file
/// How a long-running library call is executed: thread count, progress reporting and
/// cancellation. Passed explicitly; there are no hidden globals.

#include <atomic>
#include <functional>
#include <string_view>

namespace exemplar {

/// One progress report. `fraction` is the overall completion of the whole call in [0, 1].
struct ProgressEvent {
    std::string_view stage;  ///< e.g. "search", "vote", "usage", "level".
    int level = 0;           ///< Pyramid level, 0 = coarsest.
    int levels = 0;          ///< Number of pyramid levels.
    int iteration = 0;       ///< EM iteration within the level.
    int iterations = 0;      ///< EM iterations on this level.
    double fraction = 0.0;   ///< Overall completion in [0, 1].
};

using ProgressSink = std::function<void(const ProgressEvent&)>;

/// Shared flag a caller sets to stop a running call; the call then returns ErrorCode::Cancelled.
class CancelToken {
public:
    void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
    bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }

private:
    std::atomic<bool> cancelled_{false};
};

/// Execution settings of one call.
struct RunContext {
    RunContext() = default;
    /// A context with only a thread count set.
    explicit RunContext(int thread_count) : threads(thread_count) {}

    int threads = 0;                      ///< 0 = all cores, 1 = run inline on the caller.
    ProgressSink progress;                ///< Optional; called from the caller's thread.
    const CancelToken* cancel = nullptr;  ///< Optional.

    bool cancelled() const { return cancel != nullptr && cancel->cancelled(); }
    void report(const ProgressEvent& event) const {
        if (progress) progress(event);
    }
    /// This context for a part of the call (a frame of a range, one of several syntheses):
    /// the same threads and cancel token, and progress whose fraction f is reported as
    /// (done + f·size) / total of this call (no progress if this context has none).
    RunContext part(double done, double size, double total) const {
        RunContext sub = *this;
        if (progress) {
            sub.progress = [sink = progress, done, size, total](const ProgressEvent& event) {
                ProgressEvent overall = event;
                overall.fraction = (done + event.fraction * size) / total;
                sink(overall);
            };
        }
        return sub;
    }
};

}  // namespace exemplar
