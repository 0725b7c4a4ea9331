// The video codec plugin (libexemplar_video_mp4.so, src/video/video_codec.hpp): the only binary
// that links OpenCV's videoio, loaded on the first video use only; found by the `exemplar`
// executable beside it in the build tree and in lib/exemplar/ once installed; when it is missing,
// video files fail with one line naming the file and image sequences work as before.
// The other plugins (src/plugin/plugin_loader.hpp: OpenCV, Embree, Cairo) go through the same
// loader: `exemplar` links none of their libraries, plain verbs run without any plugin, and a
// command that needs a missing one fails with one line.
//
// The command-line cases run the real `exemplar` executable in a child process: the plugin is
// loaded once per process, so a missing plugin can only be seen in a fresh one.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "exemplar/io/image_io.hpp"
#include "exemplar/render/render.hpp"
#include "exemplar/render/scene.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "exemplar/video/optical_flow.hpp"
#include "temp_dir.hpp"

namespace exemplar::video {
namespace {

namespace fs = std::filesystem;

const std::string kExemplar = EXEMPLAR_BINARY;
const std::string kPlugin = EXEMPLAR_PLUGIN;
// The other plugins, built beside the codec's.
const std::vector<std::string> kOtherPlugins = {
    "libexemplar_opencv.so", "libexemplar_render_embree.so", "libexemplar_cairo.so"};

std::string file_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// True if a file whose name contains `library` is mapped into this process.
bool mapped(const std::string& library) {
    return file_text("/proc/self/maps").find(library) != std::string::npos;
}

// `text` as one shell word.
std::string quoted(const std::string& text) {
    std::string out(1, '\'');
    for (char c : text) {
        if (c == '\'') {
            out.append("'\\''");
        } else {
            out.push_back(c);
        }
    }
    out.push_back('\'');
    return out;
}

// Frame n of a small moving ramp (RGB; even sides, as MP4 needs).
Image frame(int n) {
    Image image(32, 24, 3);
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            image.at(x, y, 0) = static_cast<float>((x + 2 * n) % 32) / 32.0f;
            image.at(x, y, 1) = static_cast<float>(y) / 24.0f;
            image.at(x, y, 2) = 0.3f + 0.1f * static_cast<float>(n);
        }
    }
    return image;
}

struct ProcessRun {
    int code = -1;
    std::string out;
    std::string err;
};

class VideoPlugin : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        fs::create_directories(dir_ / "frames");
        fs::create_directories(dir_ / "out");
    }

    // Runs `executable args...` through the shell with `env` in front ("env -u NAME" or
    // "env NAME=value"), capturing the exit code and both streams.
    ProcessRun run(const std::string& env, const std::string& executable,
                   const std::vector<std::string>& args) const {
        // append() rather than " " + word: GCC 12 sees a false -Wrestrict in the latter.
        std::string command = env;
        command.append(" ").append(quoted(executable));
        for (const std::string& word : args) command.append(" ").append(quoted(word));
        command.append(" > ").append(quoted(path("stdout.txt")));
        command.append(" 2> ").append(quoted(path("stderr.txt")));
        const int status = std::system(command.c_str());
        ProcessRun r;
        r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.out = file_text(path("stdout.txt"));
        r.err = file_text(path("stderr.txt"));
        return r;
    }

    // An `exemplar animate` job on `frames` (a video or a pattern of 3 frames) styled by an
    // inverted copy of frame 0, written to out/%02d.png and, if given, to `mp4`.
    std::string job(const std::string& frames, const std::string& mp4 = "") const {
        const Image input = frame(0);
        Image output = input;
        for (std::size_t i = 0; i < output.size(); ++i) output.data()[i] = 1.0f - input.data()[i];
        EXPECT_TRUE(save_image(input, path("style_in.png")).is_ok());
        EXPECT_TRUE(save_image(output, path("style_out.png")).is_ok());
        std::ofstream f(path("job.json"));
        const bool pattern = frames.find('%') != std::string::npos;
        f << R"({"frames": ")" << frames << '"' << (pattern ? R"(, "first": 0, "last": 2)" : "")
          << R"(, "style": {"input": ")" << path("style_in.png") << R"(", "output": ")"
          << path("style_out.png") << R"("}, "output": ")" << path("out/%02d.png") << '"'
          << (mp4.empty() ? "" : R"(, "mp4": ")" + mp4 + '"') << ", \"fps\": 10}";
        return path("job.json");
    }

    void write_pngs() const {
        for (int n = 0; n < 3; ++n) {
            ASSERT_TRUE(write_frame(frame(n), path("frames/%02d.png"), n).is_ok());
        }
    }

    void write_mp4(const std::string& name) const {
        auto writer = Mp4Writer::open(path(name), 32, 24, 10.0);
        ASSERT_TRUE(writer.ok()) << writer.status().message();
        for (int n = 0; n < 3; ++n) ASSERT_TRUE(writer->write(frame(n)).is_ok());
        ASSERT_TRUE(writer->finish().is_ok());
    }
};

