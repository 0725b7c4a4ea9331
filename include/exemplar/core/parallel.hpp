#pragma once
/// \file
/// Parallel loops over an index range on oneTBB, with an explicit thread count.
/// The body must write only to outputs owned by its index so that results do not depend on
/// scheduling; exemplar's determinism rests on that.

#include <functional>

namespace exemplar {

/// Number of threads `threads` resolves to (0 = hardware concurrency).
int resolve_threads(int threads);

/// Calls `body(begin_i, end_i)` on disjoint sub-ranges covering [begin, end), using up to
/// `threads` threads (0 = all cores, 1 = inline). `grain` is the minimum sub-range length.
void parallel_for_ranges(int begin, int end, int threads, int grain,
                         const std::function<void(int, int)>& body);

/// Calls `body(i)` for every i in [begin, end) in parallel.
template <typename Body>
void parallel_for(int begin, int end, int threads, Body&& body, int grain = 1) {
    parallel_for_ranges(begin, end, threads, grain, [&](int b, int e) {
        for (int i = b; i < e; ++i) body(i);
    });
}

}  // namespace exemplar
