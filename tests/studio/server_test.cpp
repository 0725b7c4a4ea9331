// The studio's HTTP API against an in-process server on an ephemeral port, with httplib's client:
// the app, traversal attempts, uploads, sketch and paint sessions (the bytes of the library's own
// calls), jobs with progress events, cancel, the per-client bound and shutdown.

#include <gtest/gtest.h>
#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "exemplar/animate/animate.hpp"
#include "exemplar/fluid/fluid_range.hpp"
#include "exemplar/fluid/lazy_fluids.hpp"
#include "exemplar/fluid/simulate.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/noisy/noisy.hpp"
#include "exemplar/npr/npr.hpp"
#include "exemplar/npr/npr_range.hpp"
#include "exemplar/paint/directions.hpp"
#include "exemplar/paint/feature_brush.hpp"
#include "exemplar/paint/feature_fill.hpp"
#include "exemplar/paint/paint.hpp"
#include "exemplar/paint/vectorize_style.hpp"
#include "exemplar/stylit/stylit.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "file_bytes.hpp"
#include "jobs.hpp"
#include "sessions.hpp"
#include "studio.hpp"
#include "temp_dir.hpp"

namespace exemplar::studio {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A deterministic RGB texture with edges in several directions.
Image texture(int width, int height) {
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            image.at(x, y, 0) = ((x / 6 + y / 9) % 2) ? 0.9f : 0.2f;
            image.at(x, y, 1) = 0.5f + 0.4f * static_cast<float>(((x + 2 * y) / 5) % 2);
            image.at(x, y, 2) = static_cast<float>((x * 7 + y * 3) % 32) / 31.0f;
        }
    }
    return image;
}

// A size x size RGBA exemplar for LazyFluids: the texture inside a soft disc.
Image ink_exemplar(int size) {
    const Image ink = texture(size, size);
    Image exemplar(size, size, 4);
    const float centre = 0.5f * static_cast<float>(size - 1);
    const float radius = 0.425f * static_cast<float>(size);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            for (int c = 0; c < 3; ++c) exemplar.at(x, y, c) = ink.at(x, y, c);
            const float r =
                std::hypot(static_cast<float>(x) - centre, static_cast<float>(y) - centre);
            exemplar.at(x, y, 3) = std::clamp((radius - r) / 4.0f, 0.0f, 1.0f);
        }
    }
    return exemplar;
}

// `count` render frame folders `folder`/f0, f1, ... of width x height for npr: a tone ramp moving
// right by 3 px a frame, no lines, the backward motion and the disocclusion it leaves.
void write_render_frames(const std::filesystem::path& folder, int count, int width, int height) {
    for (int n = 0; n < count; ++n) {
        const std::filesystem::path frame = folder / *video::format_frame_path("f%d", n);
        std::filesystem::create_directories(frame);
        Image tone(width, height, 1), lines(width, height, 1), flow(width, height, 2),
            disocclusion(width, height, 1);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                tone.at(x, y, 0) =
                    static_cast<float>((x + 3 * n) % width) / static_cast<float>(width);
                flow.at(x, y, 0) = -3.0f;
                disocclusion.at(x, y, 0) = x < 3 ? 1.0f : 0.0f;
            }
        }
        ASSERT_TRUE(save_image(tone, (frame / "direct_diffuse.png").string()).is_ok());
        ASSERT_TRUE(save_image(lines, (frame / "lines.png").string()).is_ok());
        ASSERT_TRUE(save_image(disocclusion, (frame / "disocclusion.png").string()).is_ok());
        ASSERT_TRUE(save_flow(flow, (frame / "backward_flow.exr").string()).is_ok());
    }
}

// What the bidirectional loop and the paper layer read besides in the folders of
// write_render_frames: the forward motion (3 px right), the occlusion it leaves at the right
// edge, and a shape (alpha) of the left two thirds.
void write_loop_buffers(const std::filesystem::path& folder, int count, int width, int height) {
    for (int n = 0; n < count; ++n) {
        const std::filesystem::path frame = folder / *video::format_frame_path("f%d", n);
        Image flow(width, height, 2), occlusion(width, height, 1), alpha(width, height, 1);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                flow.at(x, y, 0) = 3.0f;
                occlusion.at(x, y, 0) = x >= width - 3 ? 1.0f : 0.0f;
                alpha.at(x, y, 0) = 3 * x < 2 * width ? 1.0f : 0.0f;
            }
        }
        ASSERT_TRUE(save_flow(flow, (frame / "forward_flow.exr").string()).is_ok());
        ASSERT_TRUE(save_image(occlusion, (frame / "occlusion.png").string()).is_ok());
        ASSERT_TRUE(save_image(alpha, (frame / "alpha.png").string()).is_ok());
    }
}

// A 64 x 64 grey dot pattern for npr: the texture's blue channel.
void write_dots(const std::filesystem::path& path) {
    Image dots(64, 64, 1);
    const Image tex = texture(64, 64);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) dots.at(x, y, 0) = tex.at(x, y, 2);
    }
    ASSERT_TRUE(save_image(dots, path.string()).is_ok());
}

// A painting stroke through `points`, `width` px wide (the other fields at their defaults).
paint::Stroke stroke_of(std::vector<paint::StrokePoint> points, float width) {
    paint::Stroke stroke;
    stroke.points = std::move(points);
    stroke.width_px = width;
    return stroke;
}

using exemplar::testing::file_bytes;

// Hidden files left anywhere under `folder` (the atomic writers' temporary files).
int hidden_files(const fs::path& folder) {
    int count = 0;
    for (const auto& e : fs::recursive_directory_iterator(folder)) {
        if (e.path().filename().string().front() == '.') ++count;
    }
    return count;
}

class StudioTest : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        fs::create_directories(dir_ / "ws");
        fs::create_directories(dir_ / "outside");
        std::ofstream(dir_ / "outside" / "secret.txt") << "secret";
        ASSERT_TRUE(save_image(texture(64, 48), (dir_ / "ws" / "tex.png").string()).is_ok());
    }
    void TearDown() override {
        stop();
        TempDirTest::TearDown();
    }

    void start(StudioOptions options = {}) {
        options.port = 0;
        options.workspace = (dir_ / "ws").string();
        options.threads = 2;
        auto server = StudioServer::create(options);
        ASSERT_TRUE(server.ok()) << server.status().message();
        server_ = std::move(*server);
        serving_ = std::thread([this] { server_->run(); });
        client_ = std::make_unique<httplib::Client>("127.0.0.1", server_->port());
        client_->set_default_headers({{"X-Studio-Client", "tab1"}});
        client_->set_read_timeout(60, 0);
    }
    void stop() {
        if (!server_) return;
        server_->shutdown();
        serving_.join();
        server_.reset();
    }
    httplib::Result post(const std::string& path, const json& body) {
        return client_->Post(path.c_str(), body.dump(), "application/json");
    }
    static json body_of(const httplib::Result& r) { return json::parse(r->body); }

    /// (key, bad value, a word the message must hold) of a request.
    using Refusals = std::vector<std::tuple<std::string, json, std::string>>;
    /// Posts `good` to `path` with each key set to its bad value in turn: every one is a 400
    /// whose one-line message holds the word (the parameter's name, mostly).
    void expect_refused(const std::string& path, const json& good, const Refusals& refusals) {
        for (const auto& [key, value, word] : refusals) {
            json bad = good;
            bad[key] = value;
            auto refused = post(path, bad);
            ASSERT_TRUE(refused);
            ASSERT_EQ(refused->status, 400) << key << ": " << refused->body;
            const std::string message = body_of(refused)["error"];
            EXPECT_NE(message.find(word), std::string::npos) << key << ": " << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }

    std::unique_ptr<StudioServer> server_;
    std::thread serving_;
    std::unique_ptr<httplib::Client> client_;
};

TEST_F(StudioTest, ServesTheEmbeddedAppAndItsInfo) {
    start();
    auto page = client_->Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("exemplar studio"), std::string::npos);
    EXPECT_NE(page->get_header_value("Content-Type").find("text/html"), std::string::npos);
    auto script = client_->Get("/app.js");
    ASSERT_TRUE(script);
    EXPECT_EQ(script->status, 200);
    EXPECT_NE(script->body.find("/api/paint/stroke"), std::string::npos);
    auto info = client_->Get("/api/info");
    ASSERT_TRUE(info);
    EXPECT_EQ(body_of(info)["max_jobs_per_client"], 2);
    auto files = client_->Get("/api/files");
    ASSERT_TRUE(files);
    EXPECT_EQ(body_of(files)["files"][0]["path"], "tex.png");
}

TEST_F(StudioTest, TraversalAttemptsReadAndWriteNothingOutside) {
    start();
    fs::create_directory_symlink(dir_ / "outside", dir_ / "ws" / "door");
    const std::string png = file_bytes(dir_ / "ws" / "tex.png");
    for (const char* path :
         {"/api/files/../outside/secret.txt", "/api/files/%2e%2e/outside/secret.txt",
          "/api/files/..%2foutside%2fsecret.txt", "/api/files/door/secret.txt",
          "/api/files//etc/passwd", "/api/files/%2Fetc%2Fpasswd", "/api/files/.hidden.png",
          "/api/files/a/%00/b.png", "/api/files/..%5c..%5coutside%5csecret.txt"}) {
        auto got = client_->Get(path);
        ASSERT_TRUE(got) << path;
        EXPECT_TRUE(got->status == 403 || got->status == 404) << path << ": " << got->status;
        EXPECT_EQ(got->body.find("secret\""), std::string::npos);
        EXPECT_NE(got->body, "secret") << path;
        auto put = client_->Put(path, png, "image/png");
        ASSERT_TRUE(put) << path;
        EXPECT_TRUE(put->status == 403 || put->status == 404) << path << ": " << put->status;
    }
    // Paths in JSON bodies go through the same check.
    auto paint = post("/api/paint/start",
                      {{"exemplar", "../outside/secret.txt"}, {"width", 8}, {"height", 8}});
    ASSERT_TRUE(paint);
    EXPECT_EQ(paint->status, 403);
    ASSERT_TRUE(post("/api/paint/start", {{"exemplar", "tex.png"}, {"width", 8}, {"height", 8}}));
    auto save = post("/api/paint/save", {{"output", "door/stolen.png"}});
    ASSERT_TRUE(save);
    EXPECT_EQ(save->status, 403);
    auto job = post("/api/jobs", {{"kind", "stylize"},
                                  {"style", "tex.png"},
                                  {"source", "tex.png"},
                                  {"target", "tex.png"},
                                  {"output", "../outside/out.png"}});
    ASSERT_TRUE(job);
    EXPECT_EQ(job->status, 403);
    // Only the two files that were there before.
    int outside = 0;
    for (const auto& e : fs::directory_iterator(dir_ / "outside")) {
        EXPECT_EQ(e.path().filename(), "secret.txt");
        ++outside;
    }
    EXPECT_EQ(outside, 1);
    EXPECT_EQ(file_bytes(dir_ / "outside" / "secret.txt"), "secret");
}

TEST_F(StudioTest, RequestsFromOtherSitesAndNamesAreRefused) {
    start();
    const std::string own = "127.0.0.1:" + std::to_string(server_->port());
    // Another site's page posting through the user's browser.
    auto cross = client_->Post("/api/paint/save", {{"Origin", "http://evil.example"}},
                               R"({"output": "x.png"})", "text/plain");
    ASSERT_TRUE(cross);
    EXPECT_EQ(cross->status, 403);
    EXPECT_NE(cross->body.find("other sites"), std::string::npos) << cross->body;
    // DNS rebinding: a foreign name that resolves here.
    httplib::Client rebound("127.0.0.1", server_->port());
    auto foreign = rebound.Get("/api/files", {{"Host", "evil.example"}});
    ASSERT_TRUE(foreign);
    EXPECT_EQ(foreign->status, 403);
    // The studio's own page: same origin, its own host name.
    auto own_page = client_->Get("/api/files", {{"Origin", "http://" + own}});
    ASSERT_TRUE(own_page);
    EXPECT_EQ(own_page->status, 200);
    auto by_name =
        rebound.Get("/api/info", {{"Host", "localhost:" + std::to_string(server_->port())}});
    ASSERT_TRUE(by_name);
    EXPECT_EQ(by_name->status, 200);
}

