// SynthesisInput::candidate_nnfs: extra candidate matches tried at the start of every level and
// in every PatchMatch iteration of the searches.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "exemplar/synth/synthesize.hpp"
#include "level_builder.hpp"
#include "patchmatch.hpp"
#include "test_images.hpp"
#include "usage.hpp"

namespace exemplar {
namespace {

constexpr int kSide = 32, kStyleW = 100, kStyleH = 52, kDx = 2, kDy = 8, kCopyX = 60;

// The style (and its guide) holds the region at (kDx, kDy) twice: once there and once at
// (kCopyX, kDy), with a 2-pixel margin so that every 5x5 patch is identical in both. The
// target's guide is that region: pixel (x, y) matches (x + kDx, y + kDy) and (x + kCopyX,
// y + kDy) exactly, and a search from a random start ends up with a mix of both.
Image with_copy(Image im) {
    for (int y = kDy - 2; y < kDy + kSide + 2; ++y)
        for (int x = kDx - 2; x < kDx + kSide + 2; ++x)
            for (int c = 0; c < im.channels(); ++c) im.at(x - kDx + kCopyX, y, c) = im.at(x, y, c);
    return im;
}

SynthesisInput crop_input() {
    SynthesisInput in;
    in.style = with_copy(testing::texture(kStyleW, kStyleH, 3, 31));
    const Image guide = with_copy(testing::texture(kStyleW, kStyleH, 2, 32, 0.5f));
    Image crop(kSide, kSide, 2);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
            for (int c = 0; c < 2; ++c) crop.at(x, y, c) = guide.at(x + kDx, y + kDy, c);
    in.guides.push_back(GuidePair{"guide", guide, crop, 8.0f, {}});
    return in;
}

// The exact answer in the copy.
Nnf exact_field() {
    Nnf exact(kSide, kSide);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) exact.at(x, y) = Match{x + kCopyX, y + kDy, 0.0f, 0.0f};
    return exact;
}

// One level, one EM iteration of one PatchMatch iteration: too little for a random start.
SynthesisOptions short_run() {
    SynthesisOptions o;
    o.levels = 1;
    o.em_iterations = 1;
    o.finest_em_iterations = 1;
    o.search_iterations = 1;
    o.final_pass_iterations = 0;
    o.usage = UsageStrategy::None;
    return o;
}

// Patch centres: the final field marks the 2-pixel border "no match".
constexpr int kLo = 2, kHi = kSide - 2;

int exact_matches(const Nnf& nnf) {
    int n = 0;
    for (int y = kLo; y < kHi; ++y)
        for (int x = kLo; x < kHi; ++x)
            n += nnf.at(x, y).x == x + kCopyX && nnf.at(x, y).y == y + kDy ? 1 : 0;
    return n;
}

TEST(SynthesizeCandidates, ExactCandidateFieldIsAdopted) {
    SynthesisInput in = crop_input();
    auto random_start = synthesize(in, short_run(), RunContext{1});
    ASSERT_TRUE(random_start.ok()) << random_start.status().message();

    // A candidate field that is exact on the left half and "none" on the right half.
    Nnf half = exact_field();
    for (int y = 0; y < kSide; ++y)
        for (int x = kSide / 2; x < kSide; ++x) half.at(x, y) = Match{-1, -1, 0.0f, 0.0f};
    in.candidate_nnfs = {half, exact_field()};
    auto with = synthesize(in, short_run(), RunContext{1});
    ASSERT_TRUE(with.ok()) << with.status().message();
    const int total = (kHi - kLo) * (kHi - kLo);
    std::printf("matches in the copy: random start %d of %d, with the candidate field %d\n",
                exact_matches(random_start->nnf), total, exact_matches(with->nnf));
    EXPECT_LT(exact_matches(random_start->nnf), total * 3 / 4);
    EXPECT_EQ(exact_matches(with->nnf), total);
}

TEST(SynthesizeCandidates, CandidatesOutsideTheSourceMaskAreNotTaken) {
    SynthesisInput in = crop_input();
    // Forbid the copy's right half: those pixels must not take their candidate.
    const int cut = kCopyX + kSide / 2;
    in.source_mask = Image(kStyleW, kStyleH, 1, 1.0f);
    for (int y = 0; y < kStyleH; ++y)
        for (int x = cut; x < kStyleW; ++x) in.source_mask.at(x, y, 0) = 0.0f;
    in.candidate_nnfs = {exact_field()};
    auto r = synthesize(in, short_run(), RunContext{1});
    ASSERT_TRUE(r.ok()) << r.status().message();
    for (int y = kLo; y < kHi; ++y)
        for (int x = kSide / 2; x < kHi; ++x) ASSERT_LT(r->nnf.at(x, y).x, cut - 2);
    // The left half (patches entirely inside the mask) takes the candidate.
    for (int y = kLo; y < kHi; ++y)
        for (int x = kLo; x < kSide / 2 - 2; ++x) ASSERT_EQ(r->nnf.at(x, y).x, x + kCopyX);
}

TEST(SynthesizeCandidates, BadCandidateFieldIsNamed) {
    SynthesisInput in = crop_input();
    in.candidate_nnfs = {exact_field(), Nnf(5, 5)};
    EXPECT_EQ(validate_input(in, short_run()).message(),
              "candidate nnf 2: is 5x5 but the target is 32x32");
    in.candidate_nnfs = {exact_field()};
    in.candidate_nnfs[0].at(3, 4) = Match{kStyleW, 0, 0.0f, 0.0f};
    EXPECT_EQ(validate_input(in, short_run()).message(),
              "candidate nnf 1: refers to 100,0 outside the 100x52 style");
}

// A candidate that loses against B' as it is at the start of a level but wins once the vote has
// changed B' (here: B' set by hand between two searches, as run_em's vote does) must be taken by
// the later search: candidates are tried in every search, not only at the level start.
TEST(SynthesizeCandidates, LaterSearchesTryTheCandidatesAgain) {
    SynthesisInput in;
    // Noise: every patch unique and no smooth basin that leads the random search to the crop.
    in.style = testing::texture(kStyleW, kStyleH, 3, 31, /*noise=*/1.0f);
    in.target_width = kSide;
    in.target_height = kSide;
    SynthesisOptions o = short_run();
    o.warm_search_iterations = 1;
    synth::LevelBuilder builder(in, o, 1, 1);
    const std::vector<Nnf> candidates = {exact_field()};
    // The B' the exact field reproduces: the style's crop at (kCopyX, kDy).
    Image crop(kSide, kSide, 3);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
            for (int c = 0; c < 3; ++c) crop.at(x, y, c) = in.style.at(x + kCopyX, y + kDy, c);

    auto run = [&](const std::vector<Nnf>* offered, int& first, int& second) {
        synth::Level L = builder.build(0);
        Nnf nnf(kSide, kSide);
        for (Match& m : nnf.matches()) m = Match{-1, -1, 0.0f, 0.0f};
        // First search: B' is another texture, against which the candidates cost as much as
        // any patch.
        synth::set_target_style(L, testing::texture(kSide, kSide, 3, 77));
        synth::ForwardProblem all{L, L.target_active.data()};
        evaluate_field(all, nnf, 1, 1);
        synth::search(synth::SearchSetup{L, o, 5, 1, nullptr, false, offered}, nnf);
        first = exact_matches(nnf);
        // Second search: B' is the crop, which only the candidates reproduce exactly.
        synth::set_target_style(L, crop);
        synth::search(synth::SearchSetup{L, o, 6, 1, nullptr, true, offered}, nnf);
        second = exact_matches(nnf);
    };
    int with_first = 0, with_second = 0, without_first = 0, without_second = 0;
    run(&candidates, with_first, with_second);
    run(nullptr, without_first, without_second);
    const int total = (kHi - kLo) * (kHi - kLo);
    std::printf("exact matches of %d: with candidates %d then %d, without %d then %d\n", total,
                with_first, with_second, without_first, without_second);
    EXPECT_LT(with_first, total / 4);
    EXPECT_EQ(with_second, total);
    EXPECT_LT(without_second, total * 3 / 4);
}

// The same through synthesize(): with candidates and without, an empty candidate list leaves the
// result bit for bit as before (the candidate loop does not touch the random streams).
TEST(SynthesizeCandidates, EmptyCandidateFieldsChangeNothing) {
    SynthesisInput in = crop_input();
    SynthesisOptions o = short_run();
    o.em_iterations = o.finest_em_iterations = 2;
    auto a = synthesize(in, o, RunContext{1});
    ASSERT_TRUE(a.ok()) << a.status().message();
    // A field of "none" entries is tried everywhere and never taken.
    Nnf none(kSide, kSide);
    for (Match& m : none.matches()) m = Match{-1, -1, 0.0f, 0.0f};
    in.candidate_nnfs = {none};
    auto b = synthesize(in, o, RunContext{2});
    ASSERT_TRUE(b.ok()) << b.status().message();
    EXPECT_TRUE(
        std::equal(a->image.data().begin(), a->image.data().end(), b->image.data().begin()));
}

}  // namespace
}  // namespace exemplar
