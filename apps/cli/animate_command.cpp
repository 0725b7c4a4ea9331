// `exemplar animate JOB.json`: temporally coherent stylization of a frame sequence (TCIA,
// Bénard et al. 2013) with frame ranges, resume and hand-over between ranges (docs/video.md).
//
// The frames to write (the range, minus finished outputs when resuming) are solved in runs of
// consecutive frames of at most `chunk` frames. A run [a, b] is extended by the neighbouring
// frames a − 1 and b + 1 when their outputs already exist: those are loaded as full keyframes
// (the hand-over), so a range continues seamlessly from the ranges solved before it.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "animate_job.hpp"
#include "commands.hpp"
#include "exemplar/animate/animate.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"

namespace exemplar::cli {

namespace {

namespace fs = std::filesystem;

bool is_pattern(const std::string& frames) {
    return frames.find('%') != std::string::npos;
}

// A folder or a video: every frame is listed up front. Patterns are opened per run instead
// (open_run_frames), so frames outside the range may be missing.
Result<video::FrameSequence> open_frames(const std::string& frames) {
    std::error_code ec;
    if (fs::is_directory(frames, ec)) return video::FrameSequence::from_folder(frames);
    return video::FrameSequence::from_video(frames);
}

// The frames `s0`..`s1` of a pattern, the job's frames being `first`..`last`: a missing file is
// named with its frame number.
Result<video::FrameSequence> open_run_frames(const std::string& pattern, int s0, int s1, int first,
                                             int last) {
    for (int n = s0; n <= s1; ++n) {
        auto path = video::format_frame_path(pattern, n);
        if (!path.ok()) return path.status();
        std::error_code ec;
        if (!fs::is_regular_file(*path, ec)) {
            return io_error(*path + ": no such file (frame " + std::to_string(n) + " of " +
                            std::to_string(first) + ".." + std::to_string(last) + ")");
        }
    }
    return video::FrameSequence::from_pattern(pattern, s0, s1);
}

// One layer's opened inputs (the whole animation when the job has no layers).
struct Source {
    const AnimateSourceSpec* spec = nullptr;
    std::optional<video::FrameSequence> frames;
    Image style_input, style_output, style_lines;
    std::vector<animate::Keyframe> keys;  // `frame` holds the frame number
    std::string output;                   // pattern of this layer's own output (layers only)
};

// "out/%04d.png" → "out/%04d.layer1.png".
std::string layer_pattern(const std::string& output, std::size_t layer) {
    const fs::path p(output);
    return (p.parent_path() /
            (p.stem().string() + ".layer" + std::to_string(layer) + p.extension().string()))
        .string();
}

// "100-199" or "42".
Result<std::pair<int, int>> parse_range(const std::string& text) {
    int a = 0, b = 0;
    char dash = 0;
    char rest = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &a, &dash, &b, &rest) == 3 && dash == '-' && a <= b) {
        return std::pair{a, b};
    }
    if (std::sscanf(text.c_str(), "%d%c", &a, &rest) == 1) return std::pair{a, a};
    return invalid_argument("--frames: '" + text + "' is invalid (use FIRST-LAST, e.g. 100-199)");
}

// A keyframe's coverage: the mask file's channel 0, else the image's 4th channel when the style
// output has 3, else none (a full key).
Result<animate::Keyframe> load_key(const AnimateKeySpec& spec, int index, int style_channels) {
    animate::Keyframe key;
    key.frame = index;
    auto image = load_image(spec.image);
    if (!image.ok()) return image.status();
    if (image->channels() == style_channels + 1 && spec.mask.empty()) {
        key.mask = extract_channels(*image, style_channels, 1);
        key.image = extract_channels(*image, 0, style_channels);
    } else {
        key.image = std::move(image).value();
    }
    if (key.image.channels() != style_channels) {
        return invalid_argument(
            spec.image + ": keyframe has " + std::to_string(key.image.channels()) +
            " channels but the style output has " + std::to_string(style_channels));
    }
    if (!spec.mask.empty()) {
        auto mask = load_image(spec.mask);
        if (!mask.ok()) return mask.status();
        key.mask = extract_channels(*mask, 0, 1);
    }
    return key;
}

}  // namespace

