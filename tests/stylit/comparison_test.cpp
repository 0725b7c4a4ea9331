// The comparison of Fig. 8.11/8.12 (Fišer et al. 2016) on the real StyLit data at 600x456 (the
// bundled example), with the paper's plain averaging vote: on the same inputs, plain
// nearest-neighbour voting (usage none) washes the strokes out, uniform usage forces non-highlight
// patches into the target's highlights, and the error budget keeps both the texture and the
// highlights.
//
// Measures: distinct source patches used per target patch and gradient energy on the object,
// for wash-out; and the fraction of the target's highlight pixels
// (its direct specular buffer above a threshold) whose NNF match lies in the exemplar's highlight
// region (the exemplar's specular buffer above the threshold, dilated by the patch radius), for
// structure.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <utility>

#include "exemplar/stylit/stylit.hpp"
#include "stylit_test_data.hpp"

namespace exemplar {
namespace {

using testing::grey_at;
using testing::load_example;

constexpr float kHighlight = 0.3f;

// The red object of a full render (the sphere, the figure), shrunk by `margin` px so that its
// outline does not count as texture.
std::vector<bool> object_mask(const Image& full, int margin) {
    const int w = full.width(), h = full.height();
    std::vector<bool> red(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            red[static_cast<std::size_t>(y) * w + x] =
                full.at(x, y, 0) - 0.5f * (full.at(x, y, 1) + full.at(x, y, 2)) > 0.3f;
        }
    }
    std::vector<bool> inside(red.size(), false);
    for (int y = margin; y < h - margin; ++y) {
        for (int x = margin; x < w - margin; ++x) {
            bool all = true;
            for (int dy = -margin; dy <= margin && all; ++dy) {
                for (int dx = -margin; dx <= margin && all; ++dx) {
                    all = red[static_cast<std::size_t>(y + dy) * w + x + dx];
                }
            }
            inside[static_cast<std::size_t>(y) * w + x] = all;
        }
    }
    return inside;
}

double gradient_energy(const Image& image, const std::vector<bool>& mask = {}) {
    double sum = 0.0;
    std::size_t count = 0;
    for (int y = 0; y + 1 < image.height(); ++y) {
        for (int x = 0; x + 1 < image.width(); ++x) {
            if (!mask.empty() && !mask[static_cast<std::size_t>(y) * image.width() + x]) continue;
            const double g = grey_at(image, x, y);
            const double dx = grey_at(image, x + 1, y) - g;
            const double dy = grey_at(image, x, y + 1) - g;
            sum += dx * dx + dy * dy;
            ++count;
        }
    }
    return sum / static_cast<double>(count);
}

struct Metrics {
    double texture = 0.0;             // gradient energy / the exemplar's
    double highlight_fidelity = 0.0;  // fraction of target highlight pixels fed by highlights
    double distinct_patches = 0.0;    // distinct source patches used / target patches
    double object_texture = 0.0;      // the same on the object only (figure vs sphere)
};

class Comparison : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        const char* names[] = {"fullgi", "dirdif", "dirspc", "indirb"};
        exemplar_ = new Image(load_example("source_style.png"));
        source_ = new std::vector<LpeBuffer>;
        target_ = new std::vector<LpeBuffer>;
        for (const char* name : names) {
            const std::string s = std::string("source_") + name + ".png";
            const std::string t = std::string("target_") + name + ".png";
            source_->push_back({name, s, load_example(s)});
            target_->push_back({name, t, load_example(t)});
        }
        // The highlight comparison is made over several seeds: on one seed the few highlight
        // pixels fed from elsewhere jump between ~4.5% and ~9.6% (a cluster of ~45 px either
        // finds the exemplar's highlight or not), which one seed cannot separate from the
        // uniform strategy's 10-13%.
        results_ = new std::map<std::pair<UsageStrategy, std::uint64_t>, Metrics>;
        for (std::uint64_t seed : kSeeds) {
            for (UsageStrategy usage :
                 {UsageStrategy::None, UsageStrategy::Uniform, UsageStrategy::ErrorBudget}) {
                (*results_)[{usage, seed}] = run(usage, seed);
            }
        }
    }
    static void TearDownTestSuite() {
        delete exemplar_;
        delete source_;
        delete target_;
        delete results_;
    }

    static constexpr std::uint64_t kSeeds[] = {1, 2, 3};

    static Metrics run(UsageStrategy usage, std::uint64_t seed) {
        StylitOptions options;
        options.synthesis.usage = usage;
        options.synthesis.seed = seed;
        // The paper's setting: plain averaging of whole patches (the engine's weighted vote
        // and narrow final vote hide part of the wash-out).
        options.synthesis.vote = VoteMode::Average;
        options.synthesis.final_pass_iterations = 0;
        options.synthesis.final_vote_size = 0;
        auto result = stylize_render(*exemplar_, *source_, *target_, options);
        EXPECT_TRUE(result.ok()) << result.status().message();
        if (!result.ok()) return {};
        const Image& out = result->synthesis.image;
        const Nnf& nnf = result->synthesis.nnf;

        // The exemplar's highlight region, dilated by the patch radius.
        const Image& source_specular = (*source_)[2].image;
        const int w = source_specular.width(), h = source_specular.height();
        std::vector<bool> highlight(static_cast<std::size_t>(w) * h, false);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                if (grey_at(source_specular, x, y) <= kHighlight) continue;
                for (int dy = -2; dy <= 2; ++dy) {
                    for (int dx = -2; dx <= 2; ++dx) {
                        const int u = std::clamp(x + dx, 0, w - 1),
                                  v = std::clamp(y + dy, 0, h - 1);
                        highlight[static_cast<std::size_t>(v) * w + u] = true;
                    }
                }
            }
        }
        const Image& target_specular = (*target_)[2].image;
        std::size_t total = 0, fed = 0;
        for (int y = 0; y < nnf.height(); ++y) {
            for (int x = 0; x < nnf.width(); ++x) {
                const Match& m = nnf.at(x, y);
                if (m.x < 0 || grey_at(target_specular, x, y) <= kHighlight) continue;
                ++total;
                if (highlight[static_cast<std::size_t>(m.y) * w + m.x]) ++fed;
            }
        }
        // Distinct source patches per target patch centre.
        std::vector<bool> seen(static_cast<std::size_t>(w) * h, false);
        std::size_t distinct = 0, centres = 0;
        for (const Match& m : nnf.matches()) {
            if (m.x < 0) continue;
            ++centres;
            const std::size_t i = static_cast<std::size_t>(m.y) * w + m.x;
            if (!seen[i]) ++distinct;
            seen[i] = true;
        }
        Metrics metrics;
        metrics.distinct_patches = static_cast<double>(distinct) / static_cast<double>(centres);
        metrics.texture = gradient_energy(out) / gradient_energy(*exemplar_);
        metrics.object_texture = gradient_energy(out, object_mask((*target_)[0].image, 3)) /
                                 gradient_energy(*exemplar_, object_mask((*source_)[0].image, 3));
        metrics.highlight_fidelity = total > 0 ? static_cast<double>(fed) / total : 0.0;
        std::printf(
            "usage %-12s seed %d  gradient energy %.3f (object %.3f)  distinct patches %.3f  "
            "highlight fidelity %.3f (%zu highlight px)\n",
            std::string(to_string(usage)).c_str(), static_cast<int>(seed), metrics.texture,
            metrics.object_texture, metrics.distinct_patches, metrics.highlight_fidelity, total);
        return metrics;
    }

    static Image* exemplar_;
    static std::vector<LpeBuffer>* source_;
    static std::vector<LpeBuffer>* target_;
    static std::map<std::pair<UsageStrategy, std::uint64_t>, Metrics>* results_;
};