// ctest runs every test in a fresh process; run by hand, this one comes first in the file.
TEST_F(VideoPlugin, CodecsLoadOnFirstVideoUseOnly) {
    ASSERT_FALSE(mapped("libexemplar_video_mp4")) << "loaded before any video was touched";
    write_pngs();
    auto pngs = FrameSequence::from_pattern(path("frames/%02d.png"), 0, 2);
    ASSERT_TRUE(pngs.ok()) << pngs.status().message();
    ASSERT_TRUE(pngs->read(1).ok());
    EXPECT_FALSE(mapped("libexemplar_video_mp4")) << "image sequences need no codec";
    // Debian's OpenImageIO links videoio itself; without it nothing but the plugin may.
    if (!mapped("libOpenImageIO")) {
        EXPECT_FALSE(mapped("libopencv_videoio"));
    }

    // The tests find the build tree's plugin through EXEMPLAR_PLUGIN_DIR (tests/plugin_dir.cpp).
    const Status support = check_video_support(path("clip.mp4"));
    ASSERT_TRUE(support.is_ok()) << support.message();
    EXPECT_TRUE(mapped("libexemplar_video_mp4"));
    EXPECT_TRUE(mapped("libopencv_videoio"));
    EXPECT_TRUE(mp4_writing_supported()) << "the MP4 round trips would be skipped";

    // Reading and writing go through the plugin.
    write_mp4("clip.mp4");
    auto clip = FrameSequence::from_video(path("clip.mp4"));
    ASSERT_TRUE(clip.ok()) << clip.status().message();
    EXPECT_EQ(clip->size(), 3);
    auto last = clip->read(2);
    ASSERT_TRUE(last.ok()) << last.status().message();
    EXPECT_EQ(last->width(), 32);
    EXPECT_EQ(last->channels(), 3);
}

TEST_F(VideoPlugin, OnlyThePluginLinksVideoio) {
    const auto needs_videoio = [&](const std::string& binary) {
        const ProcessRun r = run("env", "readelf", {"-d", binary});
        EXPECT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.out.find("(NEEDED)"), std::string::npos) << binary;
        return r.out.find("libopencv_videoio") != std::string::npos;
    };
    EXPECT_FALSE(needs_videoio(kExemplar));
    EXPECT_FALSE(needs_videoio(fs::read_symlink("/proc/self/exe").string()));
    EXPECT_TRUE(needs_videoio(kPlugin));
}

