// The studio's routes (docs/studio.md, "API"). Handlers parse JSON, resolve every path through
// the workspace, call the library and answer; the per-client tool state lives in sessions.hpp,
// the jobs in jobs.hpp.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>

#include "assets.hpp"
#include "exemplar/animate/animate.hpp"
#include "exemplar/fluid/fluid_range.hpp"
#include "exemplar/fluid/lazy_fluids.hpp"
#include "exemplar/fluid/simulate.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/noisy/noisy.hpp"
#include "exemplar/noisy/noisy_range.hpp"
#include "exemplar/npr/npr.hpp"
#include "exemplar/npr/npr_range.hpp"
#include "exemplar/paint/vectorize_style.hpp"
#include "exemplar/sketch/svg.hpp"
#include "exemplar/stylit/stylit.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "exemplar/version.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "http_server.hpp"
#include "jobs.hpp"
#include "sessions.hpp"
#include "studio.hpp"
#include "workspace.hpp"

namespace exemplar::studio {

namespace {

using nlohmann::json;
using plugin::http::Request;
using plugin::http::Response;

constexpr std::size_t kMaxJsonBytes = std::size_t{4} << 20;
constexpr std::size_t kMaxPoints = 10000;
constexpr int kMaxCanvas = 2048;
constexpr std::size_t kMaxDownloadBytes = std::size_t{1} << 30;

void answer(Response& res, int http_status, const json& body) {
    res.status = http_status;
    res.set_content(body.dump(), "application/json");
}

void fail(Response& res, int http_status, const std::string& message) {
    answer(res, http_status, {{"error", message}});
}

// A library Status as an HTTP answer: bad input 400, missing or unreadable file 404, cancelled
// (undone, superseded) 409, refused (too many jobs, shutting down) 429, anything else 500.
void fail(Response& res, const Status& status) {
    switch (status.code()) {
        case ErrorCode::InvalidArgument: return fail(res, 400, status.message());
        case ErrorCode::IoError: return fail(res, 404, status.message());
        case ErrorCode::Unsupported: return fail(res, 429, status.message());
        case ErrorCode::Cancelled: return fail(res, 409, status.message());
        default: return fail(res, 500, status.message());
    }
}

// A request's JSON body (an object), or nullopt after answering 400/413.
std::optional<json> json_body(const Request& req, Response& res) {
    if (req.body.size() > kMaxJsonBytes) {
        fail(res, 413, "request body over 4 MiB");
        return std::nullopt;
    }
    json body = json::parse(req.body, nullptr, false);
    if (body.is_discarded() || !body.is_object()) {
        fail(res, 400, "the body is not a JSON object");
        return std::nullopt;
    }
    return body;
}

// Field readers: the value, or an InvalidArgument naming the field.
Result<std::string> text_field(const json& body, const char* name) {
    const auto it = body.find(name);
    if (it == body.end() || !it->is_string())
        return invalid_argument(std::string(name) + ": missing (a string)");
    return it->get<std::string>();
}

Result<double> number_field(const json& body, const char* name, std::optional<double> fallback,
                            double lo, double hi) {
    const auto it = body.find(name);
    if (it == body.end()) {
        if (fallback) return *fallback;
        return invalid_argument(std::string(name) + ": missing (a number)");
    }
    if (!it->is_number() || !std::isfinite(it->get<double>()) || it->get<double>() < lo ||
        it->get<double>() > hi) {
        return invalid_argument(std::string(name) + ": " + it->dump() + " is invalid (must be " +
                                json(lo).dump() + ".." + json(hi).dump() + ")");
    }
    return it->get<double>();
}

// An array of `min_points`..10000 [x, y] pairs under `name`.
Result<std::vector<sketch::Vec2>> points_field(const json& body, const char* name = "points",
                                               std::size_t min_points = 1) {
    const auto it = body.find(name);
    if (it == body.end() || !it->is_array() || it->size() < min_points || it->size() > kMaxPoints) {
        return invalid_argument(std::string(name) + ": must be an array of " +
                                std::to_string(min_points) + "..10000 [x, y] pairs");
    }
    std::vector<sketch::Vec2> points;
    for (const json& p : *it) {
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number() ||
            !std::isfinite(p[0].get<double>()) || !std::isfinite(p[1].get<double>())) {
            return invalid_argument(std::string(name) +
                                    ": every point must be [x, y] with finite numbers");
        }
        points.push_back({p[0].get<double>(), p[1].get<double>()});
    }
    return points;
}

// "quality" (fast, default, best), or nullopt when absent: the caller's own defaults.
Result<std::optional<Quality>> quality_field(const json& body) {
    if (!body.contains("quality")) return std::optional<Quality>();
    auto name = text_field(body, "quality");
    if (!name.ok()) return name.status();
    auto quality = parse_quality(*name);
    if (!quality.ok()) return quality.status();
    return std::optional<Quality>(*quality);
}

// "seed" (default 1) into `seed`.
Status read_seed(const json& body, std::uint64_t& seed) {
    auto value = number_field(body, "seed", 1.0, 0.0, 1e15);
    if (!value.ok()) return value.status();
    seed = static_cast<std::uint64_t>(*value);
    return Status::ok();
}

// A list of workspace paths: one string or an array of 1..64 strings.
Result<std::vector<std::string>> path_list_field(const json& body, const char* name) {
    const auto it = body.find(name);
    if (it != body.end() && it->is_string())
        return std::vector<std::string>{it->get<std::string>()};
    const std::string refusal = std::string(name) + ": missing (a path or an array of 1..64 paths)";
    if (it == body.end() || !it->is_array() || it->empty() || it->size() > 64)
        return invalid_argument(refusal);
    std::vector<std::string> paths;
    for (const json& p : *it) {
        if (!p.is_string()) return invalid_argument(refusal);
        paths.push_back(p.get<std::string>());
    }
    return paths;
}

// A brush stroke: "points", "width" (default 40 px), "comb" (default false).
Result<paint::Stroke> stroke_field(const json& body) {
    auto points = points_field(body);
    if (!points.ok()) return points.status();
    auto width = number_field(body, "width", 40.0, 1.0, 4096.0);
    if (!width.ok()) return width.status();
    paint::Stroke stroke;
    for (const sketch::Vec2& p : *points) {
        stroke.points.push_back({static_cast<float>(p.x), static_cast<float>(p.y)});
    }
    stroke.width_px = static_cast<float>(*width);
    const auto comb = body.find("comb");
    stroke.comb = comb != body.end() && comb->is_boolean() && comb->get<bool>();
    return stroke;
}

// Sets the option `key` of a module's option table (the CLI's flag names) from a JSON number
// with the module's own checks; nullopt when the table has no such key.
template <class Options, class Spec>
std::optional<Status> set_table_key(Options& options, std::span<const Spec> specs,
                                    const std::string& key, const json& value) {
    for (const Spec& spec : specs) {
        if (spec.name != key) continue;
        if (!value.is_number()) return invalid_argument(key + ": must be a number");
        return set_option(options, spec, value.get<double>());
    }
    return std::nullopt;
}

// A region drawn as a polygon (canvas pixels) under `name`: its region image, `width` × `height`.
Result<Image> region_field(const json& body, const char* name, int width, int height) {
    auto points = points_field(body, name, 3);
    if (!points.ok()) return points.status();
    std::vector<paint::StrokePoint> polygon;
    for (const sketch::Vec2& p : *points) {
        polygon.push_back({static_cast<float>(p.x), static_cast<float>(p.y)});
    }
    return paint::polygon_mask(std::span(&polygon, 1), width, height);
}

std::string content_type_of(const std::string& path) {
    static const std::map<std::string, std::string> kTypes = {
        {".png", "image/png"},         {".jpg", "image/jpeg"},
        {".jpeg", "image/jpeg"},       {".svg", "image/svg+xml"},
        {".json", "application/json"}, {".txt", "text/plain; charset=utf-8"}};
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    const auto it = kTypes.find(ext);
    return it == kTypes.end() ? "application/octet-stream" : it->second;
}

// RGBA8 bytes of `rect` of a straight-alpha RGBA image (what the browser's ImageData holds).
std::string rgba_bytes(const Image& image, const paint::PixelRect& rect) {
    std::string out;
    out.reserve(static_cast<std::size_t>(rect.x1 - rect.x0) *
                static_cast<std::size_t>(rect.y1 - rect.y0) * 4);
    for (int y = rect.y0; y < rect.y1; ++y) {
        for (int x = rect.x0; x < rect.x1; ++x) {
            const float* p = image.pixel(x, y);
            for (int c = 0; c < 4; ++c) {
                out.push_back(static_cast<char>(static_cast<unsigned char>(
                    std::lround(std::clamp(p[c], 0.0f, 1.0f) * 255.0f))));
            }
        }
    }
    return out;
}

void answer_rgba(Response& res, const Image& image, const paint::PixelRect& rect) {
    res.set_header("X-Rect", std::to_string(rect.x0) + "," + std::to_string(rect.y0) + "," +
                                 std::to_string(rect.x1) + "," + std::to_string(rect.y1));
    res.set_content(rgba_bytes(image, rect), "application/octet-stream");
}

json suggestion_json(const sketch::Suggestion& s) {
    return {
        {"d", sketch::path_data(s.path)}, {"likelihood", s.likelihood}, {"original", s.original}};
}

json sketch_state(const SketchSession& sketch) {
    json paths = json::array();
    for (const sketch::ResolvedPath& p : sketch.drawing().paths) {
        paths.push_back(sketch::path_data(p.path));
    }
    return {{"paths", paths}, {"can_undo", sketch.can_undo()}, {"can_redo", sketch.can_redo()}};
}

// The tool state of one client (one browser tab).
struct ClientState {
    std::mutex mutex;
    std::uint64_t used = 0;  ///< When it was last asked for (the server's request count).
    SketchSession sketch;
    /// Shared: a request keeps using the painting it found while a new start replaces it.
    std::shared_ptr<PaintPipeline> paint;
    std::optional<BrushSession> brush;
    /// The brush's strokes and fills in flight: undo and a new start cancel them.
    StepSlot brush_steps;
};

}  // namespace