TEST_F(StudioTest, UploadsAreTypeCheckedAndSizeLimited) {
    StudioOptions options;
    options.max_upload_bytes = 64 * 1024;
    start(options);
    const std::string png = file_bytes(dir_ / "ws" / "tex.png");
    auto ok = client_->Put("/api/files/uploads/copy.png", png, "image/png");
    ASSERT_TRUE(ok);
    EXPECT_EQ(ok->status, 201) << ok->body;
    EXPECT_EQ(file_bytes(dir_ / "ws" / "uploads" / "copy.png"), png);

    auto text = client_->Put("/api/files/fake.png", "<svg onload=alert(1)>", "image/png");
    ASSERT_TRUE(text);
    EXPECT_EQ(text->status, 415);
    auto wrong = client_->Put("/api/files/fake.jpg", png, "image/jpeg");
    ASSERT_TRUE(wrong);
    EXPECT_EQ(wrong->status, 415);
    auto script = client_->Put("/api/files/x.html", png, "text/html");
    ASSERT_TRUE(script);
    EXPECT_EQ(script->status, 415);
    std::string big = png;
    big.resize(200 * 1024, 'x');
    auto large = client_->Put("/api/files/big.png", big, "image/png");
    ASSERT_TRUE(large);
    EXPECT_EQ(large->status, 413);
    for (const char* name : {"fake.png", "fake.jpg", "x.html", "big.png"}) {
        EXPECT_FALSE(fs::exists(dir_ / "ws" / name)) << name;
    }
    EXPECT_EQ(hidden_files(dir_ / "ws"), 0);
}

TEST_F(StudioTest, SketchSuggestsAfterEachStrokeAndUndoesAcceptedOnes) {
    start();
    // A wobbly horizontal line: the first suggestion straightens it.
    auto first = post("/api/sketch/stroke",
                      {{"points", {{100, 100}, {150, 102}, {200, 99}, {250, 101}, {300, 100}}}});
    ASSERT_TRUE(first);
    ASSERT_EQ(first->status, 200) << first->body;
    const json suggestions = body_of(first)["suggestions"];
    ASSERT_GE(suggestions.size(), 2u);
    EXPECT_FALSE(suggestions[0]["original"].get<bool>());
    EXPECT_TRUE(suggestions.back()["original"].get<bool>());
    const std::string straight = suggestions[0]["d"];
    EXPECT_EQ(std::count(straight.begin(), straight.end(), 'C'), 1)
        << "one straight segment: " << straight;
    // Cycle to the input itself and accept it.
    auto accepted = post("/api/sketch/accept", {{"index", suggestions.size() - 1}});
    ASSERT_TRUE(accepted);
    ASSERT_EQ(accepted->status, 200) << accepted->body;
    EXPECT_EQ(body_of(accepted)["paths"].size(), 1u);
    EXPECT_EQ(body_of(accepted)["paths"][0], suggestions.back()["d"]);
    // A second stroke ending near the first line's end, accepted as suggested.
    auto second = post("/api/sketch/stroke", {{"points", {{301, 103}, {302, 150}, {299, 200}}}});
    ASSERT_TRUE(second);
    ASSERT_EQ(second->status, 200);
    ASSERT_TRUE(post("/api/sketch/accept", {{"index", 0}}));
    EXPECT_EQ(body_of(client_->Get("/api/sketch"))["paths"].size(), 2u);
    auto undone = post("/api/sketch/undo", json::object());
    EXPECT_EQ(body_of(undone)["paths"].size(), 1u);
    EXPECT_TRUE(body_of(undone)["can_redo"].get<bool>());
    auto redone = post("/api/sketch/redo", json::object());
    EXPECT_EQ(body_of(redone)["paths"].size(), 2u);
    // Nothing pending any more; a bad stroke is one line.
    auto again = post("/api/sketch/accept", {{"index", 0}});
    EXPECT_EQ(again->status, 409);
    auto degenerate = post("/api/sketch/stroke", {{"points", {{5, 5}, {5, 5}}}});
    EXPECT_EQ(degenerate->status, 400);
    auto malformed = post("/api/sketch/stroke", {{"points", "M 0 0"}});
    EXPECT_EQ(malformed->status, 400);
    // Another tab has its own drawing.
    httplib::Client other("127.0.0.1", server_->port());
    other.set_default_headers({{"X-Studio-Client", "tab2"}});
    EXPECT_EQ(json::parse(other.Get("/api/sketch")->body)["paths"].size(), 0u);
}

// Compares an RGBA8 answer of the rectangle `rect` with the library's image: the bytes that
// differ from its rounding, and the answer's opaque pixels.
std::pair<int, int> compare_rgba(const std::string& body, const paint::PixelRect& rect,
                                 const Image& expected) {
    int differing = 0, opaque = 0;
    for (int y = rect.y0; y < rect.y1; ++y) {
        for (int x = rect.x0; x < rect.x1; ++x) {
            for (int c = 0; c < 4; ++c) {
                const auto got = static_cast<unsigned char>(body[static_cast<std::size_t>(
                    ((y - rect.y0) * (rect.x1 - rect.x0) + x - rect.x0) * 4 + c)]);
                const long want =
                    std::lround(std::clamp(expected.at(x, y, c), 0.0f, 1.0f) * 255.0f);
                differing += got != want;
                opaque += c == 3 && got == 255;
            }
        }
    }
    return {differing, opaque};
}

// The library's source for the studio's paint tool on `exemplar`: directions analysed once.
paint::PaintSource paint_source_of(const Image& exemplar) {
    auto field = paint::analyze_directions(exemplar, {}, 1);
    paint::PaintSource source;
    source.image = exemplar;
    if (field.ok()) source.directions = paint::direction_angles(*field);
    return source;
}

TEST_F(StudioTest, PaintStrokesRepaintTheTouchedRectangleAsTheLibraryDoes) {
    start();
    auto started = post("/api/paint/start",
                        {{"exemplar", "tex.png"}, {"width", 96}, {"height", 64}, {"seed", 3}});
    ASSERT_TRUE(started);
    ASSERT_EQ(started->status, 200) << started->body;
    const json stroke = {{"points", {{10, 30}, {50, 34}, {80, 20}}}, {"width", 16}};
    auto painted = post("/api/paint/stroke", stroke);
    ASSERT_TRUE(painted);
    ASSERT_EQ(painted->status, 200) << painted->body;
    const std::string rect_text = painted->get_header_value("X-Rect");
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    ASSERT_EQ(std::sscanf(rect_text.c_str(), "%d,%d,%d,%d", &x0, &y0, &x1, &y1), 4) << rect_text;
    ASSERT_EQ(painted->body.size(), static_cast<std::size_t>((x1 - x0) * (y1 - y0) * 4));

    // The same library calls, made here: identical bytes.
    auto exemplar = load_image((dir_ / "ws" / "tex.png").string());
    ASSERT_TRUE(exemplar.ok());
    const paint::PaintSource source = paint_source_of(*exemplar);
    ASSERT_FALSE(source.directions.empty());
    paint::PaintCanvas canvas(96, 64);
    auto changed = canvas.add_stroke(stroke_of({{10, 30}, {50, 34}, {80, 20}}, 16.0f));
    ASSERT_TRUE(changed.ok());
    EXPECT_EQ(changed->x0, x0);
    EXPECT_EQ(changed->y1, y1);
    paint::PaintOptions options;
    options.seed = 3;
    auto expected =
        paint::repaint(source, canvas, Image(96, 64, 4), *changed, options, RunContext(1));
    ASSERT_TRUE(expected.ok());
    const auto [differing, painted_pixels] =
        compare_rgba(painted->body, {x0, y0, x1, y1}, expected->image);
    EXPECT_EQ(differing, 0);
    EXPECT_GT(painted_pixels, 40 * 12);

    // Undo clears it, redo brings the same bytes back.
    auto undone = post("/api/paint/undo", json::object());
    ASSERT_EQ(undone->get_header_value("X-Rect"), "0,0,96,64");
    EXPECT_EQ(undone->body, std::string(96 * 64 * 4, '\0'));
    auto redone = post("/api/paint/redo", json::object());
    const std::string all = redone->body;
    for (int y = y0; y < y1; ++y) {
        EXPECT_EQ(all.substr(static_cast<std::size_t>((y * 96 + x0) * 4),
                             static_cast<std::size_t>((x1 - x0) * 4)),
                  painted->body.substr(static_cast<std::size_t>((y - y0) * (x1 - x0) * 4),
                                       static_cast<std::size_t>((x1 - x0) * 4)));
    }
    // Saved as a PNG in the workspace.
    auto saved = post("/api/paint/save", {{"output", "outputs/painting.png"}});
    ASSERT_EQ(saved->status, 200) << saved->body;
    auto back = load_image((dir_ / "ws" / "outputs" / "painting.png").string());
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(back->channels(), 4);
    EXPECT_EQ(back->width(), 96);

    // Bad strokes and sizes are one line each.
    EXPECT_EQ(post("/api/paint/stroke", {{"points", {{1, 1}}}, {"width", -3}})->status, 400);
    EXPECT_EQ(
        post("/api/paint/start", {{"exemplar", "tex.png"}, {"width", 5000}, {"height", 8}})->status,
        400);
    EXPECT_EQ(
        post("/api/paint/start", {{"exemplar", "none.png"}, {"width", 8}, {"height", 8}})->status,
        404);
    httplib::Client other("127.0.0.1", server_->port());
    other.set_default_headers({{"X-Studio-Client", "tab2"}});
    EXPECT_EQ(other.Post("/api/paint/stroke", stroke.dump(), "application/json")->status, 409);
}

// A palette with one line feature: a dark wavy band on a grainy light ground.
TEST_F(StudioTest, PaintPreviewArrivesFirstAndTheFinalIsTheLibrarysRepaint) {
    start();
    ASSERT_EQ(post("/api/paint/start",
                   {{"exemplar", "tex.png"}, {"width", 96}, {"height", 64}, {"seed", 3}})
                  ->status,
              200);
    const json stroke = {{"points", {{10, 30}, {50, 34}, {80, 20}}}, {"width", 16}};
    auto previewed = post("/api/paint/preview", stroke);
    ASSERT_TRUE(previewed);
    ASSERT_EQ(previewed->status, 200) << previewed->body;
    auto exemplar = load_image((dir_ / "ws" / "tex.png").string());
    ASSERT_TRUE(exemplar.ok());
    const paint::PaintSource source = paint_source_of(*exemplar);
    paint::PaintCanvas canvas(96, 64);
    auto changed = canvas.add_stroke(stroke_of({{10, 30}, {50, 34}, {80, 20}}, 16.0f));
    ASSERT_TRUE(changed.ok());
    const std::string rect = std::to_string(changed->x0) + "," + std::to_string(changed->y0) + "," +
                             std::to_string(changed->x1) + "," + std::to_string(changed->y1);
    EXPECT_EQ(previewed->get_header_value("X-Rect"), rect);
    paint::PaintOptions options;
    options.seed = 3;
    const Image blank(96, 64, 4);
    auto preview =
        paint::preview_repaint(source, canvas, blank, *changed, options, 4, RunContext(1));
    auto final_ = paint::repaint(source, canvas, blank, *changed, options, RunContext(1));
    ASSERT_TRUE(preview.ok() && final_.ok());
    const auto [preview_differing, preview_opaque] =
        compare_rgba(previewed->body, *changed, preview->image);
    EXPECT_EQ(preview_differing, 0);
    EXPECT_GT(preview_opaque, 40 * 12);
    // The preview changed nothing: undo has no stroke to take back, the canvas is blank.
    EXPECT_EQ(post("/api/paint/undo", json::object())->body, std::string(96 * 64 * 4, '\0'));
    // Then the final pixels: the library's repaint, bytes equal; undo/redo step over it alone.
    auto painted = post("/api/paint/stroke", stroke);
    ASSERT_EQ(painted->status, 200) << painted->body;
    EXPECT_EQ(painted->get_header_value("X-Rect"), rect);
    EXPECT_EQ(compare_rgba(painted->body, *changed, final_->image).first, 0);
    EXPECT_NE(painted->body, previewed->body);
    EXPECT_EQ(post("/api/paint/undo", json::object())->body, std::string(96 * 64 * 4, '\0'));
    EXPECT_EQ(
        post("/api/paint/preview", {{"points", {{1, 1}, {9, 9}}}, {"width", 4}, {"reduction", 40}})
            ->status,
        400);
}

// The rectangle of an RGBA answer (its X-Rect header).
paint::PixelRect rect_of(const httplib::Result& answer) {
    paint::PixelRect rect;
    std::sscanf(answer->get_header_value("X-Rect").c_str(), "%d,%d,%d,%d", &rect.x0, &rect.y0,
                &rect.x1, &rect.y1);
    return rect;
}

// Three overlapping strokes across a 160x120 canvas.
const std::vector<std::vector<paint::StrokePoint>> kCrossing = {
    {{10, 60}, {80, 50}, {150, 64}}, {{20, 10}, {80, 60}, {140, 110}}, {{90, 8}, {84, 112}}};