TEST_F(VideoPlugin, MissingPluginIsAOneLineErrorNamingTheVideo) {
    // Every plugin but the codec (animate estimates flow with the OpenCV plugin).
    fs::create_directories(path("no_codec"));
    for (const std::string& name : kOtherPlugins) {
        fs::create_symlink(fs::path(kPlugin).parent_path() / name, path("no_codec/" + name));
    }
    const std::string env = "env EXEMPLAR_PLUGIN_DIR=" + quoted(path("no_codec"));
    const std::string reason =
        "video support is not available (libexemplar_video_mp4.so: "
        "not found in " +
        path("no_codec") + " (set by EXEMPLAR_PLUGIN_DIR))";

    // Video frames: the error names the video, whatever its contents.
    std::ofstream(path("clip.mp4")) << "any bytes: the plugin is needed to look at them";
    ProcessRun r = run(env, kExemplar, {"animate", job(path("clip.mp4")), "-q"});
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("clip.mp4") + ": " + reason + "\n");

    // An MP4 output: refused before any frame is solved.
    write_pngs();
    r = run(env, kExemplar,
            {"animate", job(path("frames/%02d.png"), path("out/result.mp4")), "-q"});
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("out/result.mp4") + ": " + reason + "\n");
    EXPECT_TRUE(fs::is_empty(path("out")));

    // Image sequences do not need it.
    r = run(env, kExemplar, {"animate", job(path("frames/%02d.png")), "-q"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(path("out/02.png")));
}