struct StudioServer::Impl {
    Impl(const StudioOptions& o, Workspace w)
        : options(o),
          workspace(std::move(w)),
          jobs(o.max_jobs_per_client, o.threads, o.max_finished_jobs) {}

    StudioOptions options;
    Workspace workspace;
    JobManager jobs;
    std::unique_ptr<plugin::http::Server> http;
    int port = 0;
    std::atomic<bool> stopping{false};
    /// Set by shutdown: interactive calls still running (a repaint) return Cancelled.
    CancelToken interactive_cancel;

    /// The context of an interactive library call.
    RunContext interactive_context() const {
        RunContext context(options.threads);
        context.cancel = &interactive_cancel;
        return context;
    }
    std::mutex clients_mutex;
    std::map<std::string, std::shared_ptr<ClientState>> clients;

    // The client's id (header X-Studio-Client, default "default"), or "" after answering 400.
    static std::string client_id(const Request& req, Response& res) {
        std::string id = req.header("X-Studio-Client");
        if (id.empty()) return "default";
        const bool valid =
            id.size() <= 64 && std::all_of(id.begin(), id.end(), [](char c) {
                return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
            });
        if (!valid) {
            fail(res, 400, "X-Studio-Client: must be 1..64 letters, digits, '-' or '_'");
            return "";
        }
        return id;
    }

    /// The client's state, made on its first request. Beyond options.max_clients the client
    /// unused longest is forgotten (a request of it still running keeps its state until done).
    std::shared_ptr<ClientState> client(const std::string& id) {
        std::lock_guard lock(clients_mutex);
        if (!clients.contains(id) && clients.size() >= options.max_clients) {
            const auto oldest = std::min_element(
                clients.begin(), clients.end(),
                [](const auto& a, const auto& b) { return a.second->used < b.second->used; });
            clients.erase(oldest);
        }
        auto& state = clients[id];
        if (!state) state = std::make_shared<ClientState>();
        state->used = ++client_requests;
        return state;
    }
    std::uint64_t client_requests = 0;  ///< Under clients_mutex.

    // Runs `handler(state)` under the client's lock.
    template <typename Handler>
    void with_client(const Request& req, Response& res, Handler handler) {
        const std::string id = client_id(req, res);
        if (id.empty()) return;
        const auto state = client(id);
        std::lock_guard lock(state->mutex);
        handler(*state);
    }

    /// Runs a brush step, `step(session, context)` → the rectangle it changed, under the
    /// client's lock with its own cancel token (StepSlot), and answers that rectangle. A step
    /// that undo or a new start cancels answers 409 and keeps nothing (one that had finished
    /// goes to redo).
    template <typename Step>
    void brush_step(const Request& req, Response& res, Step step) {
        const std::string id = client_id(req, res);
        if (id.empty()) return;
        const auto state = client(id);
        const auto token = state->brush_steps.begin();
        std::lock_guard lock(state->mutex);
        RunContext context(options.threads);
        context.cancel = token.get();
        auto changed =
            state->brush ? step(*state->brush, context) : Result<paint::PixelRect>(unsupported(""));
        const bool kept = state->brush_steps.finish(token);
        if (!state->brush) return fail(res, 409, "no painting: POST /api/brush/start first");
        if (!changed.ok()) return fail(res, changed.status());
        if (!kept) {
            state->brush->undo();
            return fail(res, 409, "stroke: cancelled (undone, or the painting was replaced)");
        }
        answer_rgba(res, state->brush->image(), *changed);
    }

    /// Why a request comes from elsewhere than the studio's own page ("" if it does not). The
    /// app has no login, so (1) on a loopback address the Host header must name that address
    /// or localhost, which defeats DNS rebinding (a page whose name resolves to 127.0.0.1
    /// reading the workspace), and (2) an Origin header, which browsers send with cross-site
    /// requests, must be the studio's own, so another site's page cannot post strokes, jobs or
    /// saves through the user's browser.
    std::string foreign(const Request& req) const {
        const std::string host = req.header("Host");
        const std::string port_suffix = ":" + std::to_string(port);
        const bool loopback =
            options.bind == "127.0.0.1" || options.bind == "localhost" || options.bind == "::1";
        if (loopback && host != "127.0.0.1" + port_suffix && host != "localhost" + port_suffix &&
            host != "[::1]" + port_suffix) {
            return "Host \"" + host.substr(0, 80) + "\" is not this studio's address";
        }
        const std::string origin = req.header("Origin");
        if (!origin.empty() && origin != "http://" + host) {
            return "requests from other sites (Origin \"" + origin.substr(0, 80) +
                   "\") are refused";
        }
        return "";
    }
    void add_routes();
    void add_file_routes();
    void add_sketch_routes();
    /// What every painting tool starts from: an image of the workspace, the canvas size, the seed.
    struct CanvasStart {
        Image image;
        int width = 0;
        int height = 0;
        std::uint64_t seed = 1;
    };
    /// Reads `image_field` (a workspace path, loaded), "width", "height" and "seed" of a start
    /// request; nullopt after answering the error (403 for a refused path, 404 for a missing
    /// or unreadable image).
    std::optional<CanvasStart> canvas_start(const json& body, const char* image_field,
                                            Response& res) const;
    void add_paint_routes();
    void add_brush_routes();
    void add_fill_route();
    void add_paint_canvas_routes();
    void add_brush_canvas_routes();
    /// The client's painting, or null after answering (400 for a bad client id, 409 without one).
    std::shared_ptr<PaintPipeline> painting(const Request& req, Response& res);
    /// Cancels every client's pending paint strokes and brush steps (shutdown).
    void cancel_paintings();
    void add_job_routes();
    /// A job's files by field, resolved in the workspace by the route: one path per field
    /// (stylize: style, source, target, output; noisy: exemplar, reference, output; stylit:
    /// exemplar, output) and lists of paths (stylit: source, target).
    /// The frame files of a range job's pattern (a workspace path with one %d conversion)
    /// formatted for first..last, each resolved in the workspace.
    struct FrameFiles {
        int first = 0;
        std::vector<std::string> relative;  ///< As the client names them.
        std::vector<std::string> absolute;  ///< Resolved.
        /// For frames a job reads: ok when every file exists, else `FIELD: NAME: no such file`
        /// naming the first one missing.
        Status check_exist(const std::string& field) const {
            for (std::size_t k = 0; k < absolute.size(); ++k) {
                if (!std::filesystem::is_regular_file(absolute[k]))
                    return invalid_argument(field + ": " + relative[k] + ": no such file");
            }
            return Status::ok();
        }
    };
    struct JobPaths {
        std::map<std::string, std::filesystem::path> one;
        std::map<std::string, std::vector<std::string>> lists;
        std::map<std::string, FrameFiles> patterns;
        const std::filesystem::path& at(const std::string& field) const { return one.at(field); }
        bool contains(const std::string& field) const {
            return one.contains(field) || lists.contains(field) || patterns.contains(field);
        }
    };
    Result<JobWork> stylize_work(const json& body, const JobPaths& paths);
    Result<JobWork> noisy_work(const json& body, const JobPaths& paths);
    Result<JobWork> stylit_work(const json& body, const JobPaths& paths);
    Result<JobWork> animate_work(const json& body, const JobPaths& paths);
    Result<JobWork> fluid_simulate_work(const json& body, const JobPaths& paths);
    Result<JobWork> fluid_work(const json& body, const JobPaths& paths);
    Result<JobWork> npr_work(const json& body, const JobPaths& paths);
    static Status check_job_keys(const json& body, const JobPaths& paths,
                                 std::initializer_list<std::string_view> known, const char* kind);
};

void StudioServer::Impl::add_routes() {
    http->set_gate([this](const Request& req, Response& res) {
        if (stopping) {
            fail(res, 503, "the studio is shutting down");
            return true;
        }
        const std::string refusal = foreign(req);
        if (refusal.empty()) return false;
        fail(res, 403, refusal);
        return true;
    });
    for (const Asset& asset : assets()) {
        http->route("GET", std::string(asset.path), [&asset](const Request&, Response& res) {
            res.set_header("Cache-Control", "no-store");
            res.set_content(std::string(asset.bytes), std::string(asset.content_type).c_str());
        });
    }
    http->route("GET", "/api/info", [this](const Request&, Response& res) {
        answer(res, 200,
               {{"version", std::string(version())},
                {"max_upload_bytes", options.max_upload_bytes},
                {"max_jobs_per_client", options.max_jobs_per_client},
                {"max_canvas", kMaxCanvas},
                {"paint_history", PaintSession::kHistory}});
    });
    add_file_routes();
    add_sketch_routes();
    add_paint_routes();
    add_brush_routes();
    add_paint_canvas_routes();
    add_brush_canvas_routes();
    add_fill_route();
    add_job_routes();
}

