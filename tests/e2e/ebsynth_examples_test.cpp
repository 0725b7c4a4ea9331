// End-to-end runs on the three ebsynth examples (stylit, facestyle, texbynum) as bundled with
// the repository (stylit and facestyle at half resolution, to keep the suite fast; see
// tests/data/SOURCES.md), with checks that mean something: no wash-out (gradient energy close
// to the exemplar's), highlights taken from the exemplar's highlight, segments respected.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <string>

#include "exemplar/filters/measures.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/synthesize.hpp"

namespace exemplar {
namespace {

const std::string kStylit = std::string(EXEMPLAR_SOURCE_DIR) + "/examples/stylit/";
const std::string kData = std::string(EXEMPLAR_TEST_DATA_DIR) + "/ebsynth/";

Image load(const std::string& path) {
    auto image = load_image(path);
    EXPECT_TRUE(image.ok()) << image.status().message();
    return image.ok() ? std::move(image).value() : Image{};
}

// Gradient energy of the luminance per segment (segment = exact guide colour), over pixels
// whose 3x3 neighbourhood lies in one segment (so segment borders do not count).
std::map<std::array<int, 3>, double> segment_energy(const Image& im, const Image& seg) {
    std::map<std::array<int, 3>, std::pair<double, int>> acc;
    auto key = [&](int x, int y) {
        const float* p = seg.pixel(x, y);
        return std::array<int, 3>{static_cast<int>(std::lround(p[0] * 255)),
                                  static_cast<int>(std::lround(p[1] * 255)),
                                  static_cast<int>(std::lround(p[2] * 255))};
    };
    auto lum = [&](int x, int y) {
        const float* p = im.pixel(x, y);
        return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
    };
    for (int y = 1; y + 1 < im.height(); ++y) {
        for (int x = 1; x + 1 < im.width(); ++x) {
            const auto k = key(x, y);
            bool inside = true;
            for (int dy = -1; dy <= 1 && inside; ++dy)
                for (int dx = -1; dx <= 1 && inside; ++dx) inside = key(x + dx, y + dy) == k;
            if (!inside) continue;
            const double dx = lum(x + 1, y) - lum(x, y);
            const double dy = lum(x, y + 1) - lum(x, y);
            auto& a = acc[k];
            a.first += dx * dx + dy * dy;
            a.second += 1;
        }
    }
    std::map<std::array<int, 3>, double> out;
    for (const auto& [k, a] : acc) {
        if (a.second >= 500) out[k] = a.first / a.second;
    }
    return out;
}

// Fraction of matched target pixels whose segmentation colour equals (L1 distance below
// `tolerance`) the colour at the source of their match.
double segment_agreement(const Nnf& nnf, const Image& source_seg, const Image& target_seg,
                         double tolerance) {
    int n = 0, agree = 0;
    for (int y = 0; y < target_seg.height(); ++y) {
        for (int x = 0; x < target_seg.width(); ++x) {
            const Match& m = nnf.at(x, y);
            if (m.x < 0) continue;
            ++n;
            double d = 0.0;
            for (int c = 0; c < 3; ++c) {
                d += std::abs(source_seg.at(m.x, m.y, c) - target_seg.at(x, y, c));
            }
            agree += d < tolerance ? 1 : 0;
        }
    }
    return n > 0 ? static_cast<double>(agree) / n : 0.0;
}

double mean_channel(const Image& im, int x, int y) {
    double s = 0.0;
    for (int c = 0; c < im.channels(); ++c) s += im.at(x, y, c);
    return s / im.channels();
}

TEST(Examples, StylitKeepsTextureAndHighlights) {
    const std::string& dir = kStylit;
    SynthesisInput in;
    in.style = load(dir + "source_style.png");
    for (const char* pass : {"fullgi", "dirdif", "dirspc", "indirb"}) {
        in.guides.push_back(GuidePair{pass,
                                      load(dir + "source_" + pass + ".png"),
                                      load(dir + "target_" + pass + ".png"),
                                      0.5f,
                                      {}});
    }
    SynthesisOptions opt;  // defaults: error budget, patch 5
    auto result = synthesize(in, opt, RunContext(0));
    ASSERT_TRUE(result.ok()) << result.status().message();

    const double style_energy = gradient_energy(in.style);
    const double out_energy = gradient_energy(result->image);
    EXPECT_NEAR(out_energy / style_energy, 1.0, 0.2)
        << "exemplar " << style_energy << " output " << out_energy;

    // Pixels in the target's specular highlight must copy from the exemplar's highlight.
    const Image& target_spec = in.guides[2].target;
    const Image& source_spec = in.guides[2].source;
    int highlight = 0, from_highlight = 0;
    for (int y = 0; y < target_spec.height(); ++y) {
        for (int x = 0; x < target_spec.width(); ++x) {
            if (mean_channel(target_spec, x, y) < 0.5) continue;
            const Match& m = result->nnf.at(x, y);
            if (m.x < 0) continue;
            ++highlight;
            from_highlight += mean_channel(source_spec, m.x, m.y) > 0.25 ? 1 : 0;
        }
    }
    ASSERT_GT(highlight, 20);
    EXPECT_GT(static_cast<double>(from_highlight) / highlight, 0.9)
        << from_highlight << " of " << highlight;
}

TEST(Examples, FacestyleKeepsTextureAndSegments) {
    const std::string dir = kData + "facestyle/";
    SynthesisInput in;
    in.style = load(dir + "source_painting.png");
    const char* names[] = {"Gapp", "Gseg", "Gpos"};
    const float weights[] = {0.5f, 1.5f, 10.0f};
    for (int i = 0; i < 3; ++i) {
        const std::string n = names[i];
        in.guides.push_back(GuidePair{n,
                                      load(dir + "source_" + n + ".png"),
                                      load(dir + "target_" + n + ".png"),
                                      weights[i],
                                      {}});
    }
    SynthesisOptions opt;
    auto result = synthesize(in, opt, RunContext(0));
    ASSERT_TRUE(result.ok()) << result.status().message();
    // No wash-out: plain nearest neighbours (usage none) keep ~0.69 of the exemplar's gradient
    // energy on this input, the error budget ~0.75-0.80 (bench_examples facestyle --scale 0.5).
    const double texture = gradient_energy(result->image) / gradient_energy(in.style);
    EXPECT_GT(texture, 0.75);
    EXPECT_LT(texture, 1.2);
    // The segmentation colour at the source of each match agrees with the target's.
    EXPECT_GT(segment_agreement(result->nnf, in.guides[1].source, in.guides[1].target, 0.15), 0.9);
}

TEST(Examples, TextureByNumbersRespectsSegments) {
    const std::string dir = kData + "texbynum/";
    SynthesisInput in;
    in.style = load(dir + "source_photo.png");
    in.guides.push_back(GuidePair{
        "segment", load(dir + "source_segment.png"), load(dir + "target_segment.png"), 1.0f, {}});
    SynthesisOptions opt;
    opt.patch_size = 3;  // the ebsynth example's settings: patch 3, uniformity
    opt.usage = UsageStrategy::OccurrencePenalty;
    auto result = synthesize(in, opt, RunContext(0));
    ASSERT_TRUE(result.ok()) << result.status().message();
    // The target has far more sky than the photo, so compare texture detail per segment.
    const auto source_energy = segment_energy(in.style, in.guides[0].source);
    const auto output_energy = segment_energy(result->image, in.guides[0].target);
    int compared = 0;
    for (const auto& [segment, energy] : output_energy) {
        auto it = source_energy.find(segment);
        if (it == source_energy.end()) continue;
        ++compared;
        // Known gap (issue 2 notes): with 3x3 patches the output keeps 0.56-0.72 of each
        // segment's detail, short of the 0.8 reached on stylit and facestyle. This bound guards
        // against regressions until the voting improves.
        EXPECT_GT(energy / it->second, 0.5)
            << "segment " << segment[0] << "," << segment[1] << "," << segment[2];
        // Upper bound: no noise. The sky segment (far larger in the target than in the photo,
        // so the occurrence penalty pushes some of it onto other segments' patches) gets
        // 1.08-1.54x the photo's sky detail depending on the seed and on float rounding in the
        // distance kernel (seeds 1-4, scalar and SIMD kernels); noise would be several times
        // that.
        EXPECT_LT(energy / it->second, 1.7)
            << "segment " << segment[0] << "," << segment[1] << "," << segment[2];
    }
    EXPECT_GE(compared, 3);
    EXPECT_GT(segment_agreement(result->nnf, in.guides[0].source, in.guides[0].target, 0.1), 0.9);
}

}  // namespace
}  // namespace exemplar