Image* Comparison::exemplar_ = nullptr;
std::vector<LpeBuffer>* Comparison::source_ = nullptr;
std::vector<LpeBuffer>* Comparison::target_ = nullptr;
std::map<std::pair<UsageStrategy, std::uint64_t>, Metrics>* Comparison::results_ = nullptr;

// One test for both claims: ctest runs every test in its own process, and the nine runs are
// the cost (~40 s alone on 2 cores).
//
// Wash-out is the excessive reuse of a few patches (§8.2): nearest neighbours (none) feed the
// target from about half as many distinct source patches as it has patches; the error budget
// spreads the usage, which shows as texture on the object (the figure), where nearest
// neighbours smooth the strokes out: gradient energy relative to the exemplar's sphere, none
// 0.336, error budget 0.357-0.371 over seeds 1-3. (Over the whole image, dominated by the
// background strokes, gradient energy does not separate them.)
//
// Uniform usage must use every source patch, so it pushes non-highlight patches into the
// target's highlights (Fig. 8.11m, n); the error budget reuses the highlight patches instead.
TEST_F(Comparison, ErrorBudgetAvoidsWashOutAndKeepsHighlights) {
    const Metrics none = results_->at({UsageStrategy::None, 1});
    const Metrics uniform = results_->at({UsageStrategy::Uniform, 1});
    const Metrics budget = results_->at({UsageStrategy::ErrorBudget, 1});
    EXPECT_LT(none.distinct_patches, 0.6);                            // measured 0.506
    EXPECT_GT(budget.distinct_patches, none.distinct_patches + 0.1);  // measured 0.657
    EXPECT_GT(uniform.distinct_patches, 0.9);  // measured 0.991 (border patches: nearest)
    // Measured 1.32x (1.32-1.41x over seeds 1-3; 1.06x before every pixel was a centre).
    EXPECT_GT(budget.object_texture, none.object_texture * 1.03);

    // Highlight pixels fed from outside the exemplar's highlight, seeds 1, 2, 3 (2026-11-24,
    // every pixel a patch centre): error budget 4.4%, 9.6%, 9.6%; uniform 18.0%, 15.8%, 21.9%;
    // nearest neighbours 6.2%, 9.6%, 9.6%. On every seed the error budget keeps at least the
    // highlights nearest neighbours keep with the same seed, and more than uniform usage; over
    // the seeds it misses clearly fewer than uniform usage.
    double budget_miss = 0.0, uniform_miss = 0.0;
    for (std::uint64_t seed : kSeeds) {
        const Metrics& b = results_->at({UsageStrategy::ErrorBudget, seed});
        const Metrics& u = results_->at({UsageStrategy::Uniform, seed});
        const Metrics& n = results_->at({UsageStrategy::None, seed});
        EXPECT_GE(b.highlight_fidelity, n.highlight_fidelity - 0.01) << "seed " << seed;
        EXPECT_GE(b.highlight_fidelity, u.highlight_fidelity) << "seed " << seed;
        budget_miss += 1.0 - b.highlight_fidelity;
        uniform_miss += 1.0 - u.highlight_fidelity;
    }
    EXPECT_LT(budget_miss, 0.8 * uniform_miss);
}

}  // namespace
}  // namespace exemplar