void StudioServer::Impl::add_file_routes() {
    http->route("GET", "/api/files", [this](const Request&, Response& res) {
        json files = json::array();
        for (const WorkspaceFile& f : workspace.list()) {
            files.push_back({{"path", f.path}, {"bytes", f.bytes}});
        }
        answer(res, 200, {{"files", files}});
    });
    http->route("GET", R"(/api/files/(.+))", [this](const Request& req, Response& res) {
        const std::string path = req.matches[1];
        auto resolved = workspace.resolve(path);
        if (!resolved.ok()) return fail(res, 403, resolved.status().message());
        auto bytes = workspace.read(path, kMaxDownloadBytes);
        if (!bytes.ok()) return fail(res, 404, bytes.status().message());
        if (req.has_param("download")) {
            res.set_header(
                "Content-Disposition",
                "attachment; filename=\"" + std::filesystem::path(path).filename().string() + "\"");
        }
        res.set_header("Cache-Control", "no-store");
        res.set_content(std::move(*bytes), content_type_of(path).c_str());
    });
    http->route("PUT", R"(/api/files/(.+))", [this](const Request& req, Response& res) {
        const std::string path = req.matches[1];
        auto resolved = workspace.resolve(path);
        if (!resolved.ok()) return fail(res, 403, resolved.status().message());
        if (req.body.size() > options.max_upload_bytes) {
            return fail(res, 413, path + ": upload over the limit");
        }
        auto type = sniff_upload_type(req.body);
        if (!type.ok()) return fail(res, 415, path + ": " + type.status().message());
        const std::string ext = content_type_of(path);
        const bool matches = (*type == UploadType::Png && ext == "image/png") ||
                             (*type == UploadType::Jpeg && ext == "image/jpeg");
        if (!matches) {
            return fail(res, 415, path + ": the extension does not match the file's type");
        }
        const Status written = workspace.write(path, req.body);
        if (!written.is_ok()) return fail(res, 500, written.message());
        answer(res, 201, {{"path", path}});
    });
}

void StudioServer::Impl::add_sketch_routes() {
    http->route("GET", "/api/sketch", [this](const Request& req, Response& res) {
        with_client(req, res, [&](ClientState& c) { answer(res, 200, sketch_state(c.sketch)); });
    });
    http->route("POST", "/api/sketch/stroke", [this](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        auto points = points_field(*body);
        if (!points.ok()) return fail(res, points.status());
        with_client(req, res, [&](ClientState& c) {
            auto suggestions = c.sketch.stroke(*points);
            if (!suggestions.ok()) return fail(res, suggestions.status());
            json list = json::array();
            for (const sketch::Suggestion& s : *suggestions) list.push_back(suggestion_json(s));
            answer(res, 200, {{"suggestions", list}});
        });
    });
    http->route("POST", "/api/sketch/accept", [this](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        auto index = number_field(*body, "index", 0.0, 0.0, 1000.0);
        if (!index.ok()) return fail(res, index.status());
        with_client(req, res, [&](ClientState& c) {
            const Status accepted = c.sketch.accept(static_cast<int>(*index));
            if (!accepted.is_ok()) return fail(res, 409, accepted.message());
            answer(res, 200, sketch_state(c.sketch));
        });
    });
    for (const char* action : {"undo", "redo", "reset"}) {
        http->route("POST", std::string("/api/sketch/") + action,
                    [this, action](const Request& req, Response& res) {
                        with_client(req, res, [&](ClientState& c) {
                            const std::string a = action;
                            if (a == "undo") c.sketch.undo();
                            if (a == "redo") c.sketch.redo();
                            if (a == "reset") c.sketch.reset();
                            answer(res, 200, sketch_state(c.sketch));
                        });
                    });
    }
}

std::optional<StudioServer::Impl::CanvasStart> StudioServer::Impl::canvas_start(
    const json& body, const char* image_field, Response& res) const {
    auto name = text_field(body, image_field);
    auto width = number_field(body, "width", std::nullopt, 1, kMaxCanvas);
    auto height = number_field(body, "height", std::nullopt, 1, kMaxCanvas);
    auto seed = number_field(body, "seed", 1.0, 0.0, 1e15);
    for (const Status& s : {name.status(), width.status(), height.status(), seed.status()}) {
        if (!s.is_ok()) {
            fail(res, s);
            return std::nullopt;
        }
    }
    auto path = workspace.resolve(*name);
    if (!path.ok()) {
        fail(res, 403, path.status().message());
        return std::nullopt;
    }
    auto image = load_image(path->string());
    if (!image.ok()) {
        fail(res, 404, *name + ": " + image.status().message());
        return std::nullopt;
    }
    return CanvasStart{std::move(*image), static_cast<int>(*width), static_cast<int>(*height),
                       static_cast<std::uint64_t>(*seed)};
}

void StudioServer::Impl::add_paint_routes() {
    http->route("POST", "/api/paint/start", [this](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        auto start = canvas_start(*body, "exemplar", res);
        if (!start) return;
        paint::PaintOptions paint_options;
        paint_options.seed = start->seed;
        if (body->contains("usage")) {
            auto usage = text_field(*body, "usage");
            if (!usage.ok()) return fail(res, usage.status());
            auto strategy = parse_usage_strategy(*usage);
            if (!strategy.ok()) return fail(res, strategy.status());
            paint_options.usage = *strategy;
        }
        auto session = PaintSession::start(std::move(start->image), start->width, start->height,
                                           paint_options, options.threads);
        if (!session.ok()) return fail(res, session.status());
        with_client(req, res, [&](ClientState& c) {
            // The strokes still pending on the old painting stop.
            if (c.paint) c.paint->cancel();
            c.paint = std::make_shared<PaintPipeline>(std::move(*session));
            answer(res, 200, {{"width", c.paint->width()}, {"height", c.paint->height()}});
        });
    });
    // Pen-up, first request: the stroke previewed at a reduced scale (the state is unchanged);
    // the client then posts it to /api/paint/stroke for the final pixels.
    http->route("POST", "/api/paint/preview", [this](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        auto stroke = stroke_field(*body);
        if (!stroke.ok()) return fail(res, stroke.status());
        auto reduction = number_field(*body, "reduction", 4.0, 1.0, 16.0);
        if (!reduction.ok()) return fail(res, reduction.status());
        const auto paint = painting(req, res);
        if (!paint) return;
        const Status previewed =
            paint->preview(*stroke, static_cast<int>(*reduction), interactive_context(),
                           [&res](const Image& image, const paint::PixelRect& rect) {
                               answer_rgba(res, image, rect);
                           });
        if (!previewed.is_ok()) return fail(res, previewed);
    });
}

namespace {

// The "output" of a save request: a .png path in the workspace, or nullopt after answering.
std::optional<std::filesystem::path> png_output(const json& body, const Workspace& workspace,
                                                Response& res) {
    auto output = text_field(body, "output");
    if (!output.ok()) {
        fail(res, output.status());
        return std::nullopt;
    }
    if (content_type_of(*output) != "image/png") {
        fail(res, 400, "output: " + *output + " must end in .png");
        return std::nullopt;
    }
    auto path = workspace.resolve(*output);
    if (!path.ok()) {
        fail(res, 403, path.status().message());
        return std::nullopt;
    }
    return *path;
}

}  // namespace

std::shared_ptr<PaintPipeline> StudioServer::Impl::painting(const Request& req, Response& res) {
    const std::string id = client_id(req, res);
    if (id.empty()) return nullptr;
    const auto state = client(id);
    std::lock_guard lock(state->mutex);
    if (!state->paint) fail(res, 409, "no painting: POST /api/paint/start first");
    return state->paint;
}

void StudioServer::Impl::cancel_paintings() {
    std::lock_guard lock(clients_mutex);
    for (const auto& [id, state] : clients) {
        state->brush_steps.cancel_all();
        std::lock_guard client_lock(state->mutex);
        if (state->paint) state->paint->cancel();
    }
}

// A painting's stroke, undo, redo and save, through its pipeline (PaintPipeline): a stroke
// answers the rectangle it changed as RGBA once the strokes before it are final, undo and redo
// the whole canvas; save writes it as a PNG into the workspace. None holds the client's lock
// while it waits, so previews and other tools go on.
void StudioServer::Impl::add_paint_canvas_routes() {
    const auto answer_with = [](Response& res) {
        return [&res](const Image& image, const paint::PixelRect& rect) {
            answer_rgba(res, image, rect);
        };
    };
    http->route(
        "POST", "/api/paint/stroke", [this, answer_with](const Request& req, Response& res) {
            const auto body = json_body(req, res);
            if (!body) return;
            auto stroke = stroke_field(*body);
            if (!stroke.ok()) return fail(res, stroke.status());
            const auto paint = painting(req, res);
            if (!paint) return;
            const Status painted = paint->stroke(*stroke, interactive_context(), answer_with(res));
            if (!painted.is_ok()) return fail(res, painted);
        });
    http->route("POST", "/api/paint/undo", [this, answer_with](const Request& req, Response& res) {
        if (const auto paint = painting(req, res)) paint->undo(answer_with(res));
    });
    http->route("POST", "/api/paint/redo", [this, answer_with](const Request& req, Response& res) {
        if (const auto paint = painting(req, res)) paint->redo(answer_with(res));
    });
    http->route("GET", "/api/paint", [this](const Request& req, Response& res) {
        const auto paint = painting(req, res);
        if (!paint) return;
        const PaintPipeline::Counts counts = paint->counts();
        answer(res, 200,
               {{"width", paint->width()},
                {"height", paint->height()},
                {"strokes", counts.strokes},
                {"pending", counts.pending}});
    });
    http->route("POST", "/api/paint/save", [this](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        const auto path = png_output(*body, workspace, res);
        if (!path) return;
        const auto paint = painting(req, res);
        if (!paint) return;
        paint->settled([&](const Image& image, const paint::PixelRect&) {
            const Status saved = save_image(image, path->string());
            if (!saved.is_ok()) return fail(res, 500, saved.message());
            answer(res, 200, {{"path", body->value("output", std::string())}});
        });
    });
}

