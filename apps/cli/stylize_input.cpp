#include "stylize_input.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "exemplar/core/parallel.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/inpaint.hpp"
#include "output_files.hpp"

namespace exemplar::cli {

namespace {

std::string named(const std::string& flag, const std::string& path) {
    std::string text = flag;
    text.append(" ").append(path);
    return text;
}

// Formats that hold only 8/16-bit values in [0, 1] (no angles in radians, no large labels).
bool integer_only_format(const std::string& path) {
    const std::string ext = lowercase_extension(path);
    for (const char* e :
         {".png", ".jpg", ".jpeg", ".ppm", ".pgm", ".pnm", ".bmp", ".gif", ".webp", ".tga"}) {
        if (ext == e) return true;
    }
    return false;
}

Result<Image> load_orientation(const std::string& flag, const std::string& path) {
    if (integer_only_format(path)) {
        return invalid_argument(named(flag, path) +
                                ": an orientation field holds angles in radians and needs a float "
                                "format (EXR or float TIFF); this format stores only 0..1");
    }
    return load_image(path);
}

// Label maps of both sides as dense indices: each distinct colour (all channels) is one label,
// the same colour on both sides the same label. Any channel count and value range works: 8-bit
// PNG values (k/255 after loading) and integer EXR values alike.
Status load_labels(const StylizeJob& job, StylizeInput& loaded) {
    auto source = load_image(job.source_labels);
    if (!source.ok()) return source.status();
    auto target = load_image(job.target_labels);
    if (!target.ok()) return target.status();
    if (source->channels() != target->channels()) {
        return invalid_argument(named("--source-labels", job.source_labels) + ": has " +
                                std::to_string(source->channels()) + " channels but " +
                                named("--target-labels", job.target_labels) + " has " +
                                std::to_string(target->channels()));
    }
    if (!all_finite(*source)) {
        return invalid_argument(named("--source-labels", job.source_labels) +
                                ": contains NaN or infinity");
    }
    if (!all_finite(*target)) {
        return invalid_argument(named("--target-labels", job.target_labels) +
                                ": contains NaN or infinity");
    }
    std::map<std::vector<float>, int> ids;
    const auto index = [&](const Image& labels) {
        const int channels = labels.channels();
        Image out(labels.width(), labels.height(), 1);
        std::vector<float> key(static_cast<std::size_t>(channels));
        for (std::size_t i = 0; i < labels.pixel_count(); ++i) {
            const float* p = labels.data().data() + i * static_cast<std::size_t>(channels);
            key.assign(p, p + channels);
            auto [it, added] = ids.emplace(key, static_cast<int>(ids.size()));
            if (added) loaded.label_colours.push_back(key);
            out.data()[i] = static_cast<float>(it->second);
        }
        return out;
    };
    loaded.input.source_labels = index(*source);
    loaded.input.target_labels = index(*target);
    return Status::ok();
}

std::string describe_colour(const std::vector<float>& colour) {
    bool on8 = true;
    for (float v : colour) {
        const float k = v * 255.0f;
        on8 = on8 && v >= 0.0f && v <= 1.0f && std::fabs(k - std::round(k)) < 1e-3f;
    }
    std::string text = colour.size() == 1 ? "value " : "colour (";
    for (std::size_t c = 0; c < colour.size(); ++c) {
        char number[32];
        if (on8) {
            std::snprintf(number, sizeof number, "%d",
                          static_cast<int>(std::lround(colour[c] * 255.0f)));
        } else {
            std::snprintf(number, sizeof number, "%g", static_cast<double>(colour[c]));
        }
        if (c > 0) text.append(", ");
        text.append(number);
    }
    if (colour.size() != 1) text.append(")");
    if (on8) text.append(colour.size() == 1 ? " (of 255)" : " (of 255 each)");
    return text;
}

// "both or neither" inputs.
Status check_pair(const std::string& a_flag, const std::string& a, const std::string& b_flag,
                  const std::string& b, const char* what) {
    if (a.empty() == b.empty()) return Status::ok();
    const std::string& given = a.empty() ? b_flag : a_flag;
    const std::string& missing = a.empty() ? a_flag : b_flag;
    return invalid_argument(given + ": needs " + missing + " too (give both " + what +
                            ", or neither)");
}

// --inpaint MASK: the initial target and both masks of inpainting_input.
Status load_inpainting(const StylizeJob& job, StylizeInput& loaded) {
    const std::string name = named("--inpaint", job.inpaint);
    for (const auto& [flag, value] : {std::pair{"--init", &job.init},
                                      {"--target-mask", &job.target_mask},
                                      {"--source-mask", &job.source_mask}}) {
        if (!value->empty()) {
            return invalid_argument(name + ": sets " + flag + " itself (leave " + flag + " out)");
        }
    }
    auto mask = load_image(job.inpaint);
    if (!mask.ok()) return mask.status();
    auto known = inpainting_known(*mask, name);
    if (!known.ok()) return known.status();
    SynthesisInput& in = loaded.input;
    auto inpainting = inpainting_input(in.style, *known, name);
    if (!inpainting.ok()) return inpainting.status();
    in.initial_target = std::move(inpainting->initial_target);
    in.target_mask = std::move(inpainting->target_mask);
    in.source_mask = std::move(inpainting->source_mask);
    for (const char* what : {"initial target", "target mask", "source mask"}) {
        loaded.names.emplace_back(what, name);
    }
    return Status::ok();
}

}  // namespace

Result<std::pair<int, int>> parse_size(const std::string& text) {
    int w = 0, h = 0;
    char x = 0;
    std::istringstream in(text);
    if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || w <= 0 || h <= 0 || !in.eof()) {
        return invalid_argument("--size: '" + text + "' is invalid (must be WxH, e.g. 256x256)");
    }
    return std::pair{w, h};
}

