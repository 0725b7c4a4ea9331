#include "jobs.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

namespace exemplar::studio {

namespace {

using nlohmann::json;

std::string sse(const char* event, const json& data) {
    return std::string("event: ") + event + "\ndata: " + data.dump() + "\n\n";
}

// The progress sink's share of the log: a new event for each whole percent or new stage.
void record_progress(Job& job, const ProgressEvent& event) {
    std::lock_guard lock(job.mutex);
    const double fraction = std::clamp(event.fraction, 0.0, 1.0);
    if (std::floor(fraction * 100.0) == std::floor(job.fraction * 100.0) && !job.events.empty()) {
        return;
    }
    job.fraction = fraction;
    job.events.push_back(sse("progress", {{"fraction", fraction},
                                          {"stage", std::string(event.stage)},
                                          {"level", event.level},
                                          {"levels", event.levels}}));
    job.changed.notify_all();
}

}  // namespace

const char* to_string(JobState state) {
    switch (state) {
        case JobState::Running: return "running";
        case JobState::Done: return "done";
        case JobState::Failed: return "failed";
        case JobState::Cancelled: return "cancelled";
    }
    return "unknown";
}

std::string Job::summary() const {
    std::lock_guard lock(mutex);
    return json{
        {"id", id},         {"kind", kind},   {"state", to_string(state)}, {"fraction", fraction},
        {"output", output}, {"error", error}, {"outputs", outputs}}
        .dump();
}

int JobManager::running(const std::string& client) const {
    int count = 0;
    for (const auto& [id, job] : jobs_) {
        std::lock_guard lock(job->mutex);
        if (job->client == client && job->state == JobState::Running) ++count;
    }
    return count;
}

Result<std::shared_ptr<Job>> JobManager::start(const std::string& client, const std::string& kind,
                                               const std::string& output, JobWork work) {
    std::lock_guard lock(mutex_);
    if (shut_down_) return unsupported("the studio is shutting down");
    prune();
    if (running(client) >= max_per_client_) {
        return unsupported("too many jobs: " + std::to_string(max_per_client_) +
                           " are running for this client (cancel one or wait)");
    }
    auto job = std::make_shared<Job>();
    job->id = std::to_string(next_id_++);
    job->kind = kind;
    job->client = client;
    job->output = output;
    job->events.push_back(sse("progress", {{"fraction", 0.0}, {"stage", "start"}}));
    jobs_[next_id_ - 1] = job;
    // The thread holds its own reference; shutdown joins it.
    job->thread = std::thread([job, work = std::move(work), threads = threads_] {
        RunContext context(threads);
        context.cancel = &job->cancel;
        context.progress = [&job](const ProgressEvent& event) { record_progress(*job, event); };
        const OutputSink wrote = [&job](int frame, const std::string& path) {
            std::lock_guard frame_lock(job->mutex);
            job->outputs.push_back(path);
            job->events.push_back(sse("frame", {{"frame", frame}, {"path", path}}));
            job->changed.notify_all();
        };
        const Status status = work(context, wrote);
        std::lock_guard job_lock(job->mutex);
        json end;
        if (status.is_ok()) {
            if (job->outputs.empty()) job->outputs.push_back(job->output);
            job->state = JobState::Done;
            job->fraction = 1.0;
            end = {{"state", "done"}, {"output", job->output}};
        } else {
            job->state =
                status.code() == ErrorCode::Cancelled ? JobState::Cancelled : JobState::Failed;
            job->error = status.message();
            end = {{"state", to_string(job->state)}, {"error", job->error}};
        }
        job->events.push_back(sse("end", end));
        job->changed.notify_all();
    });
    return job;
}

void JobManager::prune() {
    std::vector<std::size_t> finished;  // ids, oldest first
    for (const auto& [id, job] : jobs_) {
        std::lock_guard job_lock(job->mutex);
        if (job->state != JobState::Running) finished.push_back(id);
    }
    if (finished.size() <= kept_finished_) return;
    finished.resize(finished.size() - kept_finished_);
    for (const std::size_t id : finished) {
        const auto job = jobs_.at(id);
        // The thread has recorded its end and only returns now.
        if (job->thread.joinable()) job->thread.join();
        jobs_.erase(id);
    }
}

std::shared_ptr<Job> JobManager::find(const std::string& id) const {
    std::size_t number = 0;
    const auto [end, error] = std::from_chars(id.data(), id.data() + id.size(), number);
    // One spelling per id ("011" is no job).
    if (error != std::errc() || end != id.data() + id.size() || std::to_string(number) != id)
        return nullptr;
    std::lock_guard lock(mutex_);
    const auto it = jobs_.find(number);
    return it == jobs_.end() ? nullptr : it->second;
}

std::vector<std::shared_ptr<Job>> JobManager::list() const {
    std::lock_guard lock(mutex_);
    std::vector<std::shared_ptr<Job>> out;
    for (const auto& [id, job] : jobs_) out.push_back(job);
    return out;
}

void JobManager::supersede(const std::string& client, const std::string& kind) {
    std::vector<std::shared_ptr<Job>> superseded;
    {
        std::lock_guard lock(mutex_);
        for (const auto& [id, job] : jobs_) {
            std::lock_guard job_lock(job->mutex);
            if (job->client == client && job->kind == kind && job->state == JobState::Running) {
                superseded.push_back(job);
            }
        }
    }
    for (const auto& job : superseded) job->cancel.cancel();
    for (const auto& job : superseded) {
        std::unique_lock lock(job->mutex);
        job->changed.wait(lock, [&] { return job->state != JobState::Running; });
    }
}

Result<std::shared_ptr<Job>> JobManager::replace(const std::string& client, const std::string& kind,
                                                 const std::string& output, JobWork work) {
    // Without the client's lock two posts could both cancel the old run and then both start;
    // with one lock for all clients, one client's wait for its cancelled run would hold up
    // every other client's replacement.
    std::shared_ptr<std::mutex> client_mutex;
    {
        std::lock_guard lock(mutex_);
        auto& slot = replace_mutexes_[client];
        if (!slot) slot = std::make_shared<std::mutex>();
        client_mutex = slot;
    }
    auto job = [&] {
        std::lock_guard lock(*client_mutex);
        supersede(client, kind);
        return start(client, kind, output, std::move(work));
    }();
    // The client's lock is forgotten when no other replacement holds it (copies are only made
    // under mutex_, so the count is settled here): the map stays as small as the clients
    // replacing at the moment.
    std::lock_guard lock(mutex_);
    const auto it = replace_mutexes_.find(client);
    if (it != replace_mutexes_.end() && it->second.use_count() == 2) replace_mutexes_.erase(it);
    return job;
}

void JobManager::shutdown() {
    std::map<std::size_t, std::shared_ptr<Job>> jobs;
    {
        std::lock_guard lock(mutex_);
        shut_down_ = true;
        jobs = jobs_;
    }
    for (auto& [id, job] : jobs) job->cancel.cancel();
    for (auto& [id, job] : jobs) {
        if (job->thread.joinable()) job->thread.join();
    }
}

}  // namespace exemplar::studio