// The brush painting's stroke, undo, redo and save: a stroke answers the rectangle it changed
// as RGBA, undo and redo the whole canvas; save writes it as a PNG into the workspace.
void StudioServer::Impl::add_brush_canvas_routes() {
    const std::string missing = "no painting: POST /api/brush/start first";
    http->route("POST", "/api/brush/stroke", [this, missing](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        auto stroke = stroke_field(*body);
        if (!stroke.ok()) return fail(res, stroke.status());
        brush_step(req, res, [&](BrushSession& brush, const RunContext& context) {
            return brush.stroke(*stroke, context);
        });
    });
    for (const std::string action : {"undo", "redo"}) {
        http->route(
            "POST", "/api/brush/" + action,
            [this, action, missing](const Request& req, Response& res) {
                // Undo takes back the newest stroke or fill: one still running stops.
                const std::string id = client_id(req, res);
                if (id.empty()) return;
                const bool stopped = action == "undo" && client(id)->brush_steps.cancel_newest();
                with_client(req, res, [&](ClientState& c) {
                    if (!c.brush) return fail(res, 409, missing);
                    if (action == "redo") {
                        c.brush->redo();
                    } else if (!stopped) {
                        c.brush->undo();
                    }
                    answer_rgba(res, c.brush->image(), {0, 0, c.brush->width(), c.brush->height()});
                });
            });
    }
    http->route("POST", "/api/brush/save", [this, missing](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        const auto path = png_output(*body, workspace, res);
        if (!path) return;
        with_client(req, res, [&](ClientState& c) {
            if (!c.brush) return fail(res, 409, missing);
            const Status saved = save_image(c.brush->image(), path->string());
            if (!saved.is_ok()) return fail(res, 500, saved.message());
            answer(res, 200, {{"path", body->value("output", std::string())}});
        });
    });
}

void StudioServer::Impl::add_brush_routes() {
    http->route("POST", "/api/brush/start", [this](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        const auto feature = body->find("feature");
        if (feature == body->end() || !feature->is_object()) {
            return fail(res, 400, "feature: missing (an object with points and width)");
        }
        auto selection = stroke_field(*feature);
        if (!selection.ok()) return fail(res, selection.status());
        auto start = canvas_start(*body, "palette", res);
        if (!start) return;
        paint::FeatureBrushOptions brush_options;
        brush_options.seed = start->seed;
        if (body->contains("walk")) {
            auto walk = paint::parse_walk_mode(body->value("walk", std::string()));
            if (!walk.ok()) return fail(res, walk.status());
            brush_options.walk = *walk;
        }
        auto session =
            BrushSession::start(start->image, *selection, start->width, start->height,
                                brush_options, body->value("snap", true), options.threads);
        if (!session.ok()) return fail(res, session.status());
        // Strokes and fills running or waiting on the old painting stop.
        const std::string id = client_id(req, res);
        if (id.empty()) return;
        client(id)->brush_steps.cancel_all();
        with_client(req, res, [&](ClientState& c) {
            c.brush.emplace(std::move(*session));
            json line = json::array();
            for (const paint::StrokePoint& p : c.brush->feature_line()) line.push_back({p.x, p.y});
            answer(res, 200,
                   {{"width", c.brush->width()}, {"height", c.brush->height()}, {"feature", line}});
        });
    });
}

void StudioServer::Impl::add_fill_route() {
    http->route("POST", "/api/brush/fill", [this](const Request& req, Response& res) {
        const auto body = json_body(req, res);
        if (!body) return;
        paint::FeatureFillOptions fill_options;
        for (const auto& [key, value] : body->items()) {
            if (key == "source" || key == "target") continue;
            if (key == "usage") {
                auto usage = value.is_string() ? parse_usage_strategy(value.get<std::string>())
                                               : invalid_argument("must be a string");
                if (!usage.ok()) return fail(res, 400, "usage: " + usage.status().message());
                fill_options.usage = *usage;
                continue;
            }
            if (key == "seed") {
                const Status seed = read_seed(*body, fill_options.seed);
                if (!seed.is_ok()) return fail(res, seed);
                continue;
            }
            const auto set =
                set_table_key(fill_options, paint::feature_fill_option_specs(), key, value);
            if (!set) return fail(res, 400, key + ": unknown option of the fill");
            if (!set->is_ok()) return fail(res, *set);
        }
        brush_step(req, res,
                   [&](BrushSession& brush, const RunContext& context) -> Result<paint::PixelRect> {
                       auto source = region_field(*body, "source", brush.palette().width(),
                                                  brush.palette().height());
                       if (!source.ok()) return source.status();
                       auto target = region_field(*body, "target", brush.width(), brush.height());
                       if (!target.ok()) return target.status();
                       return brush.fill(*source, *target, fill_options, context);
                   });
    });
}

namespace {

// A job's output must be an image the atomic writers know.
Status check_image_output(const std::filesystem::path& output) {
    const std::string type = content_type_of(output.string());
    if (type != "image/png" && type != "image/jpeg") {
        return invalid_argument("output: must end in .png or .jpg");
    }
    return Status::ok();
}

}  // namespace

// A stylize job (guided synthesis, one guide pair): the inputs are loaded and checked here, so a
// bad job is refused at once; the work is the synthesis and the atomic write of its output.
Result<JobWork> StudioServer::Impl::stylize_work(const json& body, const JobPaths& paths) {
    SynthesisInput input;
    input.guides.resize(1);
    input.guides[0].name = "guide";
    const std::pair<const char*, Image*> inputs[] = {{"style", &input.style},
                                                     {"source", &input.guides[0].source},
                                                     {"target", &input.guides[0].target}};
    for (const auto& [field, image] : inputs) {
        auto loaded = load_image(paths.at(field).string());
        if (!loaded.ok())
            return invalid_argument(std::string(field) + ": " + loaded.status().message());
        *image = std::move(*loaded);
    }
    EXEMPLAR_RETURN_IF_ERROR(check_image_output(paths.at("output")));
    auto quality = parse_quality(body.value("quality", std::string("default")));
    if (!quality.ok()) return quality.status();
    SynthesisOptions synthesis = SynthesisOptions::preset(*quality);
    EXEMPLAR_RETURN_IF_ERROR(read_seed(body, synthesis.seed));
    EXEMPLAR_RETURN_IF_ERROR(validate_input(input, synthesis));
    return JobWork([input = std::move(input), synthesis, path = paths.at("output").string()](
                       const RunContext& context, const OutputSink&) mutable -> Status {
        auto result = synthesize(std::move(input), synthesis, context);
        if (!result.ok()) return result.status();
        return save_image(result->image, path);
    });
}

namespace {

// The noisy job's path fields, by its form (docs/studio.md, "noisy"), for the route to resolve in
// the workspace before noisy_work runs. One frame (`reference`) has one output; a range
// (`frames`: a pattern, or a folder of images) has an output pattern, and each of its per-pixel
// inputs is one file or a pattern with the frames' numbers.
constexpr const char* kNoisyMaps[] = {"noise-map", "source-map", "frame-orientation"};

bool noisy_range_form(const json& body) {
    return body.contains("frames");
}

bool pattern_value(const json& body, const char* field) {
    const auto it = body.find(field);
    return it != body.end() && it->is_string() &&
           it->get<std::string>().find('%') != std::string::npos;
}

// One path each.
std::vector<const char*> noisy_files(const json& body) {
    const bool range = noisy_range_form(body);
    std::vector<const char*> files;
    if (!range) files = {"reference", "output"};
    if (range && !pattern_value(body, "frames")) files.push_back("frames");  // a folder
    for (const char* map : kNoisyMaps) {
        if (body.contains(map) && !(range && pattern_value(body, map))) files.push_back(map);
    }
    return files;
}

// A path or a list of paths each.
std::vector<const char*> noisy_file_lists(const json& body) {
    if (body.contains("exemplar-orientation")) return {"exemplar", "exemplar-orientation"};
    return {"exemplar"};
}

// Frame patterns, formatted for first..last.
std::vector<const char*> noisy_patterns(const json& body) {
    if (!noisy_range_form(body)) return {};
    std::vector<const char*> patterns = {"output"};
    if (pattern_value(body, "frames")) patterns.push_back("frames");
    for (const char* map : kNoisyMaps) {
        if (pattern_value(body, map)) patterns.push_back(map);
    }
    return patterns;
}

}  // namespace