// The largest difference between two images of the same shape (infinity otherwise).
float max_difference(const Image& a, const Image& b) {
    if (a.width() != b.width() || a.height() != b.height() || a.channels() != b.channels())
        return INFINITY;
    float most = 0.0f;
    for (int y = 0; y < a.height(); ++y) {
        for (int x = 0; x < a.width(); ++x) {
            for (int c = 0; c < a.channels(); ++c)
                most = std::max(most, std::abs(a.at(x, y, c) - b.at(x, y, c)));
        }
    }
    return most;
}

// The library's finals of strokes applied one by one with repaint, each from the one before.
std::vector<Image> sequential_repaints(const Image& exemplar, int width, int height,
                                       const std::vector<paint::Stroke>& strokes,
                                       const paint::PaintOptions& options) {
    const paint::PaintSource source = paint_source_of(exemplar);
    paint::PaintCanvas canvas(width, height);
    std::vector<Image> finals;
    Image previous(width, height, 4);
    for (const paint::Stroke& stroke : strokes) {
        auto changed = canvas.add_stroke(stroke);
        EXPECT_TRUE(changed.ok());
        auto painted = paint::repaint(source, canvas, previous, *changed, options, RunContext(1));
        EXPECT_TRUE(painted.ok());
        previous = painted->image;
        finals.push_back(previous);
    }
    return finals;
}

TEST_F(StudioTest, QuickStrokesAreFinalInOrderAndPreviewsShowNothingOlder) {
    start();
    ASSERT_EQ(post("/api/paint/start",
                   {{"exemplar", "tex.png"}, {"width", 160}, {"height", 120}, {"seed", 5}})
                  ->status,
              200);
    // As the page does on each pen-up: the preview, then the final posted without waiting for
    // it (on its own connection); the next stroke follows at once. The test waits only until
    // the server has queued each final (GET /api/paint), so the order is the strokes'.
    std::vector<paint::Stroke> strokes;
    std::vector<httplib::Result> previews;
    std::vector<std::optional<httplib::Result>> finals(kCrossing.size());
    std::vector<std::thread> posting;
    for (std::size_t k = 0; k < kCrossing.size(); ++k) {
        strokes.push_back(stroke_of(kCrossing[k], 18.0f));
        json points = json::array();
        for (const paint::StrokePoint& p : kCrossing[k]) points.push_back({p.x, p.y});
        const json stroke = {{"points", points}, {"width", 18}};
        previews.push_back(post("/api/paint/preview", stroke));
        ASSERT_EQ(previews.back()->status, 200) << previews.back()->body;
        posting.emplace_back([this, k, stroke, &finals] {
            httplib::Client own("127.0.0.1", server_->port());
            own.set_default_headers({{"X-Studio-Client", "tab1"}});
            own.set_read_timeout(60, 0);
            finals[k].emplace(own.Post("/api/paint/stroke", stroke.dump(), "application/json"));
        });
        for (;;) {
            auto state = client_->Get("/api/paint");
            ASSERT_EQ(state->status, 200);
            if (body_of(state)["strokes"] == k + 1) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    }
    for (std::thread& t : posting) t.join();

    auto exemplar = load_image((dir_ / "ws" / "tex.png").string());
    ASSERT_TRUE(exemplar.ok());
    paint::PaintOptions options;
    options.seed = 5;
    const std::vector<Image> expected = sequential_repaints(*exemplar, 160, 120, strokes, options);
    for (std::size_t k = 0; k < strokes.size(); ++k) {
        // Each final is the library's repaint from the one before: identical bytes.
        ASSERT_TRUE(finals[k] && *finals[k]);
        const httplib::Result& final_ = *finals[k];
        ASSERT_EQ(final_->status, 200) << final_->body;
        EXPECT_EQ(compare_rgba(final_->body, rect_of(final_), expected[k]).first, 0) << k;
        if (k == 0) continue;
        // A preview shows no pixel older than the stroke before it: wherever that stroke
        // painted, the preview holds paint (its final or its preview), never the blank canvas
        // from before it.
        const paint::PixelRect r = rect_of(previews[k]);
        int older = 0, overlap = 0;
        for (int y = r.y0; y < r.y1; ++y) {
            for (int x = r.x0; x < r.x1; ++x) {
                if (expected[k - 1].at(x, y, 3) < 0.5f) continue;
                ++overlap;
                const auto alpha =
                    static_cast<unsigned char>(previews[k]->body[static_cast<std::size_t>(
                        ((y - r.y0) * (r.x1 - r.x0) + x - r.x0) * 4 + 3)]);
                older += alpha == 0;
            }
        }
        EXPECT_GT(overlap, 100) << k;
        EXPECT_EQ(older, 0) << k;
    }
    // The whole painting is the third final; undo steps back to the second.
    auto undone = post("/api/paint/undo", json::object());
    EXPECT_EQ(compare_rgba(undone->body, {0, 0, 160, 120}, expected[1]).first, 0);
    auto redone = post("/api/paint/redo", json::object());
    EXPECT_EQ(compare_rgba(redone->body, {0, 0, 160, 120}, expected[2]).first, 0);
}

// The painting pipeline itself, where a test can act in the middle of a repaint (its progress).
class PaintPipelineTest : public ::testing::Test {
protected:
    void SetUp() override {
        auto session = PaintSession::start(texture(64, 48), 160, 120, options(), 2);
        ASSERT_TRUE(session.ok()) << session.status().message();
        pipeline_ = std::make_unique<PaintPipeline>(std::move(*session));
        for (const auto& points : kCrossing) strokes_.push_back(stroke_of(points, 18.0f));
    }
    static paint::PaintOptions options() {
        paint::PaintOptions o;
        o.seed = 5;
        return o;
    }
    // The whole painting as an undo or redo answers it.
    static PaintPipeline::Answer keep(Image& into) {
        return [&into](const Image& image, const paint::PixelRect&) { into = image; };
    }
    std::unique_ptr<PaintPipeline> pipeline_;
    std::vector<paint::Stroke> strokes_;
};

TEST_F(PaintPipelineTest, UndoStopsTheRunningRepaintAndKeepsThePaintingBefore) {
    const std::vector<Image> expected =
        sequential_repaints(texture(64, 48), 160, 120, strokes_, options());
    ASSERT_TRUE(pipeline_->stroke(strokes_[0], RunContext(2), {}).is_ok());
    // The second stroke is undone at its repaint's first progress event: the repaint stops and
    // the stroke answers Cancelled; nothing of it is kept (redo has nothing to bring back).
    Image after_undo;
    std::thread undoing;
    RunContext context(2);
    bool undone_first = false;
    context.progress = [&](const ProgressEvent&) {
        if (undoing.joinable()) return;
        undoing = std::thread([&] { pipeline_->undo(keep(after_undo)); });
        while (pipeline_->counts().pending != 0) std::this_thread::yield();
        undone_first = true;
    };
    const Status second = pipeline_->stroke(strokes_[1], context, {});
    undoing.join();
    EXPECT_TRUE(undone_first);
    EXPECT_EQ(second.code(), ErrorCode::Cancelled) << second.message();
    ASSERT_EQ(after_undo.width(), 160);
    EXPECT_EQ(max_difference(after_undo, expected[0]), 0.0f);
    Image after_redo;
    pipeline_->redo(keep(after_redo));
    EXPECT_EQ(max_difference(after_redo, expected[0]), 0.0f);
    // The painting goes on from there as if the stroke had never been sent.
    Image last;
    ASSERT_TRUE(pipeline_->stroke(strokes_[1], RunContext(2), keep(last)).is_ok());
    EXPECT_EQ(max_difference(last, expected[1]), 0.0f);
}

TEST_F(PaintPipelineTest, UndoDropsTheNewestQueuedStrokeAndCancelStopsAll) {
    const std::vector<Image> expected =
        sequential_repaints(texture(64, 48), 160, 120, strokes_, options());
    // While the first stroke repaints, the second is queued behind it and undone: it never
    // runs and answers Cancelled; the first ends as the library's, which undo then answers.
    Status second;
    std::thread queued, undoing;
    Image first_final, after_undo;
    RunContext context(2);
    context.progress = [&](const ProgressEvent&) {
        if (queued.joinable()) return;
        queued = std::thread([&] { second = pipeline_->stroke(strokes_[1], RunContext(2), {}); });
        while (pipeline_->counts().pending != 2) std::this_thread::yield();
        undoing = std::thread([&] { pipeline_->undo(keep(after_undo)); });
        while (pipeline_->counts().pending != 1) std::this_thread::yield();
    };
    EXPECT_TRUE(pipeline_->stroke(strokes_[0], context, keep(first_final)).is_ok());
    queued.join();
    undoing.join();
    EXPECT_EQ(second.code(), ErrorCode::Cancelled);
    EXPECT_EQ(max_difference(first_final, expected[0]), 0.0f);
    EXPECT_EQ(max_difference(after_undo, expected[0]), 0.0f);

    // cancel() (a new painting replaces this one) stops the running repaint and the queued
    // stroke alike, and refuses new ones; the painting keeps its last final.
    context.progress = [&](const ProgressEvent&) {
        if (queued.joinable()) return;
        queued = std::thread([&] { second = pipeline_->stroke(strokes_[2], RunContext(2), {}); });
        while (pipeline_->counts().pending != 2) std::this_thread::yield();
        pipeline_->cancel();
    };
    const Status running = pipeline_->stroke(strokes_[1], context, {});
    queued.join();
    EXPECT_EQ(running.code(), ErrorCode::Cancelled);
    EXPECT_EQ(second.code(), ErrorCode::Cancelled);
    EXPECT_EQ(pipeline_->stroke(strokes_[2], RunContext(2), {}).code(), ErrorCode::Cancelled);
    Image last;
    pipeline_->settled(keep(last));
    EXPECT_EQ(max_difference(last, expected[0]), 0.0f);
}

Image band_palette() {
    Image image(200, 64, 3);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 200; ++x) {
            const float centre = 32.0f + 3.0f * std::sin(static_cast<float>(x) * 0.11f);
            const bool band = std::abs(static_cast<float>(y) - centre) < 4.0f + (x % 17) * 0.15f;
            const float grain = static_cast<float>((x * 37 + y * 91) % 23) / 23.0f;
            for (int c = 0; c < 3; ++c) {
                image.at(x, y, c) = band ? 0.1f + 0.1f * grain + 0.05f * c : 0.8f + 0.15f * grain;
            }
        }
    }
    return image;
}

TEST(StepSlotTest, UndoCancelsTheNewestStepAndACancelledStepKeepsNothing) {
    StepSlot slot;
    const auto first = slot.begin();
    const auto second = slot.begin();
    EXPECT_TRUE(slot.cancel_newest());
    EXPECT_TRUE(second->cancelled());
    EXPECT_FALSE(first->cancelled());
    EXPECT_FALSE(slot.finish(second));
    EXPECT_TRUE(slot.finish(first));
    EXPECT_FALSE(slot.cancel_newest());  // nothing left to stop: undo steps back instead
    const auto third = slot.begin();
    slot.cancel_all();
    EXPECT_FALSE(slot.finish(third));

    // A brush stroke whose token is set stops and leaves the painting as it was.
    auto session = BrushSession::start(band_palette(), stroke_of({{20, 32}, {180, 32}}, 24.0f), 160,
                                       80, {}, true, 1);
    ASSERT_TRUE(session.ok()) << session.status().message();
    RunContext context(1);
    context.cancel = third.get();
    auto stopped = session->stroke(stroke_of({{10, 40}, {150, 44}}, 24.0f), context);
    EXPECT_EQ(stopped.status().code(), ErrorCode::Cancelled);
    EXPECT_EQ(max_difference(session->image(), Image(160, 80, 4)), 0.0f);
}

