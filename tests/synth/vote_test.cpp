#include "vote.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace exemplar::synth {
namespace {

// A field mapping every pixel of a 20x20 target to the source shifted by (5, 3), all errors
// equal, with one stray match at (10, 10).
Nnf shifted_field_with_stray() {
    Nnf nnf(20, 20);
    for (int y = 0; y < 20; ++y) {
        for (int x = 0; x < 20; ++x) nnf.at(x, y) = Match{x + 5, y + 3, 0.0f, 0.5f};
    }
    nnf.at(10, 10) = Match{40, 2, 0.0f, 0.5f};
    return nnf;
}

// Coherence (Brushables eq. 6.8): inside a coherent region every patch of the 5x5 neighbourhood
// agrees (weight 25 x the error weight); the stray agrees only with itself, and its neighbours
// lose its vote. Without coherence, equal errors give equal weights. Thread counts agree.
TEST(VoteWeights, CoherenceCountsConsistentNeighbours) {
    const Nnf nnf = shifted_field_with_stray();
    const std::vector<float> plain = vote_weights(nnf, nullptr, 5, 0.0f, 1);
    const float error_weight = plain[0];
    EXPECT_NEAR(error_weight, 1.0f / 1.01f, 1e-6f);
    for (float w : plain) EXPECT_EQ(w, error_weight);
    const std::vector<float> coherent = vote_weights(nnf, nullptr, 5, 2.0f, 1);
    auto at = [&](int x, int y) {
        return coherent[static_cast<std::size_t>(y) * 20 + x] / error_weight;
    };
    EXPECT_NEAR(at(4, 4), 25.0f, 1e-4f);
    EXPECT_NEAR(at(10, 10), 1.0f, 1e-4f);   // the stray: only itself
    EXPECT_NEAR(at(11, 10), 24.0f, 1e-4f);  // its neighbours lose one vote
    EXPECT_NEAR(at(0, 0), 9.0f, 1e-4f);     // a corner sees 3x3 entries
    // A neighbour one pixel off counts exp(-1 / (2 sigma^2)).
    Nnf off = nnf;
    off.at(4, 5) = Match{4 + 5 + 1, 5 + 3, 0.0f, 0.5f};
    const std::vector<float> near = vote_weights(off, nullptr, 5, 2.0f, 1);
    EXPECT_NEAR(near[4 * 20 + 4] / error_weight, 24.0f + std::exp(-0.25f), 1e-4f);
    EXPECT_EQ(vote_weights(nnf, nullptr, 5, 2.0f, 2), coherent);
}

}  // namespace
}  // namespace exemplar::synth