Result<Image> load_grey(const std::string& flag, const std::string& path) {
    auto image = load_image(path);
    if (!image.ok() || image->channels() == 1) return image;
    const int alpha = find_channel(*image, "A");
    if (alpha >= 0) {
        for (std::size_t i = 0; i < image->pixel_count(); ++i) {
            if (image->data()[i * image->channels() + alpha] != 1.0f) {
                return invalid_argument(named(flag, path) +
                                        ": is partly transparent; masks and weight maps are read "
                                        "from grey values, not alpha (flatten it first)");
            }
        }
    }
    const int first = alpha == 0 ? 1 : 0;
    for (std::size_t i = 0; i < image->pixel_count(); ++i) {
        const float* p = image->data().data() + i * image->channels();
        for (int c = 0; c < image->channels(); ++c) {
            if (c != alpha && p[c] != p[first]) {
                return invalid_argument(named(flag, path) + ": has " +
                                        std::to_string(image->channels()) +
                                        " channels that differ (must be grey: 1 channel, or equal "
                                        "colour channels)");
            }
        }
    }
    return extract_channels(*image, first, 1);
}

Result<StylizeInput> load_stylize_input(const StylizeJob& job) {
    StylizeInput loaded;
    SynthesisInput& in = loaded.input;
    auto& names = loaded.names;

    // The style and the guide pairs are decoded in parallel (stylit's nine 1200x912 PNGs take
    // about 10 ms each); their errors are reported in the order of the command line.
    std::vector<const std::string*> files{&job.style};
    for (const GuideSpec& spec : job.guides) {
        files.push_back(&spec.source);
        files.push_back(&spec.target);
    }
    std::vector<Result<Image>> images(files.size(), Result<Image>(Image()));
    parallel_for(0, static_cast<int>(files.size()), job.threads.value_or(0), [&](int i) {
        const auto k = static_cast<std::size_t>(i);
        images[k] = load_image(*files[k]);
    });
    for (const Result<Image>& image : images) {
        if (!image.ok()) return image.status();
    }
    in.style = std::move(images[0]).value();
    names.emplace_back("style", named("--style", job.style));
    in.style_channel_weights = job.style_weights;
    names.emplace_back("style-weights", "--style-weights");

    // Guides, named by their files: the library's messages then say which pair is wrong.
    for (std::size_t i = 0; i < job.guides.size(); ++i) {
        const GuideSpec& spec = job.guides[i];
        GuidePair pair;
        pair.name =
            "guide " + std::to_string(i + 1) + " (" + spec.source + ", " + spec.target + ")";
        pair.source = std::move(images[1 + 2 * i]).value();
        pair.target = std::move(images[2 + 2 * i]).value();
        pair.weight = spec.weight;
        if (!spec.weight_map.empty()) {
            auto map = load_grey("--weight-map", spec.weight_map);
            if (!map.ok()) return map.status();
            pair.target_weight_map = std::move(map).value();
            names.emplace_back(
                pair.name + " weight map",
                named("--weight-map", spec.weight_map) + " (guide " + std::to_string(i + 1) + ")");
        }
        in.guides.push_back(std::move(pair));
    }

    // Masks.
    if (!job.target_mask.empty()) {
        auto mask = load_grey("--target-mask", job.target_mask);
        if (!mask.ok()) return mask.status();
        in.target_mask = std::move(mask).value();
        names.emplace_back("target mask", named("--target-mask", job.target_mask));
    }
    if (!job.source_mask.empty()) {
        auto mask = load_grey("--source-mask", job.source_mask);
        if (!mask.ok()) return mask.status();
        in.source_mask = std::move(mask).value();
        names.emplace_back("source mask", named("--source-mask", job.source_mask));
    }
    if (!job.inpaint.empty()) EXEMPLAR_RETURN_IF_ERROR(load_inpainting(job, loaded));

    // Labels and orientation fields come in pairs.
    EXEMPLAR_RETURN_IF_ERROR(check_pair("--source-labels", job.source_labels, "--target-labels",
                                        job.target_labels, "label maps"));
    if (!job.source_labels.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(load_labels(job, loaded));
        names.emplace_back("source labels", named("--source-labels", job.source_labels));
        names.emplace_back("target labels", named("--target-labels", job.target_labels));
    }
    EXEMPLAR_RETURN_IF_ERROR(check_pair("--source-orientation", job.source_orientation,
                                        "--target-orientation", job.target_orientation,
                                        "orientation fields"));
    if (!job.source_orientation.empty()) {
        auto source = load_orientation("--source-orientation", job.source_orientation);
        if (!source.ok()) return source.status();
        auto target = load_orientation("--target-orientation", job.target_orientation);
        if (!target.ok()) return target.status();
        in.source_orientation = std::move(source).value();
        in.target_orientation = std::move(target).value();
        names.emplace_back("source orientation",
                           named("--source-orientation", job.source_orientation));
        names.emplace_back("target orientation",
                           named("--target-orientation", job.target_orientation));
    }

    // Starting points.
    if (!job.init.empty()) {
        auto init = load_image(job.init);
        if (!init.ok()) return init.status();
        in.initial_target = std::move(init).value();
        names.emplace_back("initial target", named("--init", job.init));
    }
    if (!job.init_nnf.empty()) {
        auto image = load_image(job.init_nnf);
        if (!image.ok()) return image.status();
        auto nnf = nnf_from_image(*image);
        if (!nnf.ok())
            return invalid_argument(named("--init-nnf", job.init_nnf) + ": " +
                                    nnf.status().message());
        in.initial_nnf = std::move(nnf).value();
        names.emplace_back("initial nnf", named("--init-nnf", job.init_nnf));
    }

    // The target size comes from the guides or --init; --size is for unguided synthesis and
    // must agree with them if given too.
    if (!job.size.empty()) {
        auto size = parse_size(job.size);
        if (!size.ok()) return size.status();
        const auto [w, h] = *size;
        const Image* sized = !in.guides.empty()           ? &in.guides.front().target
                             : !in.initial_target.empty() ? &in.initial_target
                                                          : nullptr;
        if (sized != nullptr && (sized->width() != w || sized->height() != h)) {
            return invalid_argument(
                "--size: " + job.size + " differs from the target size " +
                std::to_string(sized->width()) + "x" + std::to_string(sized->height()) + " of " +
                (in.guides.empty() ? "--init" : "the target guides") + " (leave --size out)");
        }
        in.target_width = w;
        in.target_height = h;
    }
    return loaded;
}