TEST_F(StudioTest, BrushStrokesPaintAsExemplarBrushDoes) {
    ASSERT_TRUE(save_image(band_palette(), (dir_ / "ws" / "band.png").string()).is_ok());
    start();
    const json selection = {{"points", {{8, 32}, {100, 32}, {192, 32}}}, {"width", 14}};
    auto started = post("/api/brush/start", {{"palette", "band.png"},
                                             {"feature", selection},
                                             {"width", 160},
                                             {"height", 120},
                                             {"seed", 5}});
    ASSERT_TRUE(started);
    ASSERT_EQ(started->status, 200) << started->body;
    EXPECT_GE(body_of(started)["feature"].size(), 10u);
    const json paths[] = {{{"points", {{10, 20}, {80, 60}, {150, 40}}}, {"width", 18}},
                          {{"points", {{20, 100}, {140, 90}}}, {"width", 12}}};
    for (const json& path : paths) {
        auto painted = post("/api/brush/stroke", path);
        ASSERT_TRUE(painted);
        ASSERT_EQ(painted->status, 200) << painted->body;
        EXPECT_FALSE(painted->get_header_value("X-Rect").empty());
    }
    ASSERT_EQ(post("/api/brush/save", {{"output", "brushed.png"}})->status, 200);

    // `exemplar brush`'s library calls with the same feature and paths: the same bytes.
    auto palette = load_image((dir_ / "ws" / "band.png").string());
    ASSERT_TRUE(palette.ok());
    paint::FeatureBrushOptions options;
    options.seed = 5;
    auto feature = paint::pick_line_feature(
        *palette, stroke_of({{8, 32}, {100, 32}, {192, 32}}, 14.0f), options, true, 1);
    ASSERT_TRUE(feature.ok()) << feature.status().message();
    const paint::Stroke strokes[] = {stroke_of({{10, 20}, {80, 60}, {150, 40}}, 18.0f),
                                     stroke_of({{20, 100}, {140, 90}}, 12.0f)};
    auto expected = paint::paint_feature(*feature, strokes, 160, 120, 0.0f, 1);
    ASSERT_TRUE(expected.ok()) << expected.status().message();
    auto saved = load_image((dir_ / "ws" / "brushed.png").string());
    ASSERT_TRUE(saved.ok());
    int differing = 0, opaque = 0;
    for (int y = 0; y < 120; ++y) {
        for (int x = 0; x < 160; ++x) {
            for (int c = 0; c < 4; ++c) {
                const float want =
                    std::round(std::clamp(expected->at(x, y, c), 0.0f, 1.0f) * 255.0f);
                differing += std::round(saved->at(x, y, c) * 255.0f) != want;
            }
            opaque += saved->at(x, y, 3) > 0.99f;
        }
    }
    EXPECT_EQ(differing, 0);
    EXPECT_GT(opaque, 1500);
    // Undo the second stroke: the first alone, as paint_feature paints it.
    auto undone = post("/api/brush/undo", json::object());
    ASSERT_EQ(undone->status, 200);
    auto first = paint::paint_feature(*feature, std::span(strokes, 1), 160, 120, 0.0f, 1);
    ASSERT_TRUE(first.ok());
    EXPECT_EQ(static_cast<unsigned char>(undone->body[(100 * 160 + 80) * 4 + 3]), 0)
        << "the second stroke is gone";
    const long alpha = std::lround(first->at(80, 60, 3) * 255.0f);
    EXPECT_EQ(static_cast<unsigned char>(undone->body[(60 * 160 + 80) * 4 + 3]), alpha);
    EXPECT_EQ(post("/api/brush/stroke", {{"points", {{1, 1}}}, {"width", 0}})->status, 400);
}

// Reads a job's event stream until its `end` event; `on_progress` is called for each progress
// event (with the count so far).
json follow(int port, const std::string& id, const std::function<void(int)>& on_progress = {},
            const std::function<void(const json&)>& on_frame = {}) {
    httplib::Client events("127.0.0.1", port);
    events.set_read_timeout(120, 0);
    std::string buffer;
    json end;
    json frames = json::array();
    int progress = 0;
    auto got = events.Get(
        ("/api/jobs/" + id + "/events").c_str(), [&](const char* data, std::size_t length) {
            buffer.append(data, length);
            for (std::size_t cut; (cut = buffer.find("\n\n")) != std::string::npos;) {
                const std::string event = buffer.substr(0, cut);
                buffer.erase(0, cut + 2);
                const std::size_t data_at = event.find("data: ");
                if (event.starts_with("event: frame")) {
                    frames.push_back(json::parse(event.substr(data_at + 6)));
                    if (on_frame) on_frame(frames.back());
                } else if (event.starts_with("event: progress")) {
                    ++progress;
                    if (on_progress) on_progress(progress);
                } else if (event.starts_with("event: end")) {
                    end = json::parse(event.substr(data_at + 6));
                    end["progress_events"] = progress;
                    end["frames"] = frames;
                }
            }
            return true;
        });
    EXPECT_TRUE(got);
    return end;
}

// The region image of one polygon, as the fill endpoint makes it.
Image region_of(std::vector<paint::StrokePoint> polygon, int width, int height) {
    return paint::polygon_mask(std::span(&polygon, 1), width, height);
}

TEST_F(StudioTest, BrushFillsARegionAsExemplarFillDoes) {
    ASSERT_TRUE(save_image(band_palette(), (dir_ / "ws" / "band.png").string()).is_ok());
    start();
    const json selection = {{"points", {{8, 32}, {100, 32}, {192, 32}}}, {"width", 14}};
    ASSERT_EQ(
        post("/api/brush/start",
             {{"palette", "band.png"}, {"feature", selection}, {"width", 120}, {"height", 90}})
            ->status,
        200);
    // A source region over the band in the palette, a target region on the canvas.
    const json fill = {{"source", {{20, 10}, {140, 14}, {150, 56}, {24, 50}}},
                       {"target", {{30, 20}, {100, 24}, {90, 80}, {20, 70}}},
                       {"rotations", 3},
                       {"seed", 4}};
    auto filled = post("/api/brush/fill", fill);
    ASSERT_TRUE(filled);
    ASSERT_EQ(filled->status, 200) << filled->body;
    EXPECT_EQ(filled->get_header_value("X-Rect"), "20,20,100,80");

    // `exemplar fill`'s library call with the blank painting as the canvas: the same pixels.
    auto palette = load_image((dir_ / "ws" / "band.png").string());
    ASSERT_TRUE(palette.ok());
    paint::FeatureFillOptions options;
    options.rotations = 3;
    options.seed = 4;
    auto expected = paint::fill_with_palette(
        *palette, region_of({{20, 10}, {140, 14}, {150, 56}, {24, 50}}, 200, 64), Image(120, 90, 4),
        region_of({{30, 20}, {100, 24}, {90, 80}, {20, 70}}, 120, 90), options, RunContext(1));
    ASSERT_TRUE(expected.ok()) << expected.status().message();
    ASSERT_EQ(filled->body.size(), std::size_t{80} * 60 * 4);
    int differing = 0, opaque = 0;
    for (int y = 20; y < 80; ++y) {
        for (int x = 20; x < 100; ++x) {
            for (int c = 0; c < 4; ++c) {
                const auto want = static_cast<unsigned char>(
                    std::lround(std::clamp(expected->at(x, y, c), 0.0f, 1.0f) * 255.0f));
                const auto got =
                    static_cast<unsigned char>(filled->body[((y - 20) * 80 + (x - 20)) * 4 + c]);
                differing += got != want;
            }
            opaque += expected->at(x, y, 3) > 0.99f;
        }
    }
    EXPECT_EQ(differing, 0);
    EXPECT_GT(opaque, 2500);
    // Undo takes the fill back, redo brings it again.
    auto undone = post("/api/brush/undo", json::object());
    EXPECT_EQ(static_cast<unsigned char>(undone->body[(50 * 120 + 60) * 4 + 3]), 0);
    auto redone = post("/api/brush/redo", json::object());
    EXPECT_EQ(static_cast<unsigned char>(redone->body[(50 * 120 + 60) * 4 + 3]), 255);
    // Bad parameters: one line naming the parameter.
    expect_refused("/api/brush/fill", fill,
                   {{"target", {{1, 1}, {2, 2}}, "target: "},
                    {"source", "all", "source: "},
                    {"patch-size", 4, "patch-size: "},
                    {"rotations", "many", "rotations: "},
                    {"usage", "sometimes", "usage: "},
                    {"wobble", 1, "wobble: "},
                    {"target", {{-50, -50}, {-40, -50}, {-40, -40}}, "target"}});
    httplib::Client other("127.0.0.1", server_->port());
    other.set_default_headers({{"X-Studio-Client", "tab2"}});
    EXPECT_EQ(other.Post("/api/brush/fill", fill.dump(), "application/json")->status, 409);
}

TEST_F(StudioTest, JobsReportProgressAndWriteTheirOutput) {
    start();
    auto job = post("/api/jobs", {{"kind", "stylize"},
                                  {"style", "tex.png"},
                                  {"source", "tex.png"},
                                  {"target", "tex.png"},
                                  {"output", "outputs/stylized.png"},
                                  {"quality", "fast"}});
    ASSERT_TRUE(job);
    ASSERT_EQ(job->status, 202) << job->body;
    const json end = follow(server_->port(), body_of(job)["id"]);
    EXPECT_EQ(end["state"], "done") << end.dump();
    EXPECT_GE(end["progress_events"].get<int>(), 2) << "the start and the engine's";
    EXPECT_TRUE(fs::exists(dir_ / "ws" / "outputs" / "stylized.png"));
    // A late listener still sees the whole log.
    EXPECT_EQ(follow(server_->port(), body_of(job)["id"])["state"], "done");
    auto list = client_->Get("/api/jobs");
    EXPECT_EQ(body_of(list)["jobs"][0]["state"], "done");
    // Bad jobs are refused at once.
    EXPECT_EQ(post("/api/jobs", {{"kind", "bake"}})->status, 400);
    EXPECT_EQ(post("/api/jobs", {{"kind", "stylize"},
                                 {"style", "tex.png"},
                                 {"source", "tex.png"},
                                 {"target", "tex.png"},
                                 {"output", "o.png"},
                                 {"quality", "superb"}})
                  ->status,
              400);
}

TEST_F(StudioTest, NoisyJobsWriteTheLibrarysFrame) {
    start();
    auto job = post("/api/jobs", {{"kind", "noisy"},
                                  {"exemplar", "tex.png"},
                                  {"reference", "tex.png"},
                                  {"output", "outputs/noisy.png"},
                                  {"noise", 4},
                                  {"patch-size", 5},
                                  {"seed", 7},
                                  {"frame", 3}});
    ASSERT_TRUE(job);
    ASSERT_EQ(job->status, 202) << job->body;
    const json end = follow(server_->port(), body_of(job)["id"]);
    EXPECT_EQ(end["state"], "done") << end.dump();
    EXPECT_EQ(end["output"], "outputs/noisy.png");
    EXPECT_GE(end["progress_events"].get<int>(), 2) << "the start and the levels'";
    // The same bytes as the library's call and atomic writer.
    auto tex = load_image((dir_ / "ws" / "tex.png").string());
    ASSERT_TRUE(tex.ok());
    noisy::NoisyOptions options;
    options.noise = 4.0f;
    options.patch_size = 5;
    options.seed = 7;
    noisy::NoisyFrame frame;
    frame.reference = *tex;
    auto image = noisy::synthesize_frame(*tex, frame, options, 3, RunContext(1));
    ASSERT_TRUE(image.ok()) << image.status().message();
    ASSERT_TRUE(save_image(*image, (dir_ / "library.png").string()).is_ok());
    EXPECT_EQ(file_bytes(dir_ / "ws" / "outputs" / "noisy.png"), file_bytes(dir_ / "library.png"));
    // Bad parameters are refused at once with one line naming the parameter.
    const json good = {{"kind", "noisy"},
                       {"exemplar", "tex.png"},
                       {"reference", "tex.png"},
                       {"output", "o.png"},
                       {"noise", 4}};
    expect_refused("/api/jobs", good,
                   {{"noise", -1, "noise: "},
                    {"patch-size", 4, "patch-size: "},
                    {"filter", "gauss", "gauss"},
                    {"frame", 1.5, "frame: "},
                    {"wobble", 1, "wobble: "},
                    {"output", "o.txt", "output: "},
                    {"reference", "nope.png", "reference: "}});
    json no_noise = good;
    no_noise.erase("noise");
    EXPECT_EQ(post("/api/jobs", no_noise)->status, 400);
    EXPECT_FALSE(fs::exists(dir_ / "ws" / "o.png"));
}

// The first channel of a map file, as the command reads it; `levels` scales it to grey levels
// (a source map's 0..255).
Image map_of(const fs::path& file, float levels = 1.0f) {
    auto image = load_image(file.string());
    EXPECT_TRUE(image.ok()) << file;
    Image map(image->width(), image->height(), 1);
    for (int y = 0; y < map.height(); ++y) {
        for (int x = 0; x < map.width(); ++x) {
            map.at(x, y, 0) =
                levels == 1.0f ? image->at(x, y, 0) : std::round(image->at(x, y, 0) * levels);
        }
    }
    return map;
}