AnimateCommand::AnimateCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "animate", "Stylize an animation coherently in time (TCIA, Benard et al. 2013)");
    app_->footer(
        "The job file (JSON) names the frames, motion, style pair, keyframes, weights and output;\n"
        "see docs/video.md. Example: exemplar animate examples/animate/job.json --frames 0-11");
    app_->add_option("job", job_path_, "Job file (JSON)")->required();
    app_->add_option("--frames", frames_,
                     "Frame numbers to write, FIRST-LAST (default: all); finished neighbours "
                     "are handed over as keyframes");
    app_->add_option("--output,-o", output_,
                     "Output pattern (overrides the job's), e.g. out/%04d.png");
    app_->add_option("--mp4", mp4_, "Also write the range as an MP4 (overrides the job's)");
    app_->add_option("--chunk", chunk_,
                     "Frames per solve (0 = the whole range; bounds memory and lost work)");
    app_->add_option("--threads,-j", threads_, "Threads (0 = all cores)");
    seed_flag_ = app_->add_option("--seed", seed_, "Random seed (same seed, same output)");
    app_->add_option("--quality", quality_,
                     "Search effort: fast (previews), default, best (slower); overrides the job's "
                     "\"quality\" (its explicit engine options still apply)");
    app_->add_flag("--resume,!--no-resume", resume_,
                   "Skip frames whose output exists (default on)");
    app_->add_flag("--quiet,-q", quiet_, "No progress bar, no output paths");
}