std::string StylizeInput::name_files(const std::string& message) const {
    if (message.rfind("target size:", 0) == 0) {
        return "--size: the target size is unknown (give --guide pairs, --init, or --size WxH "
               "for unguided synthesis)";
    }
    // "target labels: label 3 does not occur ..." -> the colour of label 3.
    const std::string label_prefix = "target labels: label ";
    if (message.rfind(label_prefix, 0) == 0) {
        std::size_t end = label_prefix.size();
        while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) {
            ++end;
        }
        if (end > label_prefix.size()) {
            const std::size_t id =
                std::stoul(message.substr(label_prefix.size(), end - label_prefix.size()));
            if (id < label_colours.size()) {
                std::string rewritten = "target labels: ";
                rewritten.append(describe_colour(label_colours[id])).append(message.substr(end));
                return name_files(rewritten);
            }
        }
    }
    // The longest library name the message starts with ("guide 1 (...) weight map" before
    // "guide 1 (...)").
    const std::pair<std::string, std::string>* best = nullptr;
    for (const auto& entry : names) {
        const std::string prefix = entry.first + ":";
        if (message.rfind(prefix, 0) == 0 &&
            (best == nullptr || entry.first.size() > best->first.size())) {
            best = &entry;
        }
    }
    if (best == nullptr) return message;
    return best->second + message.substr(best->first.size());
}

}  // namespace exemplar::cli
