// `exemplar paint`: Brushables texture painting (docs/paint.md): strokes from a JSON or SVG file
// paint a region and its direction field on a canvas, which is filled with the exemplar's texture.

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/directions.hpp"
#include "exemplar/paint/paint.hpp"
#include "output_files.hpp"
#include "stroke_files.hpp"

namespace exemplar::cli {

namespace {

// A segmentation as labels: each pixel's colour, rounded to 8 bits per channel, as the 24-bit
// number 0xrrggbb (grey images: (v, v, v)); alpha is ignored. Stroke files name segments the
// same way (parse_label).
Image label_map(const Image& image) {
    Image out(image.width(), image.height(), 1);
    const int channels = image.channels();
    const auto byte = [](float v) { return std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f); };
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const float* p = image.data().data() + i * static_cast<std::size_t>(channels);
        const long r = byte(p[0]);
        const long g = channels >= 3 ? byte(p[1]) : r, b = channels >= 3 ? byte(p[2]) : r;
        out.data()[i] = static_cast<float>((r << 16) | (g << 8) | b);
    }
    return out;
}

}  // namespace

PaintCommand::PaintCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "paint", "Paint with an exemplar's texture along strokes (Brushables, docs/paint.md)");
    app_->footer(
        "Strokes JSON: [{\"points\": [[x, y], ...], \"width\": 40, \"comb\": false}, ...] in "
        "canvas pixels, with --source-labels also \"label\": \"#rrggbb\" (or a grey level "
        "0..255);\nSVG: every path is a painting stroke (centre line and stroke-width; with "
        "--source-labels its stroke colour is its segment).\n"
        "Example: exemplar paint --source grass.png --strokes strokes.json --width 512 --height "
        "256 -o out.png");
    app_->add_option(
            "--source", source_,
            "Exemplar: RGBA (alpha = its shape), or RGB with --source-mask or --source-labels")
        ->required();
    app_->add_option(
        "--source-mask", source_mask_,
        "Shape of the exemplar (white = inside; all white = the whole image); default alpha > 0");
    app_->add_option("--source-directions", source_directions_,
                     "Direction field of the exemplar (.exr from `exemplar directions`); default: "
                     "analysed with radius 10");
    app_->add_option("--source-labels", source_labels_,
                     "Segmentation of the exemplar into several textures, its size: each colour "
                     "is one segment; a stroke paints only with its segment (JSON \"label\": "
                     "grey level 0..255 or \"#rrggbb\"; SVG: the stroke colour)");
    app_->add_option("--strokes", strokes_, "Strokes: .json or .svg")->required();
    app_->add_option("--width", width_, "Canvas width in px (or from --canvas)");
    app_->add_option("--height", height_, "Canvas height in px (or from --canvas)");
    app_->add_option("--output,-o", output_, "Result: RGBA image (PNG, TIFF, EXR)")->required();
    app_->add_option("--canvas", canvas_, "Background to paint over (RGB or RGBA)");
    app_->add_option("--shape-weight", options_.shape_weight,
                     "Weight lambda of the Shape Hint against the colour distance (0 = off, "
                     "..1000); default 25");
    app_->add_option("--edge-extent", options_.edge_extent_px,
                     "How deep boundary effects reach into the texture, in px: the Shape Hint's "
                     "radius (1..256); default 16");
    app_->add_option("--shape-bins", options_.shape_bins,
                     "Bins on the Shape Hint's ring (4..32); default 8");
    app_->add_option("--alpha-weight", options_.alpha_weight,
                     "Weight of alpha against each colour channel (0..100); default 3");
    app_->add_option("--vote-coherence", options_.vote_coherence,
                     "Coherence range sigma_c^2 of the vote in px^2 (0 = off, ..100); default 2");
    app_->add_option("--vote-histogram", options_.vote_histogram,
                     "Colour-histogram weight of the vote: rarer exemplar colours are not "
                     "averaged away (0 = off, ..100); default 1");
    app_->add_option("--usage", usage_,
                     "Patch usage: none (the paper's EM; default) or uniform (every exemplar "
                     "patch about equally often: keeps sparse flecks; error-budget and occurrence "
                     "as in stylize)");
    app_->add_option("--patch-size", options_.patch_size,
                     "Patch width in px (odd, 3..15); default 5");
    app_->add_option("--seed", options_.seed, "Random seed; default 1");
    app_->add_option("--save-directions", save_directions_,
                     "Also write the canvas' direction field in direction-wheel colours");
    app_->add_option("--threads", threads_, "Threads (0 = all cores); the result is the same");
    app_->add_flag("--quiet,-q", quiet_, "Do not print the output paths");
}