TEST_F(StudioTest, NoisyRangesWithSeveralMediaWriteTheLibrarysFrames) {
    // Three 40 x 32 reference frames 1..3, a second medium (the texture inverted), a source map
    // per frame (the second medium right of a moving boundary) and one noise map.
    const fs::path ws = dir_ / "ws";
    fs::create_directories(ws / "R");
    fs::create_directories(ws / "M");
    Image inverted = texture(64, 48);
    for (float& v : inverted.data()) v = 1.0f - v;
    ASSERT_TRUE(save_image(inverted, (ws / "inverted.png").string()).is_ok());
    Image noise(40, 32, 1);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 40; ++x) noise.at(x, y, 0) = static_cast<float>(x) / 39.0f;
    }
    ASSERT_TRUE(save_image(noise, (ws / "noise.png").string()).is_ok());
    for (int n = 1; n <= 3; ++n) {
        const Image tex = texture(40 + 4 * n, 32);
        Image frame(40, 32, 3), map(40, 32, 1);
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 40; ++x) {
                for (int c = 0; c < 3; ++c) frame.at(x, y, c) = tex.at(x + 4 * n, y, c);
                map.at(x, y, 0) = x >= 14 + 2 * n ? 1.0f / 255.0f : 0.0f;
            }
        }
        ASSERT_TRUE(
            save_image(frame, (ws / *video::format_frame_path("R/%d.png", n)).string()).is_ok());
        ASSERT_TRUE(
            save_image(map, (ws / *video::format_frame_path("M/%d.png", n)).string()).is_ok());
    }
    start();
    const json good = {{"kind", "noisy"},
                       {"exemplar", {"tex.png", "inverted.png"}},
                       {"frames", "R/%d.png"},
                       {"first", 1},
                       {"last", 3},
                       {"source-map", "M/%d.png"},
                       {"noise-map", "noise.png"},
                       {"output", "outputs/noisy/%d.png"},
                       {"noise", 3},
                       {"patch-size", 5},
                       {"seed", 4}};
    auto job = post("/api/jobs", good);
    ASSERT_EQ(job->status, 202) << job->body;
    const json end = follow(server_->port(), body_of(job)["id"]);
    ASSERT_EQ(end["state"], "done") << end.dump();
    ASSERT_EQ(end["frames"].size(), 3u);
    // The library's frames, each keyed by its number, in order.
    noisy::NoisyOptions options;
    options.noise = 3.0f;
    options.patch_size = 5;
    options.seed = 4;
    std::vector<noisy::NoisySource> media(2);
    media[0].image = *load_image((ws / "tex.png").string());
    media[1].image = *load_image((ws / "inverted.png").string());
    for (int n = 1; n <= 3; ++n) {
        const std::string output = *video::format_frame_path("outputs/noisy/%d.png", n);
        EXPECT_EQ(end["frames"][n - 1]["frame"], n);
        EXPECT_EQ(end["frames"][n - 1]["path"], output);
        noisy::NoisyFrame frame;
        frame.reference = *load_image((ws / *video::format_frame_path("R/%d.png", n)).string());
        frame.noise_map = map_of(ws / "noise.png");
        frame.source_map = map_of(ws / *video::format_frame_path("M/%d.png", n), 255.0f);
        auto image = noisy::synthesize_frame(media, frame, options, n, RunContext(1));
        ASSERT_TRUE(image.ok()) << image.status().message();
        const fs::path mine = dir_ / *video::format_frame_path("library%d.png", n);
        ASSERT_TRUE(save_image(*image, mine.string()).is_ok());
        EXPECT_TRUE(file_bytes(ws / output) == file_bytes(mine)) << "frame " << n;
    }

    // A folder of frames: its images in name order are frames 0, 1, ...
    auto folder = post("/api/jobs", {{"kind", "noisy"},
                                     {"exemplar", "tex.png"},
                                     {"frames", "R"},
                                     {"last", 1},
                                     {"output", "outputs/folder/%d.png"},
                                     {"noise", 3},
                                     {"patch-size", 5}});
    ASSERT_EQ(folder->status, 202) << folder->body;
    ASSERT_EQ(follow(server_->port(), body_of(folder)["id"])["state"], "done");
    options.seed = 1;
    for (int k = 0; k <= 1; ++k) {
        noisy::NoisyFrame frame;
        frame.reference = *load_image((ws / *video::format_frame_path("R/%d.png", k + 1)).string());
        auto image = noisy::synthesize_frame(media[0].image, frame, options, k, RunContext(1));
        ASSERT_TRUE(image.ok()) << image.status().message();
        const fs::path mine = dir_ / "folder.png";
        ASSERT_TRUE(save_image(*image, mine.string()).is_ok());
        EXPECT_TRUE(file_bytes(ws / *video::format_frame_path("outputs/folder/%d.png", k)) ==
                    file_bytes(mine))
            << "folder frame " << k;
    }
    EXPECT_FALSE(fs::exists(ws / "outputs" / "folder" / "2.png"));

    // Every path is resolved in the workspace: one outside is a 403 and nothing is written.
    ASSERT_TRUE(save_image(Image(40, 32, 1), (dir_ / "outside" / "1.png").string()).is_ok());
    const std::vector<std::pair<std::string, json>> outside = {
        {"frames", "../outside/%d.png"},
        {"frames", "../outside"},
        {"exemplar", {"tex.png", "../outside/1.png"}},
        {"source-map", "../outside/1.png"},
        {"noise-map", "../outside/%d.png"},
        {"output", "../outside/%d.png"},
        {"exemplar-orientation", {"../outside/o.exr", "../outside/p.exr"}}};
    for (const auto& [key, value] : outside) {
        json bad = good;
        bad[key] = value;
        if (key == "exemplar-orientation") bad["frame-orientation"] = "M/%d.png";
        auto refused = post("/api/jobs", bad);
        ASSERT_TRUE(refused);
        EXPECT_EQ(refused->status, 403) << key << ": " << refused->body;
    }
    // Bad parameters: one line naming the parameter (400).
    expect_refused("/api/jobs", good,
                   {{"last", 4, "frames: R/4.png"},
                    {"source-map", "nope/%d.png", "source-map: nope/1.png"},
                    {"noise-map", "nope.png", "noise-map: "},
                    {"frame", 2, "frame: "},
                    {"reference", "tex.png", "reference: "},
                    {"exemplar-orientation", "o.exr", "frame-orientation"},
                    {"frame-orientation", "M/%d.png", "frame-orientation: "},
                    {"output", "outputs/%d.txt", "output: "},
                    {"wobble", 1, "wobble: "}});
    json one_map_too_few = good;
    one_map_too_few.erase("source-map");
    auto refused = post("/api/jobs", one_map_too_few);
    EXPECT_EQ(refused->status, 400);
    EXPECT_EQ(body_of(refused)["error"],
              "source-map: is required with 2 exemplars (it chooses the medium of every pixel)");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "outside"), fs::directory_iterator()), 2);
}

// Light-path buffers of a small render: smooth shading that differs per buffer and per render.
Image buffer_of(int width, int height, int buffer, int render) {
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < 3; ++c) {
                const float u = static_cast<float>(x + 3 * render) / static_cast<float>(width);
                const float v = static_cast<float>(y) / static_cast<float>(height);
                image.at(x, y, c) = 0.5f + 0.45f * std::sin(3.0f * u * (buffer + 1) + 2.0f * v +
                                                            static_cast<float>(c + buffer));
            }
        }
    }
    return image;
}

TEST_F(StudioTest, StylitJobsWriteTheLibrarysImage) {
    // Two buffers per render: the exemplar render 64 x 48 (tex.png is its painting), the target
    // 56 x 40, in the workspace's stylit/ folder.
    fs::create_directories(dir_ / "ws" / "stylit");
    std::vector<LpeBuffer> source, target;
    for (int b = 0; b < 2; ++b) {
        for (int render = 0; render < 2; ++render) {
            const std::string name =
                (render == 0 ? "source_" : "target_") + std::to_string(b) + ".png";
            const Image image = render == 0 ? buffer_of(64, 48, b, 0) : buffer_of(56, 40, b, 1);
            ASSERT_TRUE(save_image(image, (dir_ / "ws" / "stylit" / name).string()).is_ok());
            auto loaded = load_image((dir_ / "ws" / "stylit" / name).string());
            ASSERT_TRUE(loaded.ok());
            (render == 0 ? source : target).push_back({name, name, std::move(*loaded)});
        }
    }
    start();
    const json good = {{"kind", "stylit"},
                       {"exemplar", "tex.png"},
                       {"source", {"stylit/source_0.png", "stylit/source_1.png"}},
                       {"target", {"stylit/target_0.png", "stylit/target_1.png"}},
                       {"output", "outputs/stylit.png"},
                       {"quality", "fast"},
                       {"seed", 3},
                       {"guidance-weight", 4}};
    auto job = post("/api/jobs", good);
    ASSERT_TRUE(job);
    ASSERT_EQ(job->status, 202) << job->body;
    const json end = follow(server_->port(), body_of(job)["id"]);
    EXPECT_EQ(end["state"], "done") << end.dump();
    EXPECT_GE(end["progress_events"].get<int>(), 2) << "the start and the engine's";
    // The same bytes as the library's call and atomic writer.
    auto painting = load_image((dir_ / "ws" / "tex.png").string());
    ASSERT_TRUE(painting.ok());
    StylitOptions options;
    options.synthesis = SynthesisOptions::preset(Quality::Fast);
    options.synthesis.seed = 3;
    options.guidance_weight = 4.0f;
    auto result = stylize_render(*painting, source, target, options, RunContext(1));
    ASSERT_TRUE(result.ok()) << result.status().message();
    ASSERT_TRUE(save_image(result->synthesis.image, (dir_ / "library.png").string()).is_ok());
    EXPECT_EQ(file_bytes(dir_ / "ws" / "outputs" / "stylit.png"), file_bytes(dir_ / "library.png"));
    // Preview: half size.
    json preview = good;
    preview["preview"] = true;
    preview["output"] = "outputs/preview.png";
    const json preview_end = follow(server_->port(), body_of(post("/api/jobs", preview))["id"]);
    EXPECT_EQ(preview_end["state"], "done") << preview_end.dump();
    auto half = load_image((dir_ / "ws" / "outputs" / "preview.png").string());
    ASSERT_TRUE(half.ok());
    EXPECT_EQ(half->width(), 28);
    // Bad parameters are refused at once with one line naming the parameter; paths outside the
    // workspace with 403.
    expect_refused("/api/jobs", good,
                   {{"guidance-weight", 101, "guidance-weight: "},
                    {"usage", "sometimes", "usage: "},
                    {"quality", "superb", "superb"},
                    {"preview", "yes", "preview: "},
                    {"preset", "maya", "preset: "},
                    {"wobble", 1, "wobble: "},
                    {"output", "o.txt", "output: "},
                    {"exemplar", "nope.png", "exemplar: "},
                    {"source", json::array(), "source: "},
                    {"source", {"stylit/source_0.png"}, "source has 1"},
                    {"target", {"stylit/target_0.png", "tex.png"}, "target"}});
    json outside = good;
    outside["target"] = {"stylit/target_0.png", "../outside/secret.txt"};
    EXPECT_EQ(post("/api/jobs", outside)->status, 403);
    EXPECT_FALSE(fs::exists(dir_ / "ws" / "o.png"));
}

