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
#include <cstdio>
#include <map>

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
        results_ = new std::map<UsageStrategy, Metrics>;
        for (UsageStrategy usage :
             {UsageStrategy::None, UsageStrategy::Uniform, UsageStrategy::ErrorBudget}) {
            (*results_)[usage] = run(usage);
        }
    }
    static void TearDownTestSuite() {
        delete exemplar_;
        delete source_;
        delete target_;
        delete results_;
    }

    static Metrics run(UsageStrategy usage) {
        StylitOptions options;
        options.synthesis.usage = usage;
        // The paper's setting: plain averaging vote, no extra 3x3 pass (both of which the
        // engine adds by default and which hide part of the wash-out).
        options.synthesis.vote = VoteMode::Average;
        options.synthesis.final_pass_iterations = 0;
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
            "usage %-12s gradient energy %.3f (object %.3f)  distinct patches %.3f  highlight "
            "fidelity %.3f (%zu highlight px)\n",
            std::string(to_string(usage)).c_str(), metrics.texture, metrics.object_texture,
            metrics.distinct_patches, metrics.highlight_fidelity, total);
        return metrics;
    }

    static Image* exemplar_;
    static std::vector<LpeBuffer>* source_;
    static std::vector<LpeBuffer>* target_;
    static std::map<UsageStrategy, Metrics>* results_;
};

Image* Comparison::exemplar_ = nullptr;
std::vector<LpeBuffer>* Comparison::source_ = nullptr;
std::vector<LpeBuffer>* Comparison::target_ = nullptr;
std::map<UsageStrategy, Metrics>* Comparison::results_ = nullptr;

// One test for both claims: ctest runs every test in its own process, and the three runs are the
// cost (~40 s on 2 cores).
//
// Wash-out is the excessive reuse of a few patches (§8.2): nearest neighbours (none) feed the
// target from about half as many distinct source patches as it has patches; the error budget
// spreads the usage, which shows as texture on the object (the figure), where nearest
// neighbours smooth the strokes out: gradient energy relative to the exemplar's sphere, none
// 0.359, error budget 0.390. (Over the whole image, dominated by the background strokes,
// gradient energy does not separate them: none 0.750, uniform 0.676, error budget 0.709.)
//
// Uniform usage must use every source patch, so it pushes non-highlight patches into the
// target's highlights (Fig. 8.11m, n); the error budget reuses the highlight patches instead.
TEST_F(Comparison, ErrorBudgetAvoidsWashOutAndKeepsHighlights) {
    const Metrics none = results_->at(UsageStrategy::None);
    const Metrics uniform = results_->at(UsageStrategy::Uniform);
    const Metrics budget = results_->at(UsageStrategy::ErrorBudget);
    EXPECT_LT(none.distinct_patches, 0.6);                            // measured 0.490
    EXPECT_GT(budget.distinct_patches, none.distinct_patches + 0.1);  // measured 0.699
    EXPECT_GT(uniform.distinct_patches, 0.9);                         // measured 1.000
    // Measured 1.086x here, 1.06x with main's engine of 43abd41 (2 finest EM iterations).
    EXPECT_GT(budget.object_texture, none.object_texture * 1.03);

    // Highlight pixels fed from outside the exemplar's highlight: measured 4.5% with the error
    // budget, 9.6% with uniform usage (21.6% before the reversed rounds resumed at the nearest
    // free target, which helps uniform usage too).
    EXPECT_GT(budget.highlight_fidelity, 0.9);
    EXPECT_LT(1.0 - budget.highlight_fidelity, 0.6 * (1.0 - uniform.highlight_fidelity));
}

}  // namespace
}  // namespace exemplar
