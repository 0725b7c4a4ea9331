#include "exemplar/core/parallel.hpp"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace exemplar {

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

}  // namespace exemplar
