#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <string>
#include <vector>

#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/core/run_context.hpp"

namespace exemplar {
namespace {

TEST(KeyedRng, SameKeySameStream) {
    KeyedRng a(7, 1, 2, 3), b(7, 1, 2, 3), c(7, 1, 2, 4);
    bool differs = false;
    for (int i = 0; i < 16; ++i) {
        const auto va = a.next();
        EXPECT_EQ(va, b.next());
        differs |= va != c.next();
    }
    EXPECT_TRUE(differs);
}

TEST(KeyedRng, RangesStayInBounds) {
    KeyedRng r(42, 0);
    std::vector<int> hist(5, 0);
    for (int i = 0; i < 5000; ++i) {
        const float u = r.uniform();
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        const int v = r.range(-2, 2);
        ASSERT_GE(v, -2);
        ASSERT_LE(v, 2);
        ++hist[v + 2];
    }
    for (int h : hist) EXPECT_GT(h, 800);  // roughly uniform: 1000 expected each
}

TEST(ParallelFor, CoversEveryIndexOnceForAnyThreadCount) {
    for (int threads : {1, 2, 3, 0}) {
        std::vector<std::atomic<int>> hits(1000);
        parallel_for(
            0, 1000, threads, [&](int i) { hits[i].fetch_add(1); }, 7);
        for (auto& h : hits) ASSERT_EQ(h.load(), 1) << "threads=" << threads;
    }
}

// Resident memory of this process, kB (Linux), or -1.
long resident_kb() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);) {
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    }
    return -1;
}

TEST(ParallelFor, RepeatedLoopsDoNotGrowMemory) {
    // A long run makes many thousands of parallel loops (a LazyFluids frame: ~300); with an
    // arena made per loop, oneTBB 2021.8 kept ~7 KB of each.
    std::vector<int> out(64);
    auto loops = [&](int n) {
        for (int k = 0; k < n; ++k) parallel_for(0, 64, 2, [&](int i) { out[i] = i + k; });
    };
    loops(500);  // warm up: threads, arenas
    const long before = resident_kb();
    if (before < 0) GTEST_SKIP() << "no /proc/self/status";
    loops(5000);
    const long growth = resident_kb() - before;
    std::printf("resident memory after 5000 more loops: %+ld kB\n", growth);
    EXPECT_LT(growth, 2048);  // it was ~35 MB
    EXPECT_EQ(out[63], 63 + 4999);
}

TEST(RunContext, APartMapsItsProgressOntoItsShareAndKeepsThreadsAndCancel) {
    CancelToken token;
    std::vector<ProgressEvent> seen;
    RunContext whole(3);
    whole.cancel = &token;
    whole.progress = [&](const ProgressEvent& e) { seen.push_back(e); };
    // Frame 2 of 4: its fractions land on 2/4..3/4 with the rest of the event kept.
    const RunContext frame = whole.part(2.0, 1.0, 4.0);
    EXPECT_EQ(frame.threads, 3);
    EXPECT_EQ(frame.cancel, &token);
    frame.report({.stage = "search", .level = 1, .fraction = 0.0});
    frame.report({.stage = "vote", .level = 2, .fraction = 0.5});
    frame.report({.stage = "end", .fraction = 1.0});
    ASSERT_EQ(seen.size(), 3u);
    EXPECT_EQ(seen[0].fraction, 0.5);
    EXPECT_EQ(seen[1].fraction, 0.625);
    EXPECT_EQ(seen[1].stage, "vote");
    EXPECT_EQ(seen[1].level, 2);
    EXPECT_EQ(seen[2].fraction, 0.75);
    // A part of a part: the second half of that frame.
    whole.part(2.0, 1.0, 4.0).part(0.5, 0.5, 1.0).report({.stage = "end", .fraction = 1.0});
    EXPECT_EQ(seen.back().fraction, 0.75);
    // No sink, no wrapping.
    EXPECT_FALSE(RunContext(2).part(0.0, 1.0, 2.0).progress);
}

}  // namespace
}  // namespace exemplar
