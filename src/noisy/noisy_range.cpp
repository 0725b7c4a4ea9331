// Color Me Noisy over a range of frames on files (noisy_range.hpp): the per-frame loop of
// `exemplar noisy` and the studio's noisy job.

#include "exemplar/noisy/noisy_range.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/parallel.hpp"

namespace exemplar::noisy {

namespace {

// The first channel of `image`: a grey map saved as RGB(A) gives its grey.
Image first_channel(Image image) {
    return image.channels() == 1 ? std::move(image) : extract_channels(image, 0, 1);
}

// A map's file for frame n (`per_frame`) or the range's one file, loaded by `load`.
template <class Load>
Result<Image> load_input(const RangeInput& input, int n, std::string& name, Load&& load) {
    auto path = input.file(n);
    if (!path.ok()) return path.status();
    name = *path;
    return load(*path);
}

// A map on the frame's grid: `map_name` is W x H like the reference `frame_name`.
Status check_map_size(const Image& map, const std::string& map_name, const Image& reference,
                      const std::string& frame_name) {
    if (map.empty() || map.same_size(reference)) return Status::ok();
    return invalid_argument(map_name + ": is " + std::to_string(map.width()) + "x" +
                            std::to_string(map.height()) + " but " + frame_name + " is " +
                            std::to_string(reference.width()) + "x" +
                            std::to_string(reference.height()));
}

}  // namespace

Status check_orientation_file(const std::string& path) {
    const std::string ext = lowercase_extension(path);
    if (ext == ".exr" || ext == ".tif" || ext == ".tiff") return Status::ok();
    return invalid_argument(path +
                            ": an orientation field holds angles in radians and needs a float "
                            "format (EXR or float TIFF)");
}

Result<Image> load_orientation_field(const std::string& path) {
    EXEMPLAR_RETURN_IF_ERROR(check_orientation_file(path));
    auto image = load_image(path);
    if (!image.ok()) return image.status();
    return first_channel(std::move(*image));
}

Result<Image> load_noise_map(const std::string& path) {
    auto map = load_image(path);
    if (!map.ok()) return map.status();
    return first_channel(std::move(*map));
}

Result<Image> load_source_map(const std::string& path, std::size_t sources) {
    auto map = load_noise_map(path);
    if (!map.ok()) return map;
    for (float& v : map->data()) v = std::round(v * 255.0f);
    const Status checked = check_source_map(*map, sources);
    if (!checked.is_ok()) return Status(checked.code(), path + ": " + checked.message());
    return map;
}

Status synthesize_range(std::span<const NoisySource> sources, const NoisyRange& range,
                        const NoisyOptions& options, const RunContext& context) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (range.last < range.first) {
        return invalid_argument("last: " + std::to_string(range.last) + " is before first " +
                                std::to_string(range.first));
    }
    if (sources.empty()) return invalid_argument("sources: none given");
    if (!range.reference || !range.reference_name || !range.output_file) {
        return invalid_argument("the range needs reference frames, their names and output files");
    }

    // The inputs given as one file for the whole range, read once.
    const auto load_noise = [](const std::string& path) { return load_noise_map(path); };
    const auto load_sources = [&](const std::string& path) {
        return load_source_map(path, sources.size());
    };
    const auto load_angles = [](const std::string& path) { return load_orientation_field(path); };
    Image fixed_noise, fixed_sources, fixed_orientation;
    std::string noise_name, sources_name, orientation_name;
    const auto fixed = [&](const RangeInput& input, Image& image, std::string& name,
                           auto&& load) -> Status {
        if (!input.file || input.per_frame) return Status::ok();
        auto loaded = load_input(input, range.first, name, load);
        if (!loaded.ok()) return loaded.status();
        image = std::move(*loaded);
        return Status::ok();
    };
    EXEMPLAR_RETURN_IF_ERROR(
        fixed(range.orientation, fixed_orientation, orientation_name, load_angles));
    EXEMPLAR_RETURN_IF_ERROR(fixed(range.noise_map, fixed_noise, noise_name, load_noise));
    EXEMPLAR_RETURN_IF_ERROR(fixed(range.source_map, fixed_sources, sources_name, load_sources));