TEST_F(StudioTest, AnimateJobsWriteEachFrameAsTheLibraryMakesIt) {
    // Three frames of a texture moving right by 2 px a frame, a grey style pair.
    fs::create_directories(dir_ / "ws" / "frames");
    const auto frame_path = [&](int n) {
        return dir_ / "ws" / "frames" / *video::format_frame_path("f%d.png", n);
    };
    const Image tex = texture(72, 40);
    for (int t = 0; t < 3; ++t) {
        Image frame(48, 32, 1);
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 48; ++x) frame.at(x, y, 0) = tex.at(x + 10 - 2 * t, y + 4, 2);
        }
        ASSERT_TRUE(save_image(frame, frame_path(t + 4).string()).is_ok());
    }
    Image style_input(40, 32, 1);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 40; ++x) style_input.at(x, y, 0) = tex.at(x, y, 1);
    }
    ASSERT_TRUE(save_image(style_input, (dir_ / "ws" / "si.png").string()).is_ok());
    start();
    const json good = {{"kind", "animate"},
                       {"frames", "frames/f%d.png"},
                       {"first", 4},
                       {"last", 6},
                       {"style-input", "si.png"},
                       {"style-output", "tex.png"},
                       {"quality", "fast"},
                       {"seed", 9},
                       {"levels", 2},
                       {"output", "outputs/anim/%03d.png"}};
    ASSERT_TRUE(save_image(texture(40, 32), (dir_ / "ws" / "tex.png").string()).is_ok());
    auto job = post("/api/jobs", good);
    ASSERT_TRUE(job);
    ASSERT_EQ(job->status, 202) << job->body;
    const json end = follow(server_->port(), body_of(job)["id"]);
    EXPECT_EQ(end["state"], "done") << end.dump();
    ASSERT_EQ(end["frames"].size(), 3u) << end.dump();
    EXPECT_EQ(end["frames"][0]["frame"], 6) << "the library hands frames over last first";
    EXPECT_EQ(end["frames"][0]["path"], "outputs/anim/006.png");
    auto list = body_of(client_->Get("/api/jobs"));
    EXPECT_EQ(list["jobs"][0]["outputs"].size(), 3u) << list.dump();

    // The library's call on the same frames: the same bytes, frame by frame.
    animate::AnimationInput input;
    input.style_input = *load_image((dir_ / "ws" / "si.png").string());
    input.style_output = *load_image((dir_ / "ws" / "tex.png").string());
    input.frame_count = 3;
    input.frame = [&](int t) { return load_image(frame_path(t + 4).string()); };
    animate::AnimateOptions options;
    options.synthesis = animate::animate_synthesis_options(Quality::Fast);
    options.synthesis.seed = 9;
    options.levels = 2;
    auto expected = animate::animate(input, options, RunContext(1));
    ASSERT_TRUE(expected.ok()) << expected.status().message();
    for (int t = 0; t < 3; ++t) {
        const fs::path mine = dir_ / *video::format_frame_path("library%d.png", t);
        ASSERT_TRUE(
            save_image(expected->frames[static_cast<std::size_t>(t)], mine.string()).is_ok());
        EXPECT_EQ(file_bytes(dir_ / "ws" / "outputs" / "anim" /
                             *video::format_frame_path("%03d.png", t + 4)),
                  file_bytes(mine))
            << "frame " << t + 4;
    }
    // Bad parameters: one line naming the parameter (400); paths outside the workspace: 403.
    expect_refused("/api/jobs", good,
                   {{"last", 3, "last: "},
                    {"last", 2000, "last: "},
                    {"first", 4.5, "first: "},
                    {"frames", "frames/f.png", "frames: "},
                    {"frames", "frames/g%d.png", "frames: frames/g4.png"},
                    {"levels", 0, "levels: "},
                    {"temporal-weight", -1, "temporal-weight: "},
                    {"quality", "superb", "superb"},
                    {"wobble", 1, "wobble: "},
                    {"output", "outputs/%d.txt", "output: "},
                    {"style-input", "nope.png", "style-input: "}});
    json outside = good;
    outside["output"] = "../outside/%04d.png";
    EXPECT_EQ(post("/api/jobs", outside)->status, 403);
}

TEST_F(StudioTest, FluidJobsSimulateAndTransferAsTheLibraryDoes) {
    ASSERT_TRUE(save_image(ink_exemplar(40), (dir_ / "ws" / "ink.png").string()).is_ok());
    start();
    // Targets: the built-in plume, 48 x 48, frames 0..3 (warm-up: the first frames are thin).
    auto simulated = post("/api/jobs", {{"kind", "fluid-simulate"},
                                        {"width", 48},
                                        {"height", 48},
                                        {"last", 3},
                                        {"alpha", "sim/alpha/%04d.png"},
                                        {"motion", "sim/motion/%04d.flo"}});
    ASSERT_EQ(simulated->status, 202) << simulated->body;
    const json sim_end = follow(server_->port(), body_of(simulated)["id"]);
    ASSERT_EQ(sim_end["state"], "done") << sim_end.dump();
    EXPECT_EQ(sim_end["frames"].size(), 4u);
    ASSERT_TRUE(fluid::simulate(
                    fluid::plume_scene(48, 48), 4,
                    [&](int frame, const Image& alpha, const Image& motion) -> Status {
                        const fs::path mine = dir_ / *video::format_frame_path("a%d.png", frame);
                        EXEMPLAR_RETURN_IF_ERROR(save_image(alpha, mine.string()));
                        EXPECT_EQ(file_bytes(dir_ / "ws" / "sim" / "alpha" /
                                             *video::format_frame_path("%04d.png", frame)),
                                  file_bytes(mine));
                        EXPECT_EQ(file_bytes(dir_ / "ws" / "sim" / "motion" /
                                             *video::format_frame_path("%04d.flo", frame))
                                      .size(),
                                  std::size_t{48} * 48 * 8 + 12);
                        (void)motion;
                        return Status::ok();
                    },
                    RunContext(1))
                    .is_ok());

    // Transfer frames 1..3; frame 1 continues from nothing (no output 0 yet).
    const json good = {{"kind", "fluid"},
                       {"exemplar", "ink.png"},
                       {"alpha", "sim/alpha/%04d.png"},
                       {"motion", "sim/motion/%04d.flo"},
                       {"first", 1},
                       {"last", 3},
                       {"output", "outputs/fluid/%04d.png"},
                       {"seed", 5},
                       {"patch-size", 3}};
    auto job = post("/api/jobs", good);
    ASSERT_EQ(job->status, 202) << job->body;
    const json end = follow(server_->port(), body_of(job)["id"]);
    ASSERT_EQ(end["state"], "done") << end.dump();
    ASSERT_EQ(end["frames"].size(), 3u);
    EXPECT_EQ(end["frames"][0]["path"], "outputs/fluid/0001.png");
    // The library's frames, each continuing from the previous one read back from its file.
    const Image stored_exemplar = *load_image((dir_ / "ws" / "ink.png").string());
    fluid::FluidOptions options;
    options.synthesis.seed = 5;
    options.patch_size = 3;
    std::optional<Image> previous, previous_motion;
    for (int n = 1; n <= 3; ++n) {
        const auto sim = [&](const char* pattern) {
            return (dir_ / "ws" / "sim" / *video::format_frame_path(pattern, n)).string();
        };
        auto alpha = load_image(sim("alpha/%04d.png"));
        ASSERT_TRUE(alpha.ok());
        fluid::FluidFrameInput input;
        input.exemplar = &stored_exemplar;
        input.target_alpha = &*alpha;
        input.previous_output = previous ? &*previous : nullptr;
        input.previous_motion = previous_motion ? &*previous_motion : nullptr;
        auto frame = fluid::synthesize_fluid_frame(input, options, RunContext(1));
        ASSERT_TRUE(frame.ok()) << frame.status().message();
        const fs::path mine = dir_ / *video::format_frame_path("fluid%d.png", n);
        ASSERT_TRUE(save_image(frame->rgba, mine.string()).is_ok());
        EXPECT_TRUE(file_bytes(dir_ / "ws" / "outputs" / "fluid" /
                               *video::format_frame_path("%04d.png", n)) == file_bytes(mine))
            << "frame " << n;
        previous = *load_image(mine.string());
        previous_motion = *load_flow(sim("motion/%04d.flo"));
    }
    // Bad parameters: one line naming the parameter (400); outside the workspace: 403.
    expect_refused("/api/jobs", good,
                   {{"last", 9, "alpha: sim/alpha/0004.png"},
                    {"patch-size", 4, "patch-size: "},
                    {"usage", "sometimes", "usage: "},
                    {"rotations", 1, "rotations: "},
                    {"wobble", 1, "wobble: "},
                    {"exemplar", "tex.png", "exemplar: "},
                    {"output", "outputs/%d.txt", "output: "}});
    json outside = good;
    outside["motion"] = "../outside/%04d.flo";
    EXPECT_EQ(post("/api/jobs", outside)->status, 403);
    EXPECT_EQ(post("/api/jobs", {{"kind", "fluid-simulate"},
                                 {"scene", "volcano"},
                                 {"last", 1},
                                 {"alpha", "a%d.png"},
                                 {"motion", "m%d.flo"}})
                  ->status,
              400);
}

TEST_F(StudioTest, FluidJobsTakeExemplarSequencesAndAlphaAsExemplarFluidDoes) {
    // Targets: the plume, 48 x 48, frames 0..3, written here.
    fs::create_directories(dir_ / "ws" / "sim");
    ASSERT_TRUE(fluid::simulate(
                    fluid::plume_scene(48, 48), 4,
                    [&](int frame, const Image& alpha, const Image& motion) -> Status {
                        const auto name = [&](const char* pattern) {
                            return (dir_ / "ws" / "sim" / *video::format_frame_path(pattern, frame))
                                .string();
                        };
                        EXEMPLAR_RETURN_IF_ERROR(save_image(alpha, name("a%04d.png")));
                        return save_flow(motion, name("m%04d.flo"));
                    },
                    RunContext(1))
                    .is_ok());
    // An exemplar sequence of two RGB frames with its alpha in a folder beside it.
    fs::create_directories(dir_ / "ws" / "ink" / "rgb");
    fs::create_directories(dir_ / "ws" / "ink" / "alpha");
    for (int k = 0; k < 2; ++k) {
        Image rgba = ink_exemplar(40);
        for (int y = 0; y < 40 && k == 1; ++y) {
            for (int x = 0; x < 40; ++x) rgba.at(x, y, 1) *= 0.6f;  // frame 1: another colour
        }
        const std::string name = *video::format_frame_path("f%d.png", k);
        ASSERT_TRUE(
            save_image(extract_channels(rgba, 0, 3), (dir_ / "ws" / "ink" / "rgb" / name).string())
                .is_ok());
        ASSERT_TRUE(save_image(extract_channels(rgba, 3, 1),
                               (dir_ / "ws" / "ink" / "alpha" / name).string())
                        .is_ok());
    }
    start();
    const json good = {{"kind", "fluid"},
                       {"exemplar", "ink/rgb"},
                       {"exemplar-alpha", "ink/alpha"},
                       {"alpha", "sim/a%04d.png"},
                       {"motion", "sim/m%04d.flo"},
                       {"motion-layer", ""},
                       {"first", 1},
                       {"last", 3},
                       {"output", "outputs/%04d.png"},
                       {"seed", 4},
                       {"patch-size", 3},
                       {"resume", false}};
    auto job = post("/api/jobs", good);
    ASSERT_EQ(job->status, 202) << job->body;
    const json end = follow(server_->port(), body_of(job)["id"]);
    ASSERT_EQ(end["state"], "done") << end.dump();
    ASSERT_EQ(end["frames"].size(), 3u);

    // The library's range driver on the same files, as exemplar fluid calls it: the same bytes.
    auto exemplar = fluid::FluidExemplar::open((dir_ / "ws" / "ink" / "rgb").string(),
                                               (dir_ / "ws" / "ink" / "alpha").string());
    ASSERT_TRUE(exemplar.ok()) << exemplar.status().message();
    EXPECT_EQ(exemplar->size(), 2);
    fluid::FluidRange range;
    range.first = 1;
    range.last = 3;
    const auto in = [&](const fs::path& folder, const char* pattern) {
        return [folder, pattern](int n) -> Result<std::string> {
            auto name = video::format_frame_path(pattern, n);
            if (!name.ok()) return name.status();
            return (folder / *name).string();
        };
    };
    range.alpha_file = in(dir_ / "ws" / "sim", "a%04d.png");
    range.motion_file = in(dir_ / "ws" / "sim", "m%04d.flo");
    range.output_file = in(dir_ / "mine", "%04d.png");
    range.resume = false;
    exemplar->use_in(range);
    EXPECT_TRUE(range.exemplar_sequence);
    fs::create_directories(dir_ / "mine");
    fluid::FluidOptions options;
    options.synthesis.seed = 4;
    options.patch_size = 3;
    ASSERT_TRUE(fluid::synthesize_fluid_range(range, options, RunContext(1)).is_ok());
    for (int n = 1; n <= 3; ++n) {
        const std::string name = *video::format_frame_path("%04d.png", n);
        EXPECT_TRUE(file_bytes(dir_ / "ws" / "outputs" / name) == file_bytes(dir_ / "mine" / name))
            << name;
    }
    // Refusals: one line naming the key (400); an alpha outside the workspace (403).
    expect_refused("/api/jobs", good,
                   {{"resume", 1, "resume: "},
                    {"motion-layer", 3, "motion-layer: "},
                    {"exemplar-alpha", "tex.png", "exemplar: "}});
    json outside = good;
    outside["exemplar-alpha"] = "../outside/alpha";
    EXPECT_EQ(post("/api/jobs", outside)->status, 403);
}