TEST_F(VideoPlugin, ExecutableFindsThePluginBesideIt) {
    write_mp4("clip.mp4");
    const ProcessRun r = run("env -u EXEMPLAR_PLUGIN_DIR", kExemplar,
                             {"animate", job(path("clip.mp4"), path("out/result.mp4")), "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    auto result = FrameSequence::from_video(path("out/result.mp4"));
    ASSERT_TRUE(result.ok()) << result.status().message();
    EXPECT_EQ(result->size(), 3);
}

TEST_F(VideoPlugin, InstalledExecutableFindsThePluginInLibExemplar) {
    const ProcessRun install =
        run("env", EXEMPLAR_CMAKE, {"--install", EXEMPLAR_BUILD_DIR, "--prefix", path("prefix")});
    ASSERT_EQ(install.code, 0) << install.err;
    const fs::path installed = dir_ / "prefix" / "bin" / "exemplar";
    ASSERT_TRUE(fs::exists(installed)) << install.out;
    write_mp4("clip.mp4");
    // animate estimates flow (the OpenCV plugin) and writes the MP4 (the codec plugin).
    ProcessRun r = run("env -u EXEMPLAR_PLUGIN_DIR", installed.string(),
                       {"animate", job(path("clip.mp4"), path("out/result.mp4")), "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    auto result = FrameSequence::from_video(path("out/result.mp4"));
    ASSERT_TRUE(result.ok()) << result.status().message();
    EXPECT_EQ(result->size(), 3);
    // The renderer (the Embree plugin).
    r = run("env -u EXEMPLAR_PLUGIN_DIR", installed.string(),
            {"render", "--scene", "sphere-on-table", "--width", "16", "--height", "12", "--spp",
             "1", "-o", path("out/sphere.exr"), "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(path("out/sphere.exr")));
}

// The same fixture for the other plugins.
using Plugins = VideoPlugin;

TEST_F(Plugins, TheCommandLinksNoneOfTheirLibraries) {
    const auto needed = [&](const std::string& binary) {
        const ProcessRun r = run("env", "readelf", {"-d", binary});
        EXPECT_EQ(r.code, 0) << r.err;
        return r.out;
    };
    const std::string command = needed(kExemplar);
    for (const char* library : {"libopencv_", "libembree", "libcairo", "libOpenEXR", "libtiff"}) {
        EXPECT_EQ(command.find(library), std::string::npos) << library;
    }
    const fs::path folder = fs::path(kPlugin).parent_path();
    EXPECT_NE(needed((folder / "libexemplar_opencv.so").string()).find("libopencv_video"),
              std::string::npos);
    EXPECT_NE(needed((folder / "libexemplar_render_embree.so").string()).find("libembree3"),
              std::string::npos);
    EXPECT_NE(needed((folder / "libexemplar_cairo.so").string()).find("libcairo"),
              std::string::npos);
    EXPECT_NE(needed((folder / "libexemplar_openexr.so").string()).find("libOpenEXR"),
              std::string::npos);
    EXPECT_NE(needed((folder / "libexemplar_tiff.so").string()).find("libtiff"), std::string::npos);
}

// ctest runs every test in a fresh process, so nothing was loaded before.
TEST_F(Plugins, LoadedOnFirstUseOnly) {
    ASSERT_FALSE(mapped("libexemplar_opencv")) << "loaded before any flow was estimated";
    ASSERT_FALSE(mapped("libexemplar_render_embree")) << "loaded before any render";
    auto flow = estimate_flow(frame(0), frame(1), {});
    ASSERT_TRUE(flow.ok()) << flow.status().message();
    EXPECT_TRUE(mapped("libexemplar_opencv"));
    EXPECT_TRUE(mapped("libopencv_video"));
    EXPECT_FALSE(mapped("libexemplar_render_embree")) << "flow needs no renderer";

    auto scene = render::builtin_scene("sphere-on-table");
    ASSERT_TRUE(scene.ok()) << scene.status().message();
    render::RenderOptions options;
    options.width = 16;
    options.height = 12;
    options.samples_per_pixel = 1;
    auto buffers = render::render(*scene, options);
    ASSERT_TRUE(buffers.ok()) << buffers.status().message();
    EXPECT_TRUE(mapped("libexemplar_render_embree"));
    EXPECT_TRUE(mapped("libembree3"));

    ASSERT_FALSE(mapped("libexemplar_openexr")) << "loaded before any EXR file";
    ASSERT_FALSE(mapped("libexemplar_tiff")) << "loaded before any TIFF file";
    ASSERT_TRUE(save_image(buffers->fullgi, path("fullgi.png")).is_ok());
    EXPECT_FALSE(mapped("libexemplar_openexr")) << "PNG files need no OpenEXR";
    ASSERT_TRUE(save_image(buffers->fullgi, path("fullgi.exr")).is_ok());
    EXPECT_TRUE(mapped("libexemplar_openexr"));
    EXPECT_TRUE(mapped("libOpenEXR"));
    EXPECT_FALSE(mapped("libexemplar_tiff")) << "EXR files need no libtiff";
    ASSERT_TRUE(save_image(buffers->fullgi, path("fullgi.tif")).is_ok());
    EXPECT_TRUE(mapped("libexemplar_tiff"));
}

TEST_F(Plugins, PlainVerbsNeedNoneAndOthersFailWithOneLine) {
    fs::create_directories(path("none"));
    const std::string env = "env EXEMPLAR_PLUGIN_DIR=" + quoted(path("none"));
    const auto reason = [&](const std::string& file, const std::string& what) {
        return what + " is not available (" + file + ": not found in " + path("none") +
               " (set by EXEMPLAR_PLUGIN_DIR))";
    };
    write_pngs();
    ProcessRun r = run(env, kExemplar,
                       {"stylize", "--style", path("frames/00.png"), "--size", "16x12", "-o",
                        path("out/stylized.png"), "-q"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(path("out/stylized.png")));

    r = run(env, kExemplar,
            {"flow", "--from", path("frames/00.png"), "--to", path("frames/01.png"), "-o",
             path("out/f.flo"), "-q"});
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: optical flow: " + reason("libexemplar_opencv.so", "OpenCV") + "\n");

    r = run(env, kExemplar,
            {"render", "--scene", "sphere-on-table", "--width", "16", "--height", "12", "--spp",
             "1", "-o", path("out/sphere.exr"), "-q"});
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + reason("libexemplar_render_embree.so", "rendering") + "\n");
    EXPECT_FALSE(fs::exists(path("out/sphere.exr")));
}

}  // namespace
}  // namespace exemplar::video
