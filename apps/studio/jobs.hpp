#pragma once
// Long library calls of the studio (docs/studio.md, "Jobs"): each runs on its own thread with a
// RunContext whose progress goes to the job's event log and whose CancelToken the client (or
// shutdown) sets. Event streams replay the log and then wait for more.

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::studio {

enum class JobState { Running, Done, Failed, Cancelled };
const char* to_string(JobState state);

/// One job. Its fields are read under `mutex`.
struct Job {
    std::string id, kind, client, output;
    CancelToken cancel;
    mutable std::mutex mutex;
    std::condition_variable changed;
    JobState state = JobState::Running;
    double fraction = 0.0;
    std::string error;
    /// Files the job has finished (workspace paths), in the order written: the frames of a range.
    std::vector<std::string> outputs;
    /// Server-sent events ("event: ...\ndata: ...\n\n"), in order; the last is `end`.
    std::vector<std::string> events;
    std::thread thread;

    /// The job as JSON text for listings.
    std::string summary() const;
};

/// What a job's work reports when a file of it is finished (written atomically): the frame
/// number and the file's workspace path. It adds a `frame` event and lists the file.
using OutputSink = std::function<void(int frame, const std::string& path)>;

/// The work of a job: one library call and its atomic writes. It returns the call's status.
using JobWork = std::function<Status(const RunContext&, const OutputSink&)>;

class JobManager {
public:
    /// Finished jobs kept for listings and late event streams by default; older ones are
    /// forgotten (their threads joined) as new jobs start, so memory stays bounded.
    static constexpr std::size_t kKeptFinished = 64;

    /// `max_per_client` running jobs per client at most; `threads` for each call's RunContext;
    /// at most `kept_finished` finished jobs remembered.
    JobManager(int max_per_client, int threads, std::size_t kept_finished = kKeptFinished)
        : max_per_client_(max_per_client), threads_(threads), kept_finished_(kept_finished) {}
    ~JobManager() { shutdown(); }
    JobManager(const JobManager&) = delete;
    JobManager& operator=(const JobManager&) = delete;

    /// Starts `work` on a new thread. Fails (Unsupported, "too many jobs") when the client
    /// already runs `max_per_client` jobs, or after shutdown. Forgets the oldest finished jobs
    /// beyond the bound first (a stream still following one keeps it alive until it ends).
    Result<std::shared_ptr<Job>> start(const std::string& client, const std::string& kind,
                                       const std::string& output, JobWork work);
    /// Cancels `client`'s running jobs of `kind`, waits until they have ended and starts `work`
    /// as start() does, as one step per client: of a client's replacements posted at the same
    /// moment one runs, the last, and the others end cancelled; other clients' replacements do
    /// not wait for it. A tool that runs again on every change (StyLit) keeps
    /// one run, the latest.
    Result<std::shared_ptr<Job>> replace(const std::string& client, const std::string& kind,
                                         const std::string& output, JobWork work);
    /// The job with id `id`, or null.
    std::shared_ptr<Job> find(const std::string& id) const;
    /// The jobs remembered, in the order they were started.
    std::vector<std::shared_ptr<Job>> list() const;
    /// Cancels every job, joins their threads and refuses new ones.
    void shutdown();

private:
    int running(const std::string& client) const;
    /// Cancels `client`'s running jobs of `kind` and waits until they have ended.
    void supersede(const std::string& client, const std::string& kind);
    /// Joins and drops the oldest finished jobs beyond kept_finished_ (under mutex_).
    void prune();

    const int max_per_client_;
    const int threads_;
    const std::size_t kept_finished_;
    mutable std::mutex mutex_;
    /// Per client, held across replace()'s cancel, wait and start (not mutex_, which listings
    /// need meanwhile), so one client's wait does not delay another's. Under mutex_.
    std::map<std::string, std::shared_ptr<std::mutex>> replace_mutexes_;
    /// By id: numbers in the order of creation.
    std::map<std::size_t, std::shared_ptr<Job>> jobs_;
    std::size_t next_id_ = 1;
    bool shut_down_ = false;
};

}  // namespace exemplar::studio
