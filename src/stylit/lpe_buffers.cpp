// Loading the light-path buffers of a render: a list of files, or named layers of one EXR.

#include "exemplar/stylit/lpe_buffers.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "exemplar/io/image_io.hpp"

namespace exemplar {

namespace {

constexpr const char* kGuideRoles[] = {"full render", "direct diffuse", "direct specular",
                                       "indirect diffuse"};

std::string role(std::size_t index) {
    return index < std::size(kGuideRoles) ? kGuideRoles[index]
                                          : "buffer " + std::to_string(index + 1);
}

std::string join(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) {
        if (!text.empty()) text += ", ";
        text += name.empty() ? "(unnamed: R, G, B...)" : name;
    }
    return text;
}

bool is_exr(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".exr";
}

// Drops an alpha channel: coverage is not lighting, and Cycles' Combined pass carries one.
Image without_alpha(Image image) {
    if (image.channels() < 2) return image;
    const int alpha = find_channel(image, "A");
    if (alpha != image.channels() - 1) return image;
    return extract_channels(image, 0, image.channels() - 1);
}

bool layer_matches(const std::string& layer, const std::string& wanted) {
    if (layer == wanted) return true;
    if (wanted.empty() || layer.size() <= wanted.size()) return false;
    return layer.compare(layer.size() - wanted.size(), wanted.size(), wanted) == 0 &&
           layer[layer.size() - wanted.size() - 1] == '.';
}

Result<std::vector<LpeBuffer>> load_exr_layers(const std::string& path,
                                               const std::vector<std::string>& layers,
                                               const LayerPreset& preset) {
    std::vector<LpeBuffer> buffers;
    for (std::size_t i = 0; i < preset.layers.size(); ++i) {
        const std::vector<std::string>& spellings = preset.layers[i];
        std::vector<std::string> found;
        for (const std::string& wanted : spellings) {
            for (const std::string& layer : layers) {
                if (layer_matches(layer, wanted)) found.push_back(layer);
            }
            if (!found.empty()) break;
        }
        std::string wanted_text;
        for (const std::string& s : spellings) {
            if (!wanted_text.empty()) wanted_text += " or ";
            wanted_text += s.empty() ? "(unnamed)" : s;
        }
        if (found.empty()) {
            return io_error(path + ": no layer " + wanted_text + " (" + role(i) + ", preset " +
                            std::string(preset.name) + "); the file has layers: " + join(layers));
        }
        if (found.size() > 1) {
            return invalid_argument(path + ": layer " + wanted_text + " (" + role(i) +
                                    ") is ambiguous: " + join(found) + "; name one with --layers");
        }
        auto image = load_image_layer(path, found.front());
        if (!image.ok()) return image.status();
        buffers.push_back({found.front(), path + " (layer " + found.front() + ")",
                           without_alpha(std::move(image).value())});
    }
    return buffers;
}

// A folder of one file per buffer (what `exemplar render --output DIR` writes): the files named
// `<layer>.<ext>` after the preset, for the extensions `exemplar render` writes.
Result<std::vector<LpeBuffer>> load_folder(const std::string& folder, const LayerPreset& preset) {
    namespace fs = std::filesystem;
    constexpr const char* kExtensions[] = {".png", ".exr"};
    std::vector<LpeBuffer> buffers;
    for (std::size_t i = 0; i < preset.layers.size(); ++i) {
        std::vector<std::string> found, tried;
        for (const std::string& name : preset.layers[i]) {
            if (name.empty()) continue;
            for (const char* extension : kExtensions) {
                const std::string file = name + extension;
                tried.push_back(file);
                std::error_code ec;
                if (fs::is_regular_file(fs::path(folder) / file, ec)) found.push_back(file);
            }
            if (!found.empty()) break;
        }
        if (found.empty()) {
            std::string wanted;
            for (const std::string& file : tried) wanted += (wanted.empty() ? "" : " or ") + file;
            return io_error(folder + ": no file " + wanted + " (" + role(i) + ", preset " +
                            std::string(preset.name) + ")");
        }
        if (found.size() > 1) {
            return invalid_argument(folder + ": " + join(found) + " (" + role(i) +
                                    ") is ambiguous; list the files instead of the folder");
        }
        const std::string path = (fs::path(folder) / found.front()).string();
        auto image = load_image(path);
        if (!image.ok()) return image.status();
        buffers.push_back({found.front(), path, without_alpha(std::move(image).value())});
    }
    return buffers;
}

}  // namespace