// A noisy job (Color Me Noisy): what `exemplar noisy` does, through the same range driver
// (noisy::synthesize_range). One frame: the medium (or media) over `reference`, keyed by `frame`
// (default 0), to `output`. A range: the frames `frames` (a pattern, or a folder whose images in
// name order are frames 0, 1, ...) first..last to the pattern `output`, each reported as it is
// written. Either takes several media (`exemplar` as an array) with `source-map`, `noise-map`,
// and `exemplar-orientation` with `frame-orientation`; `seed`, `filter` and the noisy option
// table's keys (noise required, as on the command line). Every input is checked here; frame and
// map sizes are the driver's, so a bad one fails the job at its frame.
Result<JobWork> StudioServer::Impl::noisy_work(const json& body, const JobPaths& paths) {
    const bool range_form = noisy_range_form(body);
    if (!body.contains("noise")) {
        return invalid_argument("noise: missing (the low-pass strength f in pixels)");
    }
    if (range_form && body.contains("reference")) {
        return invalid_argument(
            "reference: give reference (one frame) or frames (a range), not both");
    }
    if (range_form && body.contains("frame")) {
        return invalid_argument(
            "frame: only with reference (a range's frames are keyed by their numbers)");
    }
    noisy::NoisyOptions noisy_options;
    for (const auto& [key, value] : body.items()) {
        if (key == "kind" || paths.contains(key) || key == "seed" || key == "frame" ||
            (range_form && (key == "first" || key == "last"))) {
            continue;
        }
        if (key == "filter") {
            if (!value.is_string()) return invalid_argument("filter: must be a string");
            auto filter = noisy::parse_low_pass_filter(value.get<std::string>());
            if (!filter.ok()) return filter.status();
            noisy_options.filter = *filter;
            continue;
        }
        const auto set = set_table_key(noisy_options, noisy::noisy_option_specs(), key, value);
        if (!set) return invalid_argument(key + ": unknown option of a noisy job");
        EXEMPLAR_RETURN_IF_ERROR(*set);
    }
    EXEMPLAR_RETURN_IF_ERROR(read_seed(body, noisy_options.seed));
    EXEMPLAR_RETURN_IF_ERROR(noisy::validate(noisy_options));

    // The media and their orientation fields.
    std::vector<noisy::NoisySource> sources;
    for (const std::string& file : paths.lists.at("exemplar")) {
        auto medium = load_image(file);
        if (!medium.ok()) return invalid_argument("exemplar: " + medium.status().message());
        sources.push_back({std::move(*medium), Image()});
    }
    const bool oriented = paths.lists.contains("exemplar-orientation");
    if (oriented != paths.contains("frame-orientation")) {
        return invalid_argument(
            "exemplar-orientation and frame-orientation: give both, or neither");
    }
    if (oriented) {
        const std::vector<std::string>& files = paths.lists.at("exemplar-orientation");
        if (files.size() != sources.size()) {
            return invalid_argument("exemplar-orientation: " + std::to_string(files.size()) +
                                    " given for " + std::to_string(sources.size()) +
                                    " exemplars (give one per exemplar, in their order)");
        }
        for (std::size_t k = 0; k < files.size(); ++k) {
            auto angles = noisy::load_orientation_field(files[k]);
            if (!angles.ok())
                return invalid_argument("exemplar-orientation: " + angles.status().message());
            sources[k].orientation = std::move(*angles);
        }
    }
    if (sources.size() > 1 && !paths.contains("source-map")) {
        return invalid_argument("source-map: is required with " + std::to_string(sources.size()) +
                                " exemplars (it chooses the medium of every pixel)");
    }

    // The frames and their outputs.
    noisy::NoisyRange range;
    range.resume = false;  // a job runs again with other options: it rewrites its frames
    std::vector<std::string> reported;  // a range's outputs as the client names them
    if (!range_form) {
        auto frame = number_field(body, "frame", 0.0, 0.0, 1e9);
        if (!frame.ok()) return frame.status();
        if (*frame != std::floor(*frame)) return invalid_argument("frame: must be an integer");
        range.first = range.last = static_cast<int>(*frame);
        auto reference = load_image(paths.at("reference").string());
        if (!reference.ok()) return invalid_argument("reference: " + reference.status().message());
        EXEMPLAR_RETURN_IF_ERROR(check_image_output(paths.at("output")));
        range.reference = [image = std::move(*reference)](int) -> Result<Image> { return image; };
        range.reference_name = [name = body.value("reference", std::string())](int) {
            return name;
        };
        range.output_file = [file = paths.at("output").string()](int) -> Result<std::string> {
            return file;
        };
    } else {
        const FrameFiles& outputs = paths.patterns.at("output");
        EXEMPLAR_RETURN_IF_ERROR(check_image_output(outputs.absolute.front()));
        range.first = outputs.first;
        range.last = outputs.first + static_cast<int>(outputs.absolute.size()) - 1;
        reported = outputs.relative;
        FrameFiles frames;
        if (paths.patterns.contains("frames")) {
            frames = paths.patterns.at("frames");
            EXEMPLAR_RETURN_IF_ERROR(frames.check_exist("frames"));
        } else {
            // A folder: its images in name order, each resolved in the workspace.
            const std::string folder = body.value("frames", std::string());
            auto sequence = video::FrameSequence::from_folder(paths.at("frames").string());
            if (!sequence.ok()) return invalid_argument("frames: " + sequence.status().message());
            if (range.last >= sequence->size()) {
                return invalid_argument("last: " + std::to_string(range.last) +
                                        " is invalid (the folder " + folder + " has frames 0.." +
                                        std::to_string(sequence->size() - 1) + ")");
            }
            frames.first = range.first;
            for (int n = range.first; n <= range.last; ++n) {
                const std::string name =
                    folder + "/" +
                    std::filesystem::path(sequence->frame_name(n)).filename().string();
                auto path = workspace.resolve(name);
                if (!path.ok()) return invalid_argument("frames: " + path.status().message());
                frames.relative.push_back(name);
                frames.absolute.push_back(path->string());
            }
        }
        range.reference = [files = frames.absolute, first = range.first](int n) {
            return load_image(files[static_cast<std::size_t>(n - first)]);
        };
        range.reference_name = [names = frames.relative, first = range.first](int n) {
            return names[static_cast<std::size_t>(n - first)];
        };
        range.output_file = [files = outputs.absolute,
                             first = range.first](int n) -> Result<std::string> {
            return files[static_cast<std::size_t>(n - first)];
        };
    }

    // The per-pixel inputs: one file (checked now) or a file per frame (each must exist).
    const auto range_input = [&](const char* field,
                                 const auto& check) -> Result<noisy::RangeInput> {
        noisy::RangeInput input;
        if (paths.one.contains(field)) {
            const std::string file = paths.at(field).string();
            const Status checked = check(file);
            if (!checked.is_ok())
                return invalid_argument(std::string(field) + ": " + checked.message());
            input.file = [file](int) -> Result<std::string> { return file; };
        } else if (paths.patterns.contains(field)) {
            const FrameFiles& files = paths.patterns.at(field);
            EXEMPLAR_RETURN_IF_ERROR(files.check_exist(field));
            input.per_frame = true;
            input.file = [files = files.absolute,
                          first = files.first](int n) -> Result<std::string> {
                return files[static_cast<std::size_t>(n - first)];
            };
        }
        return input;
    };
    auto noise_map = range_input(
        "noise-map", [](const std::string& file) { return noisy::load_noise_map(file).status(); });
    if (!noise_map.ok()) return noise_map.status();
    range.noise_map = std::move(*noise_map);
    auto source_map = range_input("source-map", [&](const std::string& file) {
        return noisy::load_source_map(file, sources.size()).status();
    });
    if (!source_map.ok()) return source_map.status();
    range.source_map = std::move(*source_map);
    auto orientation = range_input("frame-orientation", [](const std::string& file) {
        return noisy::load_orientation_field(file).status();
    });
    if (!orientation.ok()) return orientation.status();
    range.orientation = std::move(*orientation);
    if (range.orientation.per_frame) {
        const Status checked = noisy::check_orientation_file(*range.orientation.file(range.first));
        if (!checked.is_ok()) return invalid_argument("frame-orientation: " + checked.message());
    }

    return JobWork([sources = std::move(sources), range, noisy_options, reported](
                       const RunContext& context, const OutputSink& wrote) -> Status {
        noisy::NoisyRange job_range = range;
        if (!reported.empty()) {
            job_range.on_frame = [&](int n, const std::string&) {
                wrote(n, reported[static_cast<std::size_t>(n - job_range.first)]);
                return Status::ok();
            };
        }
        return noisy::synthesize_range(sources, job_range, noisy_options, context);
    });
}