    // The frames to make.
    std::vector<int> todo;
    std::vector<std::string> outputs;
    for (int n = range.first; n <= range.last; ++n) {
        auto path = range.output_file(n);
        if (!path.ok()) return path.status();
        std::error_code ec;
        if (range.resume && std::filesystem::exists(*path, ec)) continue;
        todo.push_back(n);
        outputs.push_back(*path);
    }

    // Reads frame n and its maps; the size of the first frame read is the range's.
    int width = 0, height = 0;
    std::string first_name;
    const auto read_frame = [&](int n) -> Result<NoisyFrame> {
        auto image = range.reference(n);
        if (!image.ok()) return image.status();
        const std::string name = range.reference_name(n);
        if (width == 0) {
            width = image->width();
            height = image->height();
            first_name = name;
        } else if (image->width() != width || image->height() != height) {
            return invalid_argument(name + ": is " + std::to_string(image->width()) + "x" +
                                    std::to_string(image->height()) + " but " + first_name +
                                    " is " + std::to_string(width) + "x" + std::to_string(height));
        }
        NoisyFrame frame{std::move(*image), fixed_noise, fixed_orientation, fixed_sources};
        // A per-frame input's file of this frame into `target` (`fixed_name`: the range's one
        // file); a map must have the frame's size.
        const auto frame_input = [&](const RangeInput& input, const std::string& fixed_name,
                                     auto&& load, Image& target, bool map) -> Status {
            std::string file = fixed_name;
            if (input.file && input.per_frame) {
                auto loaded = load_input(input, n, file, load);
                if (!loaded.ok()) return loaded.status();
                target = std::move(*loaded);
            }
            return map ? check_map_size(target, file, frame.reference, name) : Status::ok();
        };
        EXEMPLAR_RETURN_IF_ERROR(frame_input(range.orientation, orientation_name, load_angles,
                                             frame.orientation, false));
        EXEMPLAR_RETURN_IF_ERROR(
            frame_input(range.noise_map, noise_name, load_noise, frame.noise_map, true));
        EXEMPLAR_RETURN_IF_ERROR(
            frame_input(range.source_map, sources_name, load_sources, frame.source_map, true));
        return frame;
    };

    // Batches of frames in parallel (one thread each), or one frame with all threads.
    const int threads = resolve_threads(context.threads);
    const std::size_t batch =
        static_cast<int>(todo.size()) >= threads ? static_cast<std::size_t>(threads) : 1;
    const double count = static_cast<double>(todo.size());
    for (std::size_t start = 0; start < todo.size(); start += batch) {
        if (context.cancelled()) return cancelled();
        const std::size_t end = std::min(todo.size(), start + batch);
        std::vector<NoisyFrame> inputs;
        for (std::size_t i = start; i < end; ++i) {
            auto frame = read_frame(todo[i]);
            if (!frame.ok()) return frame.status();
            inputs.push_back(std::move(*frame));
        }
        std::vector<Status> statuses(inputs.size());
        RunContext frame_context = context.part(static_cast<double>(start), 1.0, count);
        if (batch > 1) {  // one thread per frame; the batch reports its progress at its end
            frame_context.threads = 1;
            frame_context.progress = nullptr;
        }
        parallel_for(0, static_cast<int>(inputs.size()), batch > 1 ? threads : 1, [&](int i) {
            const auto k = static_cast<std::size_t>(i);
            const int n = todo[start + k];
            auto image = synthesize_frame(sources, inputs[k], options, n, frame_context);
            if (!image.ok()) {
                statuses[k] = image.status().code() == ErrorCode::Cancelled
                                  ? image.status()
                                  : Status(image.status().code(), range.reference_name(n) + ": " +
                                                                      image.status().message());
                return;
            }
            statuses[k] = save_image(*image, outputs[start + k], range.save);
        });
        // The frames written are reported even when another of the batch failed.
        Status first_error;
        for (std::size_t k = 0; k < statuses.size(); ++k) {
            if (!statuses[k].is_ok()) {
                if (first_error.is_ok()) first_error = statuses[k];
                continue;
            }
            if (range.on_frame) {
                EXEMPLAR_RETURN_IF_ERROR(range.on_frame(todo[start + k], outputs[start + k]));
            }
        }
        EXEMPLAR_RETURN_IF_ERROR(first_error);
        if (batch > 1) {
            context.report({.stage = "frame", .fraction = static_cast<double>(end) / count});
        }
    }
    return Status::ok();
}

}  // namespace exemplar::noisy