Status PaintCommand::run(const Streams& streams) const {
    // Checks that need no file.
    paint::PaintOptions options = options_;
    auto usage = parse_usage_strategy(usage_);
    if (!usage.ok()) return invalid_argument("--" + usage.status().message());
    options.usage = usage.value();
    if (Status s = paint::validate(options); !s.is_ok())
        return invalid_argument("--" + s.message());
    if (threads_ < 0) {
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_stroke_file("--strokes", strokes_));
    EXEMPLAR_RETURN_IF_ERROR(check_canvas_size(canvas_, width_, height_));
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));
    EXEMPLAR_RETURN_IF_ERROR(check_output_format("--output", output_, Image(1, 1, 4), {}));
    if (!save_directions_.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--save-directions", save_directions_));
    }

    // Inputs.
    paint::PaintSource source;
    auto image = load_image(source_);
    if (!image.ok()) return image.status();
    source.image = std::move(image).value();
    if (source.image.channels() != 3 && source.image.channels() != 4) {
        return invalid_argument("--source " + source_ + ": has " +
                                std::to_string(source.image.channels()) +
                                " channels (must be RGB or RGBA)");
    }
    if (!source_mask_.empty()) {
        auto mask = load_image(source_mask_);
        if (!mask.ok()) return mask.status();
        if (!mask->same_size(source.image)) {
            return invalid_argument(
                "--source-mask " + source_mask_ + ": is " + std::to_string(mask->width()) + "x" +
                std::to_string(mask->height()) + " but --source is " +
                std::to_string(source.image.width()) + "x" + std::to_string(source.image.height()));
        }
        source.mask = extract_channels(*mask, 0, 1);
    }
    if (!source_directions_.empty()) {
        auto field = load_image(source_directions_);
        if (!field.ok()) return field.status();
        const int angle = find_channel(*field, "angle");
        if (angle < 0 && field->channels() != 1) {
            return invalid_argument("--source-directions " + source_directions_ +
                                    ": needs one channel \"angle\" (exemplar directions)");
        }
        if (!field->same_size(source.image)) {
            return invalid_argument("--source-directions " + source_directions_ +
                                    ": is not the size of --source");
        }
        source.directions = extract_channels(*field, std::max(angle, 0), 1);
    }
    std::set<int> segments;
    if (!source_labels_.empty()) {
        auto labels = load_image(source_labels_);
        if (!labels.ok()) return labels.status();
        if (!labels->same_size(source.image)) {
            return invalid_argument(
                "--source-labels " + source_labels_ + ": is " + std::to_string(labels->width()) +
                "x" + std::to_string(labels->height()) + " but --source is " +
                std::to_string(source.image.width()) + "x" + std::to_string(source.image.height()));
        }
        source.labels = label_map(*labels);
        for (float v : source.labels.data()) segments.insert(static_cast<int>(v));
    }
    auto canvas_file = load_canvas(canvas_, width_, height_);
    if (!canvas_file.ok()) return canvas_file.status();
    const int width = canvas_file->width, height = canvas_file->height;
    const Image& background = canvas_file->background;
    auto strokes = read_strokes("--strokes", strokes_, width, height, !source_labels_.empty());
    if (!strokes.ok()) return strokes.status();
    if (strokes->empty()) return invalid_argument("--strokes " + strokes_ + ": has no strokes");
    // The shape hint needs the exemplar's shape: its alpha, a mask, or its segments.
    if (source.image.channels() == 3 && source_mask_.empty() && source_labels_.empty()) {
        return invalid_argument("--source " + source_ +
                                ": has no alpha channel and no --source-mask or --source-labels "
                                "gives its shape (an all-white mask paints with the whole image)");
    }
    for (std::size_t i = 0; i < strokes->size() && !segments.empty(); ++i) {
        const paint::Stroke& stroke = (*strokes)[i];
        if (stroke.comb || segments.count(stroke.label) > 0) continue;
        std::string have;
        int listed = 0;
        for (int label : segments) {
            if (listed++ == 8) {
                have += ", ...";
                break;
            }
            have += (have.empty() ? "" : ", ") + label_colour(label);
        }
        return invalid_argument("--strokes " + strokes_ + ": stroke " + std::to_string(i) +
                                ": label " + label_colour(stroke.label) +
                                " has no segment in --source-labels " + source_labels_ +
                                " (its colours: " + have + ")");
    }

    // Strokes one after the other (painting, then combing refines), then the synthesis.
    paint::PaintCanvas canvas(width, height);
    for (const paint::Stroke& stroke : *strokes) {
        auto changed = canvas.add_stroke(stroke, threads_);
        if (!changed.ok()) return changed.status();
    }
    auto result = paint::paint(source, canvas, options, RunContext(threads_));
    if (!result.ok()) return result.status();
    Image out = background.empty() ? std::move(result->image)
                                   : paint::composite_over(result->image, background);

    // Outputs, each atomic.
    EXEMPLAR_RETURN_IF_ERROR(save_image(out, output_));
    if (!quiet_) streams.out << output_ << '\n';
    if (!save_directions_.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(
            save_image(paint::direction_wheel(canvas.directions()), save_directions_));
        if (!quiet_) streams.out << save_directions_ << '\n';
    }
    return Status::ok();
}

}  // namespace exemplar::cli
