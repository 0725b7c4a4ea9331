// Micro-benchmarks of the synthesis kernels: patch distance (reference vs production), one
// PatchMatch iteration and one vote, on stylit-like feature counts (3 style + 12 guide channels).
#include <benchmark/benchmark.h>

#include <map>

#include "level_builder.hpp"
#include "patch_distance.hpp"
#include "patchmatch.hpp"
#include "ssd.hpp"
#include "test_images.hpp"
#include "vote.hpp"

namespace exemplar::synth {
namespace {

struct Setup {
    SynthesisInput in;
    SynthesisOptions opt;
    Level L;
    Nnf nnf;
};

// `weight_maps`: every guide gets a per-pixel target weight map (as the animation solver's
// occlusion-aware temporal term does).
Setup& setup(int size, bool weight_maps = false) {
    static std::map<std::pair<int, bool>, Setup> cache;
    auto it = cache.find({size, weight_maps});
    if (it != cache.end()) return it->second;
    Setup& s = cache[{size, weight_maps}];
    s.in.style = testing::texture(size, size, 3, 1);
    for (int g = 0; g < 4; ++g) {
        s.in.guides.push_back(GuidePair{
            "g", testing::texture(size, size, 3, 10 + g), testing::texture(size, size, 3, 20 + g),
            0.5f, weight_maps ? testing::texture(size, size, 1, 30 + g) : Image()});
    }
    LevelBuilder builder(s.in, s.opt, 1, 1);
    s.L = builder.build(0);
    set_target_style(s.L, testing::texture(size, size, 3, 5));
    s.nnf = Nnf(size, size);
    for (Match& m : s.nnf.matches()) m = Match{-1, -1, 0, 0};
    ForwardProblem all{s.L, s.L.target_active.data()};
    evaluate_field(all, s.nnf, 1, 1);
    return s;
}

void BM_PatchDistanceReference(benchmark::State& state) {
    const Level& L = setup(128).L;
    int i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(patch_distance_reference(L, 10 + i % 100, 20, 30, 40 + i % 50, 0));
        ++i;
    }
}
BENCHMARK(BM_PatchDistanceReference);

void BM_PatchDistanceFast(benchmark::State& state) {
    set_simd_enabled(state.range(0) != 0);
    state.SetLabel(state.range(0) != 0 ? simd_target_name() : "scalar");
    const Level& L = setup(128).L;
    int i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(patch_distance(L, 10 + i % 100, 20, 30, 40 + i % 50, 0));
        ++i;
    }
}
BENCHMARK(BM_PatchDistanceFast)->Arg(0)->Arg(1);

// range(0): threads; range(1): image side (1024: features of 16 MiB per image, past the caches,
// which is the regime of the finest levels of real runs).
// Per-pixel guide weights: range(0) 0 = the general (reference) path, 1 = the SIMD fast path.
void BM_PatchDistanceWeightMap(benchmark::State& state) {
    set_simd_enabled(true);
    const Level& L = setup(128, true).L;
    const bool fast = state.range(0) != 0;
    state.SetLabel(fast ? "fast path" : "general path");
    int i = 0;
    for (auto _ : state) {
        const int tx = 10 + i % 100, sy = 40 + i % 50;
        benchmark::DoNotOptimize(fast ? patch_distance(L, tx, 20, 30, sy, 0)
                                      : patch_distance_reference(L, tx, 20, 30, sy, 0));
        ++i;
    }
}
BENCHMARK(BM_PatchDistanceWeightMap)->Arg(0)->Arg(1);

// Patches over the border (target column 0, the column random search clamps to), where the
// production kernel takes the gathered path: range(0) 0 = the reference's loop, 1 = production.
void BM_PatchDistanceBorder(benchmark::State& state) {
    set_simd_enabled(true);
    const Level& L = setup(128).L;
    const bool fast = state.range(0) != 0;
    state.SetLabel(fast ? "gathered path" : "reference loop");
    int i = 0;
    for (auto _ : state) {
        const int ty = 10 + i % 100, sy = 40 + i % 50;
        benchmark::DoNotOptimize(fast ? patch_distance(L, 0, ty, 30, sy, 0)
                                      : patch_distance_reference(L, 0, ty, 30, sy, 0));
        ++i;
    }
}
BENCHMARK(BM_PatchDistanceBorder)->Arg(0)->Arg(1);

void BM_PatchMatchIteration(benchmark::State& state) {
    set_simd_enabled(true);
    const int size = static_cast<int>(state.range(1));
    Setup& s = setup(size);
    ForwardProblem all{s.L, s.L.target_active.data()};
    for (auto _ : state) {
        Nnf nnf = s.nnf;
        run_patchmatch(all, nnf, 1, 7, static_cast<int>(state.range(0)));
        benchmark::DoNotOptimize(nnf.matches().data());
    }
    state.SetItemsProcessed(state.iterations() * size * size);
}
BENCHMARK(BM_PatchMatchIteration)
    ->Args({1, 256})
    ->Args({2, 256})
    ->Args({1, 1024})
    ->Unit(benchmark::kMillisecond);

// As the engine votes (clamped source reads, weighted by the matches' errors); range(1) = 1 runs
// the per-pixel reference, 0 the row vote (the same bytes).
void BM_Vote(benchmark::State& state) {
    Setup& s = setup(256);
    Image out(256, 256, 3);
    const std::vector<float> weights = vote_weights(s.nnf, nullptr, 5, 0.0f, 1);
    VoteParams params;
    params.clamp_source = true;
    params.patch_weights = weights;
    const bool reference = state.range(1) != 0;
    state.SetLabel(reference ? "reference" : "rows");
    for (auto _ : state) {
        if (reference) {
            vote_reference(s.nnf, s.L.source_style, params, out, static_cast<int>(state.range(0)));
        } else {
            vote(s.nnf, s.L.source_style, params, out, static_cast<int>(state.range(0)));
        }
        benchmark::DoNotOptimize(out.data().data());
    }
    state.SetItemsProcessed(state.iterations() * 256 * 256);
}
BENCHMARK(BM_Vote)->Args({1, 1})->Args({1, 0})->Args({2, 0})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace exemplar::synth

BENCHMARK_MAIN();