const std::vector<LayerPreset>& layer_presets() {
    static const std::vector<LayerPreset> presets = {
        // `exemplar render`'s buffer names; "full" and "indirect" are the names of the first
        // version of this preset.
        {"exemplar",
         {{"fullgi", "full"},
          {"direct_diffuse"},
          {"direct_specular"},
          {"indirect_diffuse", "indirect"}}},
        {"cycles", {{"Combined", "Image"}, {"DiffDir"}, {"GlossDir"}, {"DiffInd"}}},
        {"arnold",
         {{"RGBA", "beauty", ""}, {"diffuse_direct"}, {"specular_direct"}, {"diffuse_indirect"}}},
    };
    return presets;
}

Result<LayerPreset> find_layer_preset(std::string_view name) {
    std::string known;
    for (const LayerPreset& preset : layer_presets()) {
        if (preset.name == name) return preset;
        if (!known.empty()) known += ", ";
        known += preset.name;
    }
    return invalid_argument("layer preset '" + std::string(name) + "' is unknown (use " + known +
                            ", or --layers NAME,NAME,...)");
}

Result<LayerPreset> custom_layer_preset(std::string_view comma_separated) {
    LayerPreset preset{"custom", {}};
    std::size_t start = 0;
    while (start <= comma_separated.size()) {
        const std::size_t end = std::min(comma_separated.find(',', start), comma_separated.size());
        const std::string name(comma_separated.substr(start, end - start));
        if (name.empty()) {
            return invalid_argument("--layers '" + std::string(comma_separated) +
                                    "': empty layer name (expected NAME,NAME,...)");
        }
        preset.layers.push_back({name});
        start = end + 1;
    }
    return preset;
}

Result<std::vector<LpeBuffer>> load_lpe_buffers(const std::vector<std::string>& paths,
                                                const LayerPreset& preset) {
    if (paths.empty()) return invalid_argument("no buffers given");
    std::vector<LpeBuffer> buffers;
    std::error_code ec;
    if (paths.size() == 1 && std::filesystem::is_directory(paths.front(), ec)) {
        auto loaded = load_folder(paths.front(), preset);
        if (!loaded.ok()) return loaded.status();
        buffers = std::move(loaded).value();
    } else if (paths.size() == 1 && is_exr(paths.front())) {
        auto layers = read_layer_names(paths.front());
        if (!layers.ok()) return layers.status();
        if (layers->size() > 1) {
            auto loaded = load_exr_layers(paths.front(), *layers, preset);
            if (!loaded.ok()) return loaded.status();
            buffers = std::move(loaded).value();
        }
    }
    if (buffers.empty()) {
        for (const std::string& path : paths) {
            auto image = load_image(path);
            if (!image.ok()) return image.status();
            buffers.push_back({std::filesystem::path(path).filename().string(), path,
                               without_alpha(std::move(image).value())});
        }
    }
    for (const LpeBuffer& buffer : buffers) {
        if (!buffer.image.same_size(buffers.front().image)) {
            return invalid_argument(buffer.origin + ": is " + std::to_string(buffer.image.width()) +
                                    "x" + std::to_string(buffer.image.height()) + " but " +
                                    buffers.front().origin + " is " +
                                    std::to_string(buffers.front().image.width()) + "x" +
                                    std::to_string(buffers.front().image.height()) +
                                    " (all buffers of a render must have one size)");
        }
    }
    return buffers;
}

Status check_buffer_pairs(const std::vector<LpeBuffer>& source,
                          const std::vector<LpeBuffer>& target, int exemplar_width,
                          int exemplar_height) {
    if (source.empty()) return invalid_argument("--source: no buffers");
    if (source.size() != target.size()) {
        return invalid_argument("--source has " + std::to_string(source.size()) +
                                " buffers but --target has " + std::to_string(target.size()) +
                                " (list them in the same order for both renders)");
    }
    const Image& first = source.front().image;
    if (first.width() != exemplar_width || first.height() != exemplar_height) {
        return invalid_argument(source.front().origin + ": is " + std::to_string(first.width()) +
                                "x" + std::to_string(first.height()) +
                                " but the exemplar painting is " + std::to_string(exemplar_width) +
                                "x" + std::to_string(exemplar_height) +
                                " (the painting must be aligned to the exemplar render)");
    }
    for (std::size_t i = 0; i < source.size(); ++i) {
        if (source[i].image.channels() != target[i].image.channels()) {
            return invalid_argument(source[i].origin + " has " +
                                    std::to_string(source[i].image.channels()) + " channels but " +
                                    target[i].origin + " has " +
                                    std::to_string(target[i].image.channels()));
        }
    }
    return Status::ok();
}

}  // namespace exemplar