// A StyLit job (the call `exemplar stylit` makes): the painting `exemplar` over the target
// render, guided by both renders' light-path buffers; `source` and `target` are each a list of
// buffer files in guide order, or one folder of `exemplar render` or one multi-layer EXR (a
// string) whose files or layers `preset` (or `layers`) names. Every input is loaded and checked
// here; the work is stylize_render and the atomic write of its image.
Result<JobWork> StudioServer::Impl::stylit_work(const json& body, const JobPaths& paths) {
    EXEMPLAR_RETURN_IF_ERROR(check_job_keys(
        body, paths, {"preset", "layers", "quality", "usage", "seed", "guidance-weight", "preview"},
        "a stylit job"));
    StylitOptions stylit;
    auto quality = quality_field(body);
    if (!quality.ok()) return quality.status();
    stylit.synthesis = SynthesisOptions::preset(quality->value_or(Quality::Default));
    if (body.contains("usage")) {
        auto usage = text_field(body, "usage");
        if (!usage.ok()) return usage.status();
        auto strategy = parse_usage_strategy(*usage);
        if (!strategy.ok()) return invalid_argument("usage: " + strategy.status().message());
        stylit.synthesis.usage = *strategy;
    }
    EXEMPLAR_RETURN_IF_ERROR(read_seed(body, stylit.synthesis.seed));
    auto weight = number_field(body, "guidance-weight", 2.0, 0.0, 100.0);
    if (!weight.ok()) return weight.status();
    stylit.guidance_weight = static_cast<float>(*weight);
    const auto preview = body.find("preview");
    if (preview != body.end() && !preview->is_boolean())
        return invalid_argument("preview: must be true or false");
    stylit.preview = preview != body.end() && preview->get<bool>();
    Result<LayerPreset> preset = invalid_argument("");
    if (body.contains("layers")) {
        auto layers = text_field(body, "layers");
        if (!layers.ok()) return layers.status();
        preset = custom_layer_preset(*layers);
    } else {
        auto name = body.contains("preset") ? text_field(body, "preset")
                                            : Result<std::string>(std::string("exemplar"));
        if (!name.ok()) return name.status();
        preset = find_layer_preset(*name);
    }
    if (!preset.ok()) return invalid_argument("preset: " + preset.status().message());
    EXEMPLAR_RETURN_IF_ERROR(check_image_output(paths.at("output")));

    auto exemplar = load_image(paths.at("exemplar").string());
    if (!exemplar.ok()) return invalid_argument("exemplar: " + exemplar.status().message());
    auto source = load_lpe_buffers(paths.lists.at("source"), *preset);
    if (!source.ok()) return invalid_argument("source: " + source.status().message());
    auto target = load_lpe_buffers(paths.lists.at("target"), *preset);
    if (!target.ok()) return invalid_argument("target: " + target.status().message());
    auto input = stylit_input(*exemplar, *source, *target, stylit);
    if (!input.ok()) return input.status();
    EXEMPLAR_RETURN_IF_ERROR(validate_input(*input, stylit.synthesis));
    return JobWork([exemplar = std::move(*exemplar), source = std::move(*source),
                    target = std::move(*target), stylit, path = paths.at("output").string()](
                       const RunContext& context, const OutputSink&) -> Status {
        auto result = stylize_render(exemplar, source, target, stylit, context);
        if (!result.ok()) return result.status();
        return save_image(result->synthesis.image, path);
    });
}

namespace {

constexpr int kMaxFrames = 1000;

// "first" and "last" of a frame-range job: integers, first <= last, at most kMaxFrames frames.
Result<std::pair<int, int>> frame_range(const json& body) {
    auto first = number_field(body, "first", 0.0, 0.0, 1e6);
    if (!first.ok()) return first.status();
    auto last = number_field(body, "last", std::nullopt, 0.0, 1e6);
    if (!last.ok()) return last.status();
    if (*first != std::floor(*first)) return invalid_argument("first: must be an integer");
    if (*last != std::floor(*last)) return invalid_argument("last: must be an integer");
    if (*last < *first || *last - *first >= kMaxFrames) {
        return invalid_argument("last: " + json(*last).dump() + " is invalid (must be first.." +
                                "first + " + std::to_string(kMaxFrames - 1) + ")");
    }
    return std::pair{static_cast<int>(*first), static_cast<int>(*last)};
}

// The file of frame n of a range job's pattern `field` (its frames first.. resolved as
// `absolute`): those of the range by number; the frame before it (a range continued) by its
// name in the workspace, when it is inside.
std::function<Result<std::string>(int)> frame_namer(const Workspace& workspace, const json& body,
                                                    const char* field, int first,
                                                    const std::vector<std::string>& absolute) {
    return [workspace, absolute, first, pattern = body.value(field, std::string()),
            field](int n) -> Result<std::string> {
        const int k = n - first;
        if (k >= 0 && k < static_cast<int>(absolute.size()))
            return absolute[static_cast<std::size_t>(k)];
        if (n < 0) return invalid_argument(std::string(field) + ": no frame " + std::to_string(n));
        auto name = video::format_frame_path(pattern, n);
        if (!name.ok()) return name.status();
        auto path = workspace.resolve(*name);
        if (!path.ok()) return path.status();
        return path->string();
    };
}

}  // namespace

// An animate job (TCIA, the call `exemplar animate` makes for a job whose flows are estimated):
// the frames `frames` (a pattern) first..last stylized by the pair `style-input` →
// `style-output`; each output frame is written to `output` (a pattern) as soon as it is final
// (the library hands them over from the last to the first).
Result<JobWork> StudioServer::Impl::animate_work(const json& body, const JobPaths& paths) {
    animate::AnimateOptions animate_options;
    EXEMPLAR_RETURN_IF_ERROR(check_job_keys(body, paths,
                                            {"first", "last", "quality", "seed", "levels",
                                             "input-weight", "output-weight", "temporal-weight"},
                                            "an animate job"));
    auto quality = quality_field(body);
    if (!quality.ok()) return quality.status();
    if (*quality) animate_options.synthesis = animate::animate_synthesis_options(**quality);
    EXEMPLAR_RETURN_IF_ERROR(read_seed(body, animate_options.synthesis.seed));
    const std::pair<const char*, float*> weights[] = {
        {"input-weight", &animate_options.input_weight},
        {"output-weight", &animate_options.output_weight},
        {"temporal-weight", &animate_options.temporal_weight}};
    for (const auto& [name, field] : weights) {
        auto weight = number_field(body, name, *field, 0.0, 100.0);
        if (!weight.ok()) return weight.status();
        *field = static_cast<float>(*weight);
    }
    auto levels = number_field(body, "levels", animate_options.levels, 1.0, 8.0);
    if (!levels.ok()) return levels.status();
    if (*levels != std::floor(*levels)) return invalid_argument("levels: must be an integer");
    animate_options.levels = static_cast<int>(*levels);
    animate_options.keep_frames = false;

    const FrameFiles& frames = paths.patterns.at("frames");
    const FrameFiles& outputs = paths.patterns.at("output");
    EXEMPLAR_RETURN_IF_ERROR(check_image_output(outputs.absolute.front()));
    animate::AnimationInput input;
    const std::pair<const char*, Image*> styles[] = {{"style-input", &input.style_input},
                                                     {"style-output", &input.style_output}};
    for (const auto& [field, image] : styles) {
        auto loaded = load_image(paths.at(field).string());
        if (!loaded.ok())
            return invalid_argument(std::string(field) + ": " + loaded.status().message());
        *image = std::move(*loaded);
    }
    input.frame_count = static_cast<int>(frames.absolute.size());
    input.frame = [files = frames.absolute](int t) -> Result<Image> {
        auto frame = load_image(files[static_cast<std::size_t>(t)]);
        if (!frame.ok()) return invalid_argument("frames: " + frame.status().message());
        return frame;
    };
    EXEMPLAR_RETURN_IF_ERROR(frames.check_exist("frames"));
    EXEMPLAR_RETURN_IF_ERROR(animate::validate(input, animate_options));
    return JobWork([input = std::move(input), animate_options, outputs, first = frames.first](
                       const RunContext& context, const OutputSink& wrote) mutable -> Status {
        animate_options.on_frame = [&](int t, const Image& image) -> Status {
            const auto k = static_cast<std::size_t>(t);
            EXEMPLAR_RETURN_IF_ERROR(save_image(image, outputs.absolute[k]));
            wrote(first + t, outputs.relative[k]);
            return Status::ok();
        };
        return animate::animate(input, animate_options, context).status();
    });
}

// Refuses keys of `body` that are not `kind`, the job's files or one of `known`.
Status StudioServer::Impl::check_job_keys(const json& body, const JobPaths& paths,
                                          std::initializer_list<std::string_view> known,
                                          const char* kind) {
    for (const auto& [key, value] : body.items()) {
        if (key == "kind" || paths.contains(key) ||
            std::find(known.begin(), known.end(), key) != known.end()) {
            continue;
        }
        return invalid_argument(key + ": unknown option of " + kind);
    }
    return Status::ok();
}

