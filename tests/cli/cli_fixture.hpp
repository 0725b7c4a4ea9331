#pragma once
// Runs the `exemplar` command line in-process (run_cli) in a fresh temporary folder holding a few
// tiny images, and checks failures the way a user sees them: the exit code, one line on stderr
// naming the file or parameter, and no output file left behind.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "exemplar/core/image.hpp"
#include "exemplar/io/image_io.hpp"
#include "file_bytes.hpp"
#include "temp_dir.hpp"
#include "test_images.hpp"

namespace exemplar::cli::testing {

namespace fs = std::filesystem;

struct CliRun {
    int code = -1;
    std::string out;
    std::string err;
};

inline CliRun run(std::vector<std::string> args) {
    args.insert(args.begin(), "exemplar");
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    const int code = run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
    return {code, out.str(), err.str()};
}

/// Smooth deterministic texture in [0, 1]: a few sinusoids per channel plus hashed noise.
inline Image texture(int w, int h, int channels, std::uint32_t seed) {
    Image im(w, h, channels);
    for (int c = 0; c < channels; ++c) {
        const float fx = 0.2f + 0.07f * static_cast<float>((seed * 7 + c * 3) % 5);
        const float fy = 0.15f + 0.05f * static_cast<float>((seed * 5 + c * 11) % 7);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                std::uint32_t n =
                    seed * 747796405u +
                    static_cast<std::uint32_t>((y * w + x) * channels + c) * 2891336453u;
                n ^= n >> 15;
                n *= 2246822519u;
                n ^= n >> 13;
                const float noise = static_cast<float>(n % 1000) / 1000.0f - 0.5f;
                const float v = 0.5f +
                                0.3f * std::sin(fx * x + static_cast<float>(seed)) *
                                    std::cos(fy * y + static_cast<float>(c)) +
                                0.15f * noise;
                im.at(x, y, c) = std::clamp(v, 0.0f, 1.0f);
            }
        }
    }
    return im;
}

using exemplar::testing::ramp;

using exemplar::testing::file_bytes;

/// Bit depth of a PNG file from its IHDR chunk (byte 24), or -1.
inline int png_bit_depth(const std::string& path) {
    const std::string bytes = file_bytes(path);
    return bytes.size() > 24 ? static_cast<unsigned char>(bytes[24]) : -1;
}

inline float max_abs_diff(const Image& a, const Image& b) {
    float diff = 0.0f;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        diff = std::max(diff, std::abs(a.data()[i] - b.data()[i]));
    }
    return diff;
}

/// A temporary folder with style.png (32x28 RGB), a.png (its guide, 32x28 RGB), b.png (the
/// target guide, 36x30 RGB) and the float guides ramp_a.exr / ramp_b.exr.
class Cli : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        write("style.png", texture(32, 28, 3, 1));
        write("a.png", texture(32, 28, 3, 2));
        write("b.png", texture(36, 30, 3, 3));
        write("ramp_a.exr", ramp(32, 28));
        write("ramp_b.exr", ramp(36, 30));
    }

    void write(const std::string& name, const Image& image, const SaveOptions& options = {}) {
        const Status status = save_image(image, path(name), options);
        ASSERT_TRUE(status.is_ok()) << status.message();
    }
    Image read(const std::string& name) const {
        auto image = load_image(path(name));
        EXPECT_TRUE(image.ok()) << image.status().message();
        return image.ok() ? std::move(image).value() : Image();
    }

    /// A quick stylize command line: style.png with the guide pair a.png -> b.png, one level.
    std::vector<std::string> stylize_args() const {
        return {"stylize",
                "--style",
                path("style.png"),
                "--guide",
                path("a.png"),
                path("b.png"),
                "--levels",
                "1",
                "--em-iterations",
                "2",
                "--final-pass-iterations",
                "1"};
    }
    static std::vector<std::string> with(std::vector<std::string> args,
                                         const std::vector<std::string>& more) {
        args.insert(args.end(), more.begin(), more.end());
        return args;
    }

    /// Runs `args` plus `-o out.png` and expects exit code `code`, exactly one stderr line
    /// `exemplar: ...` containing `part`, and no file written (not even a temporary one).
    void expect_failure(std::vector<std::string> args, int code, const std::string& part) {
        args.push_back("-o");
        args.push_back(path("out.png"));
        expect_failure_as_is(args, code, part);
        EXPECT_FALSE(fs::exists(path("out.png")));
    }
    void expect_failure_as_is(const std::vector<std::string>& args, int code,
                              const std::string& part) {
        const auto before = listing();
        const CliRun r = run(args);
        EXPECT_EQ(r.code, code) << r.err;
        EXPECT_NE(r.err.find(part), std::string::npos) << "expected '" << part << "' in: " << r.err;
        EXPECT_EQ(r.err.rfind("exemplar: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
        EXPECT_EQ(listing(), before) << "a failed run wrote a file";
    }

    std::vector<std::string> listing() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::recursive_directory_iterator(dir_)) {
            names.push_back(entry.path().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }
};

}  // namespace exemplar::cli::testing
