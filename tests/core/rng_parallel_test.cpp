#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"

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

}  // namespace
}  // namespace exemplar
