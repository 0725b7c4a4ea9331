#include "exemplar/core/parallel.hpp"

#include <algorithm>

#if EXEMPLAR_USE_TBB
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <map>
#include <memory>
#include <mutex>
#else
#include <atomic>
#include <thread>
#include <vector>
#endif

namespace exemplar {

namespace {

#if EXEMPLAR_USE_TBB

int hardware_threads() {
    return tbb::info::default_concurrency();
}

// One arena per thread count, made on first use and kept for the process: oneTBB 2021.8
// (Debian bookworm) keeps ~7 KB per task_arena constructed and destroyed, so an arena per call
// made a long run's memory grow with its number of parallel loops (a 60-frame LazyFluids run:
// +2 MB per frame at 2 threads). Never destroyed, so no shutdown-order questions.
tbb::task_arena& arena_for(int threads) {
    static std::mutex mutex;
    static auto* arenas = new std::map<int, std::unique_ptr<tbb::task_arena>>();
    const std::lock_guard<std::mutex> lock(mutex);
    std::unique_ptr<tbb::task_arena>& arena = (*arenas)[threads];
    if (!arena) arena = std::make_unique<tbb::task_arena>(threads);
    return *arena;
}

void run_parallel(int begin, int end, int threads, int grain,
                  const std::function<void(int, int)>& body) {
    tbb::task_arena& arena = arena_for(threads);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(begin, end, static_cast<std::size_t>(grain)),
                          [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
    });
}

#else  // Plain std::thread backend: fully visible to ThreadSanitizer (the tsan preset uses it).

int hardware_threads() {
    return static_cast<int>(std::thread::hardware_concurrency());
}

void run_parallel(int begin, int end, int threads, int grain,
                  const std::function<void(int, int)>& body) {
    std::atomic<int> next{begin};
    auto work = [&] {
        for (int b = next.fetch_add(grain); b < end; b = next.fetch_add(grain)) {
            body(b, std::min(end, b + grain));
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
}

#endif

}  // namespace

int resolve_threads(int threads) {
    if (threads > 0) return threads;
    return std::max(1, hardware_threads());
}

void parallel_for_ranges(int begin, int end, int threads, int grain,
                         const std::function<void(int, int)>& body) {
    if (end <= begin) return;
    const int n = resolve_threads(threads);
    grain = std::max(1, grain);
    if (n == 1 || end - begin <= grain) {
        body(begin, end);
        return;
    }
    run_parallel(begin, end, n, grain, body);
}

}  // namespace exemplar