TEST_F(StudioTest, NprJobsStyleFrameFoldersAsTheLibraryDoes) {
    // Three render frame folders of 64 x 48: a tone ramp moving right, no lines, the motion.
    write_render_frames(dir_ / "ws" / "render", 3, 64, 48);
    write_dots(dir_ / "ws" / "dots.png");
    start();
    const json good = {{"kind", "npr"},
                       {"pattern", "dots.png"},
                       {"frames", "render/f%d"},
                       {"last", 2},
                       {"output", "outputs/npr/%d.png"},
                       {"levels", 2},
                       {"patch-size", 8},
                       {"seed", 3}};
    auto job = post("/api/jobs", good);
    ASSERT_EQ(job->status, 202) << job->body;
    const json end = follow(server_->port(), body_of(job)["id"]);
    ASSERT_EQ(end["state"], "done") << end.dump();
    ASSERT_EQ(end["frames"].size(), 3u);
    EXPECT_TRUE(fs::exists(dir_ / "ws" / "outputs" / "npr" / "2.png.state.exr"));
    // The library's frames, each continuing from the one before.
    npr::NprOptions options;
    options.levels = 2;
    options.patch_size = 8;
    options.seed = 3;
    auto pattern = npr::prepare_pattern(*load_image((dir_ / "ws" / "dots.png").string()), options,
                                        RunContext(1));
    ASSERT_TRUE(pattern.ok()) << pattern.status().message();
    std::optional<npr::FrameState> previous;
    for (int n = 0; n < 3; ++n) {
        const fs::path folder = dir_ / "ws" / "render" / *video::format_frame_path("f%d", n);
        npr::NprFrame frame;
        for (const npr::BufferNeed& need : npr::needed_buffers(options, previous.has_value())) {
            const bool exr = need.name == "backward_flow";
            auto buffer = load_image((folder / (need.name + (exr ? ".exr" : ".png"))).string());
            ASSERT_TRUE(buffer.ok()) << need.name;
            frame[need.role] = *buffer;
        }
        auto styled = npr::stylize_frame(*pattern, frame, previous ? &*previous : nullptr, n,
                                         options, RunContext(1));
        ASSERT_TRUE(styled.ok()) << styled.status().message();
        const fs::path mine = dir_ / *video::format_frame_path("npr%d.png", n);
        ASSERT_TRUE(save_image(styled->image, mine.string()).is_ok());
        EXPECT_TRUE(file_bytes(dir_ / "ws" / "outputs" / "npr" /
                               *video::format_frame_path("%d.png", n)) == file_bytes(mine))
            << "frame " << n;
        previous = styled->state;
    }
    // Bad parameters: one line naming the parameter (400).
    expect_refused("/api/jobs", good,
                   {{"last", 3, "frames: render/f3"},
                    {"levels", 9, "levels: "},
                    {"style", "crosshatch", "crosshatch"},
                    {"lines", "yes", "lines: "},
                    {"paper-grain", 0.2, "paper-grain: "},
                    {"wobble", 1, "wobble: "},
                    {"tone", "sunlight", "sunlight"},
                    {"pattern", "nope.png", "pattern: "}});
}

// The paper layer and the bidirectional loop: the frames and states are those of the library's
// range driver (the one exemplar npr calls) on the same files.
TEST_F(StudioTest, NprJobsWithPaperAndBidirectionalLoopGiveTheLibrarysBytes) {
    write_render_frames(dir_ / "ws" / "render", 5, 64, 48);
    write_loop_buffers(dir_ / "ws" / "render", 5, 64, 48);
    write_dots(dir_ / "ws" / "dots.png");
    fs::copy_file(std::string(EXEMPLAR_TEST_DATA_DIR) + "/paper/struc.pgm",
                  dir_ / "ws" / "paper.pgm");
    start();
    const json good = {{"kind", "npr"},
                       {"pattern", "dots.png"},
                       {"paper", "paper.pgm"},
                       {"frames", "render/f%d"},
                       {"last", 4},
                       {"output", "outputs/npr/%d.png"},
                       {"bidirectional", 2},
                       {"erosion", 1.5},
                       {"levels", 2},
                       {"patch-size", 8},
                       {"seed", 3}};
    // The library's range on the same files, written outside the workspace.
    npr::NprOptions options;
    options.levels = 2;
    options.patch_size = 8;
    options.seed = 3;
    options.paper = true;
    options.erosion_px = 1.5f;
    const RunContext context(1);
    auto pattern =
        npr::prepare_pattern(*load_image((dir_ / "ws" / "dots.png").string()), options, context);
    auto paper =
        npr::prepare_pattern(*load_image((dir_ / "ws" / "paper.pgm").string()), options, context);
    ASSERT_TRUE(pattern.ok() && paper.ok());
    const auto named = [](const fs::path& files) {
        return [files](int n) -> Result<std::string> {
            return video::format_frame_path(files.string(), n);
        };
    };
    npr::NprRange range;
    range.last = 4;
    range.frame_folder = named(dir_ / "ws" / "render" / "f%d");
    range.output_file = named(dir_ / "lib" / "%d.png");
    range.bidirectional = 2;
    for (const bool with_paper : {true, false}) {
        json job_body = good;
        if (!with_paper) {
            job_body.erase("paper");
            job_body.erase("erosion");
            job_body["output"] = "outputs/plain/%d.png";
            options.paper = false;
            range.output_file = named(dir_ / "plain" / "%d.png");
        }
        ASSERT_TRUE(
            npr::stylize_range(*pattern, with_paper ? &*paper : nullptr, range, options, context)
                .is_ok());
        auto job = post("/api/jobs", job_body);
        ASSERT_EQ(job->status, 202) << job->body;
        const json end = follow(server_->port(), body_of(job)["id"]);
        ASSERT_EQ(end["state"], "done") << end.dump();
        ASSERT_EQ(end["frames"].size(), 5u);
        const std::string folder = with_paper ? "npr" : "plain";
        for (int n = 0; n <= 4; ++n) {
            const std::string name = *video::format_frame_path("%d.png", n);
            const fs::path mine = dir_ / (with_paper ? "lib" : "plain") / name;
            const fs::path theirs = dir_ / "ws" / "outputs" / folder / name;
            for (const char* suffix : {"", ".state.exr", ".paper.state.exr"}) {
                if (!with_paper && std::string(suffix) == ".paper.state.exr") continue;
                EXPECT_TRUE(fs::exists(theirs.string() + suffix)) << name << suffix;
                EXPECT_TRUE(file_bytes(theirs.string() + suffix) ==
                            file_bytes(mine.string() + suffix))
                    << name << suffix;
            }
        }
    }
    // Bad parameters: one line naming the parameter (400), the paper outside the workspace 403.
    expect_refused("/api/jobs", good,
                   {{"bidirectional", 1, "bidirectional: 1 is invalid (must be 0 or 2..1000)"},
                    {"bidirectional", 2.5, "bidirectional: "},
                    {"paper", "nope.png", "paper: "},
                    {"paper", 3, "paper: "},
                    {"paper-grain", 2, "paper-grain: "}});
    json no_paper = good;
    no_paper.erase("paper");
    expect_refused("/api/jobs", no_paper, {{"erosion", 1.5, "erosion: needs paper"}});
    json outside = good;
    outside["paper"] = "../outside/secret.txt";
    EXPECT_EQ(post("/api/jobs", outside)->status, 403);
    // The backward passes read the forward flow, checked when the job is posted.
    fs::remove(dir_ / "ws" / "render" / "f3" / "forward_flow.exr");
    expect_refused("/api/jobs", good,
                   {{"last", 4, "frames: render/f3: missing buffer 'forward_flow'"}});
}

TEST_F(StudioTest, FinishedJobsAndIdleClientsBeyondTheBoundsAreForgotten) {
    StudioOptions options;
    options.max_finished_jobs = 2;
    options.max_clients = 2;
    start(options);
    const json noisy = {{"kind", "noisy"},
                        {"exemplar", "tex.png"},
                        {"reference", "tex.png"},
                        {"output", "o.png"},
                        {"noise", 4}};
    std::vector<std::string> ids;
    for (int k = 0; k < 4; ++k) {
        auto job = post("/api/jobs", noisy);
        ASSERT_EQ(job->status, 202) << job->body;
        ids.push_back(body_of(job)["id"]);
        EXPECT_EQ(follow(server_->port(), ids.back())["state"], "done");
    }
    // Starting the fourth forgot the first: two finished ones are kept besides it.
    const json list = body_of(client_->Get("/api/jobs"));
    ASSERT_EQ(list["jobs"].size(), 3u) << list.dump();
    for (const json& job : list["jobs"]) EXPECT_NE(job["id"], ids[0]);
    EXPECT_EQ(client_->Get(("/api/jobs/" + ids[0] + "/events").c_str())->status, 404);
    EXPECT_EQ(client_->Get(("/api/jobs/" + ids[1] + "/events").c_str())->status, 200);

    // tab1 paints; tab2 and tab3 come after it: tab1's painting is forgotten, tab3's sketch kept.
    ASSERT_EQ(
        post("/api/paint/start", {{"exemplar", "tex.png"}, {"width", 32}, {"height", 32}})->status,
        200);
    for (const char* tab : {"tab2", "tab3"}) {
        httplib::Client other("127.0.0.1", server_->port());
        other.set_default_headers({{"X-Studio-Client", tab}});
        EXPECT_EQ(other.Get("/api/sketch")->status, 200);
    }
    EXPECT_EQ(post("/api/paint/stroke", {{"points", {{4, 4}, {20, 20}}}})->status, 409);
}

TEST_F(StudioTest, JobsAreListedInTheOrderTheyWereStarted) {
    start();
    // Eleven small jobs: ids 1..11, so "10" and "11" sort before "2" as strings.
    for (int k = 1; k <= 11; ++k) {
        auto job = post("/api/jobs", {{"kind", "fluid-simulate"},
                                      {"width", 8},
                                      {"height", 8},
                                      {"last", 0},
                                      {"alpha", "sim/a%d.png"},
                                      {"motion", "sim/m%d.flo"}});
        ASSERT_EQ(job->status, 202) << job->body;
        const std::string id = body_of(job)["id"];
        EXPECT_EQ(id, std::to_string(k));
        EXPECT_EQ(follow(server_->port(), id)["state"], "done");
    }
    const json list = body_of(client_->Get("/api/jobs"));
    ASSERT_EQ(list["jobs"].size(), 11u) << list.dump();
    for (int k = 1; k <= 11; ++k) EXPECT_EQ(list["jobs"][k - 1]["id"], std::to_string(k));
    // Ids are numbers: other spellings of one are no job.
    EXPECT_EQ(client_->Get("/api/jobs/011/events")->status, 404);
    EXPECT_EQ(client_->Get("/api/jobs/11/events")->status, 200);
}

// A job long enough to cancel: the bundled texture-by-numbers example at the best quality.
json long_job(const std::string& output) {
    return {{"kind", "stylize"},
            {"style", "texbynum/source_photo.png"},
            {"source", "texbynum/source_segment.png"},
            {"target", "texbynum/target_segment.png"},
            {"output", output},
            {"quality", "best"}};
}

class StudioJobTest : public StudioTest {
protected:
    void SetUp() override {
        StudioTest::SetUp();
        fs::create_directories(dir_ / "ws" / "texbynum");
        for (const char* name : {"source_photo.png", "source_segment.png", "target_segment.png"}) {
            fs::copy_file(fs::path(EXEMPLAR_TEST_DATA_DIR) / "ebsynth" / "texbynum" / name,
                          dir_ / "ws" / "texbynum" / name);
        }
    }

    // Posts `job`, cancels it at its second progress event (the engine's first) and checks
    // that it ends cancelled with nothing written to `output`.
    void cancel_after_first_progress(const json& job, const std::string& output) {
        auto posted = post("/api/jobs", job);
        ASSERT_EQ(posted->status, 202) << posted->body;
        const std::string id = body_of(posted)["id"];
        httplib::Client canceller("127.0.0.1", server_->port());
        const json end = follow(server_->port(), id, [&](int progress) {
            if (progress == 2) {
                auto c = canceller.Post(("/api/jobs/" + id + "/cancel").c_str(), "{}",
                                        "application/json");
                EXPECT_EQ(c->status, 200);
            }
        });
        EXPECT_EQ(end["state"], "cancelled") << end.dump();
        EXPECT_FALSE(fs::exists(dir_ / "ws" / output));
        EXPECT_EQ(hidden_files(dir_ / "ws"), 0);
    }