Status AnimateCommand::run(const Streams& streams) const {
    auto loaded = load_animate_job(job_path_);
    if (!loaded.ok()) return loaded.status();
    AnimateJob job = std::move(loaded).value();
    if (!output_.empty()) job.output = output_;
    if (!mp4_.empty()) job.mp4 = mp4_;
    if (chunk_ >= 0) job.chunk = chunk_;
    if (!quality_.empty()) {
        // The job's own options were checked when it was read: only the flag can be wrong here.
        if (auto quality = parse_quality(quality_); !quality.ok()) return quality.status();
        job.quality = quality_;
        EXEMPLAR_RETURN_IF_ERROR(build_synthesis_options(job, job_path_));
    }
    if (seed_flag_->count() > 0) job.options.synthesis.seed = seed_;
    if (job.output.empty()) return invalid_argument(job_path_ + ": key 'output' is missing");
    if (job.chunk == 1) return invalid_argument("--chunk: must be 0 (whole range) or >= 2");
    auto probe = video::format_frame_path(job.output, 0);
    if (!probe.ok()) return invalid_argument("output: " + probe.status().message());
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("output", *probe));
    if (!job.mp4.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("mp4", job.mp4));
        EXEMPLAR_RETURN_IF_ERROR(video::check_video_support(job.mp4));
        if (!video::mp4_writing_supported()) {
            return unsupported("mp4: this OpenCV build cannot encode MP4");
        }
    }

    // Inputs: one source, or one per layer (back to front).
    std::vector<AnimateSourceSpec> specs =
        job.layers.empty() ? std::vector<AnimateSourceSpec>{job.base} : job.layers;
    const bool layered = !job.layers.empty();
    std::vector<Source> sources(specs.size());
    std::optional<std::pair<int, int>> range;
    if (!frames_.empty()) {
        auto parsed = parse_range(frames_);
        if (!parsed.ok()) return parsed.status();
        range = *parsed;
    }
    int first = 0, last = -1, W = 0, H = 0;
    for (std::size_t i = 0; i < specs.size(); ++i) {
        Source& src = sources[i];
        src.spec = &specs[i];
        const std::string what = layered ? "layer " + std::to_string(i) + ": " : "";
        int f0 = 0, f1 = -1, probe_number = 0;
        if (is_pattern(src.spec->frames)) {
            // Only the frames a run reads must exist; the first of the range tells the size.
            if (job.first < 0 || job.last < 0) {
                return invalid_argument("frames " + src.spec->frames +
                                        ": a pattern needs \"first\" and \"last\" frame numbers");
            }
            if (job.last < job.first) {
                return invalid_argument("frames " + src.spec->frames + ": last " +
                                        std::to_string(job.last) + " is before first " +
                                        std::to_string(job.first));
            }
            f0 = job.first;
            f1 = job.last;
            probe_number = std::clamp(range ? range->first : f0, f0, f1);
            auto probe_frames =
                open_run_frames(src.spec->frames, probe_number, probe_number, f0, f1);
            if (!probe_frames.ok()) return probe_frames.status();
            src.frames.emplace(std::move(probe_frames).value());
        } else {
            auto sequence = open_frames(src.spec->frames);
            if (!sequence.ok()) return sequence.status();
            src.frames.emplace(std::move(sequence).value());
            f0 = src.frames->first_number();
            f1 = f0 + src.frames->size() - 1;
            // "first"/"last" narrow a folder or video to a part of its frames.
            if (job.first >= 0 || job.last >= 0) {
                const int a = job.first >= 0 ? job.first : f0, b = job.last >= 0 ? job.last : f1;
                if (a < f0 || b > f1 || b < a) {
                    return invalid_argument("frames " + src.spec->frames + ": first/last " +
                                            std::to_string(a) + ".." + std::to_string(b) +
                                            " is invalid (it has frames " + std::to_string(f0) +
                                            ".." + std::to_string(f1) + ")");
                }
                f0 = a;
                f1 = b;
            }
            probe_number = f0;
        }
        for (const auto& [file, image] : {std::pair{&src.spec->style_input, &src.style_input},
                                          std::pair{&src.spec->style_output, &src.style_output},
                                          std::pair{&src.spec->style_lines, &src.style_lines}}) {
            if (file->empty()) continue;
            auto loaded_image = load_image(*file);
            if (!loaded_image.ok()) return loaded_image.status();
            *image = std::move(loaded_image).value();
        }
        auto frame0 = src.frames->read(probe_number - src.frames->first_number());
        if (!frame0.ok()) return frame0.status();
        if (i == 0) {
            first = f0;
            last = f1;
            W = frame0->width();
            H = frame0->height();
        } else if (f0 != first || f1 != last || frame0->width() != W || frame0->height() != H) {
            return invalid_argument(what + src.spec->frames + ": frames " + std::to_string(f0) +
                                    ".." + std::to_string(f1) + " of " + size_str(*frame0) +
                                    " but layer 0 has " + std::to_string(first) + ".." +
                                    std::to_string(last) + " of " + std::to_string(W) + "x" +
                                    std::to_string(H));
        }
        if (frame0->channels() != src.style_input.channels()) {
            return invalid_argument(
                src.frames->frame_name(probe_number - src.frames->first_number()) + ": has " +
                std::to_string(frame0->channels()) + " channels but style input " +
                src.spec->style_input + " has " + std::to_string(src.style_input.channels()));
        }
        if (src.style_output.channels() != sources[0].style_output.channels()) {
            return invalid_argument(what + "style output " + src.spec->style_output + " has " +
                                    std::to_string(src.style_output.channels()) +
                                    " channels but layer 0's has " +
                                    std::to_string(sources[0].style_output.channels()));
        }
        for (const AnimateKeySpec& spec : src.spec->keyframes) {
            if (spec.frame < first || spec.frame > last) {
                return invalid_argument(job_path_ + ": " + what + "keyframe " +
                                        std::to_string(spec.frame) + " is outside the frames " +
                                        std::to_string(first) + ".." + std::to_string(last));
            }
            // Keys beyond the range's hand-over neighbours are never read.
            if (range && (spec.frame < range->first - 1 || spec.frame > range->second + 1)) {
                continue;
            }
            auto key = load_key(spec, spec.frame, src.style_output.channels());
            if (!key.ok()) return key.status();
            if (key->image.width() != W || key->image.height() != H) {
                return invalid_argument(spec.image + ": keyframe is " + size_str(key->image) +
                                        " but the frames are " + std::to_string(W) + "x" +
                                        std::to_string(H));
            }
            src.keys.push_back(std::move(key).value());
        }
        src.output = layered ? layer_pattern(job.output, i) : job.output;
    }
    int lo = first, hi = last;
    if (range) {
        std::tie(lo, hi) = *range;
        if (lo < first || hi > last) {
            return invalid_argument("--frames: " + frames_ + " is outside the frames " +
                                    std::to_string(first) + ".." + std::to_string(last));
        }
    }
    if (!job.mp4.empty() && (W % 2 != 0 || H % 2 != 0)) {
        return invalid_argument("mp4: the frames are " + std::to_string(W) + "x" +
                                std::to_string(H) + " but MP4 needs even sizes");
    }
    auto path_of = [](const std::string& pattern, int number) {
        return video::format_frame_path(pattern, number).value();
    };
    auto output_path = [&](int number) { return path_of(job.output, number); };
    // A frame is finished when its output (and, with layers, every layer's) exists.
    auto exists = [&](int number) {
        std::error_code ec;
        if (!fs::exists(output_path(number), ec)) return false;
        for (const Source& src : sources) {
            if (layered && !fs::exists(path_of(src.output, number), ec)) return false;
        }
        return true;
    };
    auto done = [&](int number) { return resume_ && exists(number); };
    // A neighbour's output is handed over when it is outside the range, or (inside it) when it
    // is finished: resumed, or written by this invocation (never a stale one with --no-resume).
    std::vector<char> written(static_cast<std::size_t>(last - first + 1), 0);
    auto handed_over = [&](int number) {
        if (number < first || number > last || !exists(number)) return false;
        return resume_ || number < lo || number > hi ||
               written[static_cast<std::size_t>(number - first)] != 0;
    };

    // Runs of frames to solve.
    std::vector<std::pair<int, int>> runs;
    for (int n = lo; n <= hi; ++n) {
        if (done(n)) continue;
        if (!runs.empty() && runs.back().second == n - 1 &&
            (job.chunk == 0 || n - runs.back().first < job.chunk)) {
            runs.back().second = n;
        } else {
            runs.emplace_back(n, n);
        }
    }
    int todo = 0;
    for (const auto& [a, b] : runs) todo += b - a + 1;
    if (todo == 0 && !quiet_) streams.err << "exemplar animate: every frame of the range exists\n";

    ProgressBar bar(streams.err, "animate", !quiet_ && streams.err_is_terminal);
    int solved = 0;
    for (const auto& [a, b] : runs) {
        // Hand-over: finished neighbours become full keyframes (each layer its own output).
        // Runs are solved in order, so the run before this one has been written already.
        const bool before = handed_over(a - 1);
        const bool after = handed_over(b + 1);
        const int s0 = before ? a - 1 : a, s1 = after ? b + 1 : b;
        std::vector<animate::Layer> layers;
        for (Source& src : sources) {
            if (is_pattern(src.spec->frames)) {
                // A pattern reads only this run's frames (and needs only those to exist).
                auto run_frames = open_run_frames(src.spec->frames, s0, s1, first, last);
                if (!run_frames.ok()) return run_frames.status();
                src.frames.emplace(std::move(run_frames).value());
            }
            const AnimateSourceSpec& spec = *src.spec;
            animate::AnimationInput in;
            in.style_input = src.style_input;
            in.style_output = src.style_output;
            in.frame_count = s1 - s0 + 1;
            // Sequence index of the run's first frame.
            const int index0 = s0 - src.frames->first_number();
            video::FrameSequence& frames = *src.frames;
            in.frame = [&frames, index0, W, H](int t) -> Result<Image> {
                auto f = frames.read(index0 + t);
                if (f.ok() && (f->width() != W || f->height() != H)) {
                    return invalid_argument(frames.frame_name(index0 + t) + ": is " + size_str(*f) +
                                            " but the first frame is " + std::to_string(W) + "x" +
                                            std::to_string(H));
                }
                return f;
            };
            in.style_lines = src.style_lines;
            if (!spec.lines.empty()) {
                in.lines = [&spec, s0](int t) -> Result<Image> {
                    auto file = video::format_frame_path(spec.lines, s0 + t);
                    if (!file.ok()) return invalid_argument("lines: " + file.status().message());
                    return load_image(*file);
                };
            }
            if (!spec.estimate_flow) {
                in.motion = [&spec, s0, W, H](int t) -> Result<video::FlowPair> {
                    video::FlowPair pair;
                    const std::pair<const std::string*, int> files[] = {
                        {&spec.forward_flow, s0 + t}, {&spec.backward_flow, s0 + t + 1}};
                    const std::string* flow_layers[] = {&spec.forward_flow_layer,
                                                        &spec.backward_flow_layer};
                    for (int k = 0; k < 2; ++k) {
                        auto file = video::format_frame_path(*files[k].first, files[k].second);
                        if (!file.ok()) {
                            return invalid_argument("flows: " + file.status().message());
                        }
                        auto flow = load_flow(*file, *flow_layers[k]);
                        if (!flow.ok()) return flow.status();
                        if (flow->width() != W || flow->height() != H) {
                            return invalid_argument(*file + ": flow is " + size_str(*flow) +
                                                    " but the frames are " + std::to_string(W) +
                                                    "x" + std::to_string(H));
                        }
                        (k == 0 ? pair.forward : pair.backward) = std::move(flow).value();
                    }
                    return pair;
                };
            }
            for (const animate::Keyframe& k : src.keys) {
                if (k.frame < s0 || k.frame > s1) continue;
                if ((before && k.frame == s0) || (after && k.frame == s1)) continue;
                animate::Keyframe local = k;
                local.frame -= s0;
                in.keyframes.push_back(std::move(local));
            }
            for (int n : {before ? s0 : -1, after ? s1 : -1}) {
                if (n < 0) continue;
                auto handed = load_image(path_of(src.output, n));
                if (!handed.ok()) return handed.status();
                if (handed->channels() > src.style_output.channels()) {
                    handed = extract_channels(*handed, 0, src.style_output.channels());
                }
                in.keyframes.push_back({n - s0, std::move(handed).value(), {}});
            }
            animate::Layer layer{std::move(in), {}};
            if (!spec.coverage.empty()) {
                layer.coverage = [&spec, s0](int t) -> Result<Image> {
                    auto file = video::format_frame_path(spec.coverage, s0 + t);
                    if (!file.ok()) return invalid_argument("coverage: " + file.status().message());
                    auto c = load_image(*file);
                    if (!c.ok()) return c.status();
                    return extract_channels(*c, 0, 1);
                };
            } else {
                layer.coverage = [W, H](int) -> Result<Image> { return Image(W, H, 1, 1.0f); };
            }
            layers.push_back(std::move(layer));
        }

        animate::AnimateOptions options = job.options;
        options.keep_frames = false;
        auto write_frame = [&, s0, a, b](int t, const Image& image,
                                         const std::string& pattern) -> Status {
            const int n = s0 + t;
            if (n < a || n > b) return Status::ok();        // a hand-over frame: already written
            return save_image(image, path_of(pattern, n));  // atomic
        };
        RunContext context(threads_);
        const int run_frames = b - a + 1;
        context.progress = [&, a, b, run_frames](const ProgressEvent& e) {
            char detail[96];
            std::snprintf(detail, sizeof detail, "frames %d-%d  %s  level %d/%d  frame %d/%d", a, b,
                          std::string(e.stage).c_str(), e.level + 1, e.levels, e.iteration + 1,
                          e.iterations);
            bar.update((solved + e.fraction * run_frames) / std::max(1, todo), detail);
        };
        Status status;
        if (!layered) {
            options.on_frame = [&](int t, const Image& image) -> Status {
                EXEMPLAR_RETURN_IF_ERROR(write_frame(t, image, job.output));
                if (s0 + t >= a && s0 + t <= b)
                    written[static_cast<std::size_t>(s0 + t - first)] = 1;
                return Status::ok();
            };
            auto result = animate::animate(layers.front().input, options, context);
            status = result.status();
        } else {
            auto result = animate::animate_layers(layers, options, context);
            status = result.status();
            // Every layer's output first, the composite last: the composite marks the frame done.
            for (int t = 0; status.is_ok() && t < s1 - s0 + 1; ++t) {
                for (std::size_t l = 0; status.is_ok() && l < sources.size(); ++l) {
                    status = write_frame(t, result->layers[l][static_cast<std::size_t>(t)],
                                         sources[l].output);
                }
                if (status.is_ok()) {
                    status =
                        write_frame(t, result->frames[static_cast<std::size_t>(t)], job.output);
                }
                if (status.is_ok() && s0 + t >= a && s0 + t <= b) {
                    written[static_cast<std::size_t>(s0 + t - first)] = 1;
                }
            }
        }
        if (!status.is_ok()) {
            bar.finish();
            return status;
        }
        solved += run_frames;
    }
    bar.finish();
    if (!quiet_ && todo > 0) {
        streams.out << job.output << " (" << todo << " frame" << (todo == 1 ? "" : "s") << ")\n";
    }

    if (!job.mp4.empty()) {
        auto writer = video::Mp4Writer::open(job.mp4, W, H, job.fps);
        if (!writer.ok()) return writer.status();
        for (int n = lo; n <= hi; ++n) {
            auto image = load_image(output_path(n));
            if (!image.ok()) return image.status();
            EXEMPLAR_RETURN_IF_ERROR(writer->write(*image));
        }
        EXEMPLAR_RETURN_IF_ERROR(writer->finish());
        if (!quiet_) streams.out << job.mp4 << '\n';
    }
    return Status::ok();
}

}  // namespace exemplar::cli