// A fluid-simulate job (`exemplar fluid simulate --scene plume`): the built-in plume in a
// `width` × `height` domain simulated for frames 0..last; frames first..last are written, the
// alpha mask to `alpha` and the forward motion to `motion` (patterns; .flo or .exr), each
// atomically as it comes.
Result<JobWork> StudioServer::Impl::fluid_simulate_work(const json& body, const JobPaths& paths) {
    EXEMPLAR_RETURN_IF_ERROR(check_job_keys(
        body, paths, {"scene", "width", "height", "first", "last"}, "a fluid-simulate job"));
    const std::string scene_name = body.value("scene", std::string("plume"));
    if (scene_name != "plume") {
        return invalid_argument("scene: \"" + scene_name + "\" is invalid (must be plume)");
    }
    auto width = number_field(body, "width", 256.0, 8, kMaxCanvas);
    if (!width.ok()) return width.status();
    auto height = number_field(body, "height", 256.0, 8, kMaxCanvas);
    if (!height.ok()) return height.status();
    const fluid::FluidScene scene =
        fluid::plume_scene(static_cast<int>(*width), static_cast<int>(*height));
    EXEMPLAR_RETURN_IF_ERROR(fluid::validate(scene));
    const FrameFiles& alpha = paths.patterns.at("alpha");
    const FrameFiles& motion = paths.patterns.at("motion");
    if (!check_image_output(alpha.absolute.front()).is_ok())
        return invalid_argument("alpha: must end in .png or .jpg");
    const std::string motion_type =
        std::filesystem::path(motion.relative.front()).extension().string();
    if (motion_type != ".flo" && motion_type != ".exr")
        return invalid_argument("motion: must end in .flo or .exr");
    return JobWork(
        [scene, alpha, motion](const RunContext& context, const OutputSink& wrote) -> Status {
            const int frames = alpha.first + static_cast<int>(alpha.absolute.size());
            return fluid::simulate(
                scene, frames,
                [&](int frame, const Image& mask, const Image& flow) -> Status {
                    context.report(
                        {.stage = "simulate", .fraction = static_cast<double>(frame + 1) / frames});
                    if (frame < alpha.first) return Status::ok();
                    const auto k = static_cast<std::size_t>(frame - alpha.first);
                    EXEMPLAR_RETURN_IF_ERROR(save_flow(flow, motion.absolute[k]));
                    EXEMPLAR_RETURN_IF_ERROR(save_image(mask, alpha.absolute[k]));
                    wrote(frame, alpha.relative[k]);
                    return Status::ok();
                },
                context);
        });
}

// A fluid job (LazyFluids, what `exemplar fluid` does with a still RGBA exemplar): frames
// first..last of the target alpha masks `alpha` and motion `motion` (patterns) are synthesized
// in order, each written atomically to `output` (a pattern) and read back as the next frame's
// previous output, as the command does, so the frames are its bytes. A frame before `first`
// whose output and motion exist is the first frame's previous output (a range continued).
Result<JobWork> StudioServer::Impl::fluid_work(const json& body, const JobPaths& paths) {
    fluid::FluidOptions fluid_options;
    bool resume = false;  // a job runs again with other options: it rewrites its frames
    std::string motion_layer;
    for (const auto& [key, value] : body.items()) {
        if (key == "kind" || paths.contains(key) || key == "first" || key == "last" ||
            key == "seed") {
            continue;
        }
        if (key == "usage") {
            if (value != "uniform" && value != "none")
                return invalid_argument("usage: must be uniform or none");
            fluid_options.uniform_usage = value == "uniform";
            continue;
        }
        if (key == "rotations" || key == "resume") {
            if (!value.is_boolean()) return invalid_argument(key + ": must be true or false");
            (key == "rotations" ? fluid_options.rotations : resume) = value.get<bool>();
            continue;
        }
        if (key == "motion-layer") {
            if (!value.is_string()) return invalid_argument("motion-layer: must be a string");
            motion_layer = value.get<std::string>();
            continue;
        }
        const auto set = set_table_key(fluid_options, fluid::fluid_option_specs(), key, value);
        if (!set) return invalid_argument(key + ": unknown option of a fluid job");
        EXEMPLAR_RETURN_IF_ERROR(*set);
    }
    EXEMPLAR_RETURN_IF_ERROR(read_seed(body, fluid_options.synthesis.seed));
    EXEMPLAR_RETURN_IF_ERROR(fluid::validate(fluid_options));
    // A still or a folder of frames, with its alpha apart or not, as exemplar fluid opens it;
    // every file it reads lies in the workspace.
    auto exemplar = fluid::FluidExemplar::open(
        paths.at("exemplar").string(),
        paths.contains("exemplar-alpha") ? paths.at("exemplar-alpha").string() : "");
    if (!exemplar.ok()) return invalid_argument("exemplar: " + exemplar.status().message());
    for (const std::string& file : exemplar->files()) {
        const auto inside =
            workspace.resolve(std::filesystem::relative(file, workspace.root()).generic_string());
        if (!inside.ok()) return invalid_argument("exemplar: " + inside.status().message());
    }
    const FrameFiles& alpha = paths.patterns.at("alpha");
    const FrameFiles& motion = paths.patterns.at("motion");
    const FrameFiles& outputs = paths.patterns.at("output");
    EXEMPLAR_RETURN_IF_ERROR(check_image_output(outputs.absolute.front()));
    // Every alpha mask and the motion between them exist before anything runs.
    for (std::size_t k = 0; k < alpha.absolute.size(); ++k) {
        if (!std::filesystem::is_regular_file(alpha.absolute[k]))
            return invalid_argument("alpha: " + alpha.relative[k] + ": no such file");
        if (k + 1 < alpha.absolute.size() && !std::filesystem::is_regular_file(motion.absolute[k]))
            return invalid_argument("motion: " + motion.relative[k] + ": no such file");
    }
    fluid::FluidRange range;
    range.first = alpha.first;
    range.last = alpha.first + static_cast<int>(alpha.absolute.size()) - 1;
    range.alpha_file = frame_namer(workspace, body, "alpha", alpha.first, alpha.absolute);
    range.motion_file = frame_namer(workspace, body, "motion", motion.first, motion.absolute);
    range.output_file = frame_namer(workspace, body, "output", outputs.first, outputs.absolute);
    range.resume = resume;
    range.motion_layer = motion_layer;
    return JobWork([exemplar = std::make_shared<fluid::FluidExemplar>(std::move(*exemplar)),
                    fluid_options, range,
                    outputs](const RunContext& context, const OutputSink& wrote) -> Status {
        fluid::FluidRange job_range = range;
        exemplar->use_in(job_range);
        job_range.on_frame = [&](int n, const Image&, bool) -> Status {
            wrote(n, outputs.relative[static_cast<std::size_t>(n - outputs.first)]);
            return Status::ok();
        };
        return fluid::synthesize_fluid_range(job_range, fluid_options, context);
    });
}

namespace {

// `status` with the workspace's absolute paths in its message named as the client names them
// (relative to the workspace), after `prefix`.
Status in_client_terms(const Status& status, const Workspace& workspace,
                       const std::string& prefix = "") {
    if (status.is_ok()) return status;
    std::string message = status.message();
    const std::string root = workspace.root().string() + "/";
    for (std::size_t at = message.find(root); at != std::string::npos; at = message.find(root, at))
        message.erase(at, root.size());
    return Status(status.code(), prefix + message);
}

}  // namespace

// An npr job (image-space stippling and hatching, the range driver `exemplar npr` calls,
// npr::stylize_range, without resume: a job run again redoes its frames): the frame folders
// `frames` (a pattern of `exemplar render --frames` folders) first..last styled with `pattern`
// in order, each frame continuing from the one before, with the paper layer of `paper` and the
// bidirectional loop when asked; each output is written atomically to `output` (a pattern) with
// its synthesis states beside it (OUT.state.exr, OUT.paper.state.exr, as the command writes
// them, so the command can continue the range), and a finished frame just before the range
// hands its states over, as the command does. Every buffer the range reads is checked when the
// job is posted.
Result<JobWork> StudioServer::Impl::npr_work(const json& body, const JobPaths& paths) {
    npr::NprOptions npr_options;
    for (const auto& [key, value] : body.items()) {
        if (key == "kind" || paths.contains(key) || key == "first" || key == "last" ||
            key == "seed" || key == "bidirectional") {
            continue;
        }
        if (key == "style" || key == "tone" || key == "orientation") {
            if (!value.is_string()) return invalid_argument(key + ": must be a string");
            const std::string text = value.get<std::string>();
            if (key == "style") {
                auto style = npr::parse_style(text);
                if (!style.ok()) return style.status();
                npr_options.style = *style;
            } else {
                (key == "tone" ? npr_options.tone : npr_options.orientation) = text;
            }
            continue;
        }
        if (key == "lines" || key == "tone-correction") {
            if (!value.is_boolean()) return invalid_argument(key + ": must be true or false");
            (key == "lines" ? npr_options.lines : npr_options.tone_correction) = value.get<bool>();
            continue;
        }
        const auto set = set_table_key(npr_options, npr::npr_option_specs(), key, value);
        if (!set) return invalid_argument(key + ": unknown option of an npr job");
        EXEMPLAR_RETURN_IF_ERROR(*set);
    }
    npr_options.paper = paths.contains("paper");
    for (const char* key : {"paper-grain", "erosion"}) {
        if (!npr_options.paper && body.contains(key))
            return invalid_argument(std::string(key) + ": needs paper");
    }
    EXEMPLAR_RETURN_IF_ERROR(read_seed(body, npr_options.seed));
    EXEMPLAR_RETURN_IF_ERROR(npr::validate(npr_options));
    auto bidirectional = number_field(body, "bidirectional", 0.0, 0.0, 1000.0);
    if (!bidirectional.ok()) return bidirectional.status();
    if (*bidirectional != std::floor(*bidirectional))
        return invalid_argument("bidirectional: must be an integer");
    const FrameFiles& folders = paths.patterns.at("frames");
    const FrameFiles& outputs = paths.patterns.at("output");
    EXEMPLAR_RETURN_IF_ERROR(check_image_output(outputs.absolute.front()));
    npr::NprRange range;
    range.first = folders.first;
    range.last = folders.first + static_cast<int>(folders.absolute.size()) - 1;
    range.frame_folder = frame_namer(workspace, body, "frames", folders.first, folders.absolute);
    range.output_file = frame_namer(workspace, body, "output", outputs.first, outputs.absolute);
    range.bidirectional = static_cast<int>(*bidirectional);
    range.resume = false;
    EXEMPLAR_RETURN_IF_ERROR(npr::validate(range));
    // Every frame folder and buffer the range reads is there before anything runs.
    EXEMPLAR_RETURN_IF_ERROR(
        in_client_terms(npr::check_npr_range(range, npr_options), workspace, "frames: "));
    const RunContext prepare_context(options.threads);
    std::optional<npr::Pattern> patterns[2];  // the pattern and the paper
    for (int k = 0; k < (npr_options.paper ? 2 : 1); ++k) {
        const std::string field = k == 0 ? "pattern" : "paper";
        auto image = load_image(paths.at(field).string());
        if (!image.ok()) return invalid_argument(field + ": " + image.status().message());
        auto prepared = npr::prepare_pattern(*image, npr_options, prepare_context);
        if (!prepared.ok()) return invalid_argument(field + ": " + prepared.status().message());
        patterns[k] = std::move(prepared).value();
    }
    return JobWork([pattern = std::move(*patterns[0]), paper = std::move(patterns[1]), npr_options,
                    range, outputs,
                    ws = workspace](const RunContext& context, const OutputSink& wrote) -> Status {
        npr::NprRange job_range = range;
        job_range.on_frame = [&](int n, const std::string&, const Image*) -> Status {
            wrote(n, outputs.relative[static_cast<std::size_t>(n - outputs.first)]);
            return Status::ok();
        };
        return in_client_terms(
            npr::stylize_range(pattern, paper ? &*paper : nullptr, job_range, npr_options, context),
            ws);
    });
}

