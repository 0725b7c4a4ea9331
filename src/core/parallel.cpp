#include "exemplar/core/parallel.hpp"

#include <algorithm>

#if EXEMPLAR_USE_TBB
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#else
#include <atomic>
#include <thread>
#include <vector>
#endif

namespace exemplar {

#if EXEMPLAR_USE_TBB

int resolve_threads(int threads) {
    if (threads > 0) return threads;
    return std::max(1, tbb::info::default_concurrency());
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
    tbb::task_arena arena(n);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(begin, end, static_cast<std::size_t>(grain)),
                          [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
    });
}

#else  // Plain std::thread backend: fully visible to ThreadSanitizer (the tsan preset uses it).

int resolve_threads(int threads) {
    if (threads > 0) return threads;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
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
    std::atomic<int> next{begin};
    auto work = [&] {
        for (int b = next.fetch_add(grain); b < end; b = next.fetch_add(grain)) {
            body(b, std::min(end, b + grain));
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < n; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
}

#endif

}  // namespace exemplar