    // Posts the range job `job` (outputs in outputs/, frames 0..3) and cancels it when its first
    // frame is written: it ends cancelled, the images in outputs/ are exactly the frames it
    // reported (fewer than four), each whole (`size`), and no temporary file is left. Returns
    // the reported frames' paths.
    std::vector<std::string> cancel_after_first_frame(const json& job, const std::string& size) {
        auto posted = post("/api/jobs", job);
        EXPECT_EQ(posted->status, 202) << posted->body;
        const std::string id = body_of(posted)["id"];
        httplib::Client canceller("127.0.0.1", server_->port());
        const json end = follow(server_->port(), id, {}, [&](const json& frame) {
            if (frame["frame"] != 0) return;
            auto c =
                canceller.Post(("/api/jobs/" + id + "/cancel").c_str(), "{}", "application/json");
            EXPECT_EQ(c->status, 200);
        });
        EXPECT_EQ(end["state"], "cancelled") << end.dump();
        std::vector<std::string> reported, written;
        for (const json& frame : end["frames"]) reported.push_back(frame["path"]);
        for (const auto& entry : fs::directory_iterator(dir_ / "ws" / "outputs")) {
            const std::string name = entry.path().filename().string();
            if (name.ends_with(".png")) written.push_back("outputs/" + name);
        }
        std::sort(written.begin(), written.end());
        EXPECT_EQ(written, reported);
        EXPECT_GE(reported.size(), 1u);
        EXPECT_LT(reported.size(), 4u);
        for (const std::string& file : written) {
            auto image = load_image((dir_ / "ws" / file).string());
            EXPECT_TRUE(image.ok()) << file;
            if (image.ok()) {
                EXPECT_EQ(size_str(*image), size) << file;
            }
        }
        EXPECT_EQ(hidden_files(dir_ / "ws"), 0);
        return reported;
    }
};

TEST_F(StudioJobTest, CancelStopsARunningJobAndWritesNothing) {
    start();
    cancel_after_first_progress(long_job("outputs/cancelled.png"), "outputs/cancelled.png");
    EXPECT_EQ(client_->Post("/api/jobs/999/cancel")->status, 404);
}

TEST_F(StudioJobTest, CancelStopsANoisyJobAndWritesNothing) {
    start();
    // The chapter's schedule (no warm levels) from f = 16: about twenty levels, long enough.
    cancel_after_first_progress({{"kind", "noisy"},
                                 {"exemplar", "texbynum/source_photo.png"},
                                 {"reference", "texbynum/source_photo.png"},
                                 {"output", "outputs/noisy.png"},
                                 {"noise", 16},
                                 {"warm-search-iterations", 0}},
                                "outputs/noisy.png");
}

TEST_F(StudioJobTest, CancelStopsANoisyRangeAndKeepsTheFinishedFramesWhole) {
    // Four 320 x 462 frames, two at a time (the server's two threads, one each).
    for (int n = 0; n < 4; ++n) {
        fs::copy_file(dir_ / "ws" / "texbynum" / "source_photo.png",
                      dir_ / "ws" / "texbynum" / *video::format_frame_path("f%d.png", n));
    }
    start();
    cancel_after_first_frame({{"kind", "noisy"},
                              {"exemplar", "texbynum/source_photo.png"},
                              {"frames", "texbynum/f%d.png"},
                              {"last", 3},
                              {"output", "outputs/%d.png"},
                              {"noise", 8}},
                             "320x462");
}

TEST_F(StudioJobTest, CancelStopsAnAnimateJobAndLeavesNoHalfWrittenFrame) {
    // The texture-by-numbers target as a still animation of four frames, at the best quality.
    for (int n = 0; n < 4; ++n) {
        fs::copy_file(dir_ / "ws" / "texbynum" / "target_segment.png",
                      dir_ / "ws" / "texbynum" / *video::format_frame_path("frame%d.png", n));
    }
    start();
    cancel_after_first_progress({{"kind", "animate"},
                                 {"frames", "texbynum/frame%d.png"},
                                 {"last", 3},
                                 {"style-input", "texbynum/source_segment.png"},
                                 {"style-output", "texbynum/source_photo.png"},
                                 {"output", "outputs/%d.png"},
                                 {"quality", "best"}},
                                "outputs/0.png");
}

TEST_F(StudioJobTest, CancelStopsAFluidJobAndKeepsTheFinishedFramesWhole) {
    // Four 384 x 384 frames of a still disc (no motion): each takes a while.
    ASSERT_TRUE(save_image(ink_exemplar(48), (dir_ / "ws" / "ink.png").string()).is_ok());
    fs::create_directories(dir_ / "ws" / "target");
    Image disc(384, 384, 1), still(384, 384, 2);
    for (int y = 0; y < 384; ++y) {
        for (int x = 0; x < 384; ++x) {
            const float r =
                std::hypot(static_cast<float>(x) - 191.5f, static_cast<float>(y) - 191.5f);
            disc.at(x, y, 0) = std::clamp((170.0f - r) / 4.0f, 0.0f, 1.0f);
        }
    }
    for (int n = 0; n < 4; ++n) {
        const fs::path target = dir_ / "ws" / "target";
        ASSERT_TRUE(
            save_image(disc, (target / *video::format_frame_path("a%d.png", n)).string()).is_ok());
        ASSERT_TRUE(
            save_flow(still, (target / *video::format_frame_path("m%d.flo", n)).string()).is_ok());
    }
    start();
    cancel_after_first_frame({{"kind", "fluid"},
                              {"exemplar", "ink.png"},
                              {"alpha", "target/a%d.png"},
                              {"motion", "target/m%d.flo"},
                              {"last", 3},
                              {"output", "outputs/%d.png"}},
                             "384x384");
}

TEST_F(StudioJobTest, CancelStopsAnNprJobAndKeepsTheFinishedFramesWhole) {
    // Four 768 x 576 render frames at the default three levels: each takes a while.
    write_render_frames(dir_ / "ws" / "render", 4, 768, 576);
    write_dots(dir_ / "ws" / "dots.png");
    start();
    const std::vector<std::string> finished =
        cancel_after_first_frame({{"kind", "npr"},
                                  {"pattern", "dots.png"},
                                  {"frames", "render/f%d"},
                                  {"last", 3},
                                  {"output", "outputs/%d.png"}},
                                 "768x576");
    // Each finished frame has its state beside it, the others neither.
    for (int n = 0; n <= 3; ++n) {
        const std::string file = "outputs/" + std::to_string(n) + ".png";
        const bool done = std::find(finished.begin(), finished.end(), file) != finished.end();
        EXPECT_EQ(fs::exists(dir_ / "ws" / (file + ".state.exr")), done) << file;
    }
}

TEST_F(StudioJobTest, StylitRunsPostedAtOnceLeaveOneRunning) {
    // One job per client at most: two runs started side by side would be refused (429).
    StudioOptions options;
    options.max_jobs_per_client = 1;
    start(options);
    constexpr int kPosts = 4;
    std::vector<std::thread> posters;
    std::vector<int> statuses(kPosts, 0);
    std::vector<std::string> ids(kPosts);
    for (int k = 0; k < kPosts; ++k) {
        posters.emplace_back([&, k] {
            httplib::Client tab("127.0.0.1", server_->port());
            tab.set_default_headers({{"X-Studio-Client", "tab1"}});
            tab.set_read_timeout(120, 0);
            const json run = {{"kind", "stylit"},
                              {"exemplar", "texbynum/source_photo.png"},
                              {"source", "texbynum/source_segment.png"},
                              {"target", "texbynum/target_segment.png"},
                              {"output", "outputs/run" + std::to_string(k) + ".png"},
                              {"quality", "best"}};
            auto posted = tab.Post("/api/jobs", run.dump(), "application/json");
            if (!posted) return;
            statuses[static_cast<std::size_t>(k)] = posted->status;
            if (posted->status == 202)
                ids[static_cast<std::size_t>(k)] = json::parse(posted->body)["id"];
        });
    }
    for (std::thread& poster : posters) poster.join();
    for (int k = 0; k < kPosts; ++k) ASSERT_EQ(statuses[static_cast<std::size_t>(k)], 202) << k;
    // Each post cancelled the runs before it and waited for them: one is left running.
    int running = 0;
    for (const json& job : body_of(client_->Get("/api/jobs"))["jobs"])
        running += job["state"] == "running" ? 1 : 0;
    EXPECT_LE(running, 1);
    // The last one started runs to the end; the others were cancelled.
    std::sort(ids.begin(), ids.end(), [](const std::string& a, const std::string& b) {
        return std::stoi(a) < std::stoi(b);
    });
    for (int k = 0; k < kPosts; ++k) {
        const json end = follow(server_->port(), ids[static_cast<std::size_t>(k)]);
        EXPECT_EQ(end["state"], k + 1 < kPosts ? "cancelled" : "done") << end.dump();
    }
    EXPECT_EQ(hidden_files(dir_ / "ws"), 0);
}

TEST(JobManagerTest, OneClientsReplaceWaitDoesNotHoldUpAnothers) {
    JobManager jobs(1, 1);
    // Client a's run ends only when the test lets it (it notices no cancel before).
    std::mutex gate_mutex;
    std::condition_variable gate_changed;
    bool open = false;
    const JobWork slow = [&](const RunContext&, const OutputSink&) -> Status {
        std::unique_lock lock(gate_mutex);
        gate_changed.wait(lock, [&] { return open; });
        return Status::ok();
    };
    const JobWork quick = [](const RunContext&, const OutputSink&) { return Status::ok(); };
    auto first = jobs.replace("a", "stylit", "a1.png", slow);
    ASSERT_TRUE(first.ok());
    // A second run of a: it cancels the first and waits for it, holding a's replace lock.
    std::thread waiting([&] { EXPECT_TRUE(jobs.replace("a", "stylit", "a2.png", quick).ok()); });
    while (!(*first)->cancel.cancelled()) std::this_thread::yield();
    // Meanwhile client b replaces its own run at once, without waiting for a's.
    auto other = std::async(std::launch::async,
                            [&] { return jobs.replace("b", "stylit", "b1.png", quick); });
    const bool returned = other.wait_for(std::chrono::seconds(60)) == std::future_status::ready;
    EXPECT_TRUE(returned) << "b's replace waited for a's cancelled run";
    {
        std::lock_guard lock(gate_mutex);
        open = true;
    }
    gate_changed.notify_all();
    waiting.join();
    EXPECT_TRUE(other.get().ok());
}

TEST_F(StudioJobTest, AStylitRunReplacesTheClientsRunningOne) {
    // The texture-by-numbers images as a one-buffer render pair, at the best quality: long enough
    // to be running when the next run arrives.
    start();
    const json first = {{"kind", "stylit"},
                        {"exemplar", "texbynum/source_photo.png"},
                        {"source", "texbynum/source_segment.png"},
                        {"target", "texbynum/target_segment.png"},
                        {"output", "outputs/first.png"},
                        {"quality", "best"}};
    json second = first;
    second["output"] = "outputs/second.png";
    second["quality"] = "fast";
    auto posted = post("/api/jobs", first);
    ASSERT_EQ(posted->status, 202) << posted->body;
    httplib::Client other_request("127.0.0.1", server_->port());
    other_request.set_default_headers({{"X-Studio-Client", "tab1"}});
    std::string second_id;
    const json end = follow(server_->port(), body_of(posted)["id"], [&](int progress) {
        if (progress != 2) return;
        auto replaced = other_request.Post("/api/jobs", second.dump(), "application/json");
        ASSERT_EQ(replaced->status, 202) << replaced->body;
        second_id = body_of(replaced)["id"];
    });
    EXPECT_EQ(end["state"], "cancelled") << end.dump();
    ASSERT_FALSE(second_id.empty());
    EXPECT_EQ(follow(server_->port(), second_id)["state"], "done");
    EXPECT_FALSE(fs::exists(dir_ / "ws" / "outputs" / "first.png"));
    EXPECT_TRUE(fs::exists(dir_ / "ws" / "outputs" / "second.png"));
}

TEST_F(StudioJobTest, JobsPerClientAreBoundedAndShutdownCancelsThem) {
    StudioOptions options;
    options.max_jobs_per_client = 1;
    start(options);
    auto first = post("/api/jobs", long_job("outputs/a.png"));
    ASSERT_EQ(first->status, 202) << first->body;
    auto second = post("/api/jobs", long_job("outputs/b.png"));
    EXPECT_EQ(second->status, 429);
    EXPECT_NE(body_of(second)["error"].get<std::string>().find("too many jobs"), std::string::npos);
    httplib::Client other("127.0.0.1", server_->port());
    other.set_default_headers({{"X-Studio-Client", "tab2"}});
    auto third = other.Post("/api/jobs", long_job("outputs/c.png").dump(), "application/json");
    EXPECT_EQ(third->status, 202) << third->body;
    // Shutdown cancels both, waits for them, and nothing is left half-written.
    stop();
    EXPECT_FALSE(fs::exists(dir_ / "ws" / "outputs" / "a.png"));
    EXPECT_FALSE(fs::exists(dir_ / "ws" / "outputs" / "c.png"));
    EXPECT_EQ(hidden_files(dir_ / "ws"), 0);
}

}  // namespace
}  // namespace exemplar::studio