void StudioServer::Impl::add_job_routes() {
    http->route("POST", "/api/jobs", [this](const Request& req, Response& res) {
        const std::string id = client_id(req, res);
        if (id.empty()) return;
        const auto body = json_body(req, res);
        if (!body) return;
        const std::string kind = body->value("kind", std::string());
        using Fields = std::vector<const char*>;
        struct Kind {
            Fields files;       ///< One path each.
            Fields file_lists;  ///< A path or a list of paths each.
            Result<JobWork> (Impl::*work)(const json&, const JobPaths&);
            Fields optional_files = {};  ///< One path each, when given.
        };
        // Frame patterns (range jobs): "frames", "output" formatted for first..last.
        using Patterns = std::vector<const char*>;
        const std::map<std::string, Patterns> patterns = {{"animate", {"frames", "output"}},
                                                          {"fluid-simulate", {"alpha", "motion"}},
                                                          {"fluid", {"alpha", "motion", "output"}},
                                                          {"npr", {"frames", "output"}},
                                                          {"noisy", noisy_patterns(*body)}};
        const std::map<std::string, Kind> kinds = {
            {"stylize", {{"style", "source", "target", "output"}, {}, &Impl::stylize_work}},
            {"noisy", {noisy_files(*body), noisy_file_lists(*body), &Impl::noisy_work}},
            {"stylit", {{"exemplar", "output"}, {"source", "target"}, &Impl::stylit_work}},
            {"animate", {{"style-input", "style-output"}, {}, &Impl::animate_work}},
            {"fluid-simulate", {{}, {}, &Impl::fluid_simulate_work}},
            {"fluid", {{"exemplar"}, {}, &Impl::fluid_work, {"exemplar-alpha"}}},
            {"npr", {{"pattern"}, {}, &Impl::npr_work, {"paper"}}}};
        const auto found = kinds.find(kind);
        if (found == kinds.end()) {
            return fail(res, 400,
                        "kind: \"" + kind +
                            "\" is invalid (must be stylize, noisy, stylit, animate, "
                            "fluid-simulate, fluid or npr)");
        }
        // Every path is checked before anything is read: a refusal is 403.
        JobPaths paths;
        const auto resolve = [&](const char* field, const std::string& name) {
            auto path = workspace.resolve(name);
            if (!path.ok()) fail(res, 403, std::string(field) + ": " + path.status().message());
            return path;
        };
        for (const Fields* fields : {&found->second.files, &found->second.optional_files}) {
            for (const char* field : *fields) {
                if (fields == &found->second.optional_files && !body->contains(field)) continue;
                auto name = text_field(*body, field);
                if (!name.ok()) return fail(res, name.status());
                auto path = resolve(field, *name);
                if (!path.ok()) return;
                paths.one[field] = *path;
            }
        }
        for (const char* field : found->second.file_lists) {
            auto names = path_list_field(*body, field);
            if (!names.ok()) return fail(res, names.status());
            for (const std::string& name : *names) {
                auto path = resolve(field, name);
                if (!path.ok()) return;
                paths.lists[field].push_back(path->string());
            }
        }
        if (const auto p = patterns.find(kind); p != patterns.end() && !p->second.empty()) {
            auto range = frame_range(*body);
            if (!range.ok()) return fail(res, range.status());
            for (const char* field : p->second) {
                auto pattern = text_field(*body, field);
                if (!pattern.ok()) return fail(res, pattern.status());
                FrameFiles& files = paths.patterns[field];
                files.first = range->first;
                for (int n = range->first; n <= range->second; ++n) {
                    auto name = video::format_frame_path(*pattern, n);
                    if (!name.ok())
                        return fail(res, 400, std::string(field) + ": " + name.status().message());
                    auto path = resolve(field, *name);
                    if (!path.ok()) return;
                    files.relative.push_back(*name);
                    files.absolute.push_back(path->string());
                }
            }
        }
        auto work = (this->*found->second.work)(*body, paths);
        if (!work.ok()) return fail(res, 400, work.status().message());
        const std::string output = body->value("output", std::string());
        // A StyLit run replaces the client's previous one (the tool runs again on every change).
        auto job = kind == "stylit" ? jobs.replace(id, kind, output, std::move(*work))
                                    : jobs.start(id, kind, output, std::move(*work));
        if (!job.ok()) return fail(res, 429, job.status().message());
        answer(res, 202, {{"id", (*job)->id}});
    });
    http->route("GET", "/api/jobs", [this](const Request&, Response& res) {
        json list = json::array();
        for (const auto& job : jobs.list()) list.push_back(json::parse(job->summary()));
        answer(res, 200, {{"jobs", list}});
    });
    http->route("POST", R"(/api/jobs/([0-9]+)/cancel)", [this](const Request& req, Response& res) {
        const auto job = jobs.find(req.matches[1]);
        if (!job) return fail(res, 404, "no such job");
        job->cancel.cancel();
        answer(res, 200, json::parse(job->summary()));
    });
    http->route("GET", R"(/api/jobs/([0-9]+)/events)", [this](const Request& req, Response& res) {
        const auto job = jobs.find(req.matches[1]);
        if (!job) return fail(res, 404, "no such job");
        res.set_header("Cache-Control", "no-store");
        res.content_type = "text/event-stream";
        // Each call waits up to 250 ms for new events, so a stream notices the end quickly.
        res.stream = [job, next = std::size_t{0}](std::string& chunk) mutable {
            std::unique_lock lock(job->mutex);
            job->changed.wait_for(lock, std::chrono::milliseconds(250),
                                  [&] { return job->events.size() > next; });
            for (; next < job->events.size(); ++next) chunk += job->events[next];
            return job->state == JobState::Running;
        };
    });
}

StudioServer::StudioServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

StudioServer::~StudioServer() {
    shutdown();
}

Result<std::unique_ptr<StudioServer>> StudioServer::create(const StudioOptions& options) {
    if (options.max_jobs_per_client < 1 || options.max_jobs_per_client > 16) {
        return invalid_argument("max-jobs: " + std::to_string(options.max_jobs_per_client) +
                                " is invalid (must be 1..16)");
    }
    if (options.max_finished_jobs < 1 || options.max_clients < 1) {
        return invalid_argument("max_finished_jobs and max_clients: must be at least 1");
    }
    if (options.port < 0 || options.port > 65535) {
        return invalid_argument("port: " + std::to_string(options.port) +
                                " is invalid (must be 0..65535)");
    }
    auto workspace = Workspace::open(options.workspace);
    if (!workspace.ok()) return workspace.status();
    auto http = plugin::load<plugin::http::Entry>(plugin::http::kPlugin);
    if (!http.ok()) return http.status();
    auto impl = std::make_unique<Impl>(options, std::move(*workspace));
    plugin::http::ServerOptions http_options;
    http_options.max_body_bytes = std::max(options.max_upload_bytes, kMaxJsonBytes);
    impl->http = (*http)->new_server(http_options);
    impl->add_routes();
    impl->port = impl->http->bind(options.bind, options.port);
    if (impl->port <= 0) {
        return io_error(options.bind + ":" + std::to_string(options.port) +
                        ": cannot listen (address in use or not available)");
    }
    return std::unique_ptr<StudioServer>(new StudioServer(std::move(impl)));
}

int StudioServer::port() const {
    return impl_->port;
}

std::string StudioServer::workspace() const {
    return impl_->workspace.root().string();
}

void StudioServer::run() {
    if (!impl_->stopping) impl_->http->listen();
}

void StudioServer::shutdown() {
    if (impl_->stopping.exchange(true)) return;
    impl_->interactive_cancel.cancel();
    impl_->cancel_paintings();
    impl_->jobs.shutdown();
    impl_->http->stop();
}

}  // namespace exemplar::studio
