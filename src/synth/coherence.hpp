#pragma once
// The coherence sums of the weighted vote (vote_weights) for a field without rotations, one row
// at a time: a Highway kernel with runtime dispatch, the per-pixel loop of vote.cpp its
// definition (VoteWeights.TabulatedCoherenceEqualsReferenceExactly compares them bit for bit).

#include <cstddef>
#include <cstdint>

#include "exemplar/synth/nnf.hpp"

namespace exemplar::synth {

/// Where the coherence sums of row `y` of an unrotated field come from.
struct CoherenceRow {
    const Match* matches = nullptr;        ///< The field (width x height, row-major).
    const std::uint8_t* active = nullptr;  ///< Entries that vote (nullptr: every matched one).
    int width = 0, height = 0;
    int radius = 0;  ///< Patch radius r: the neighbours within (2r + 1)² of a pixel.
    int reach = 0;   ///< Coordinate differences beyond ±reach count the factor of ±(reach + 1).
    /// Per patch offset (dx, dy), row-major over the (2r + 1)² offsets, `table_row` factors:
    /// those of the differences -reach - 1 .. reach + 1 (the factor of angle 0's table).
    const double* table = nullptr;
    std::size_t table_row = 0;
};

/// For every pixel x of row y that votes (active, matched): adds to agree[x], neighbour offset
/// after neighbour offset (dy, then dx, each from -r to r), the products of the x and y factors
/// of the neighbours inside the field that vote: X(dx, dy)[p.x − q.x] · X(−dy, dx)[p.y − q.y]
/// with the differences clamped to ±(reach + 1), as vote.cpp's loop adds them (two roundings,
/// never fused). Leaves the other entries of agree as they are.
void add_coherence_row(const CoherenceRow& field, int y, double* agree);

}  // namespace exemplar::synth
