// Writing render buffers: one file per buffer (PNG for viewing and for the StyLit guides, EXR for
// the linear values) or one multi-layer EXR.

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "exemplar/io/image_io.hpp"
#include "exemplar/render/render.hpp"

namespace exemplar::render {

namespace {

bool is_light_buffer(const std::string& name) {
    return name == "fullgi" || name == "direct_diffuse" || name == "direct_specular" ||
           name == "indirect_diffuse" || name == "diffuse_bounces" ||
           name == "diffuse_interreflection";
}

// Buffers of float data that 8-bit files cannot hold: written as EXR even in PNG folders.
bool is_float_buffer(const std::string& name) {
    return name == "orientation" || name == "forward_flow" || name == "backward_flow";
}

// The 8-bit-file version of a buffer (see BufferFileFormat::Png).
Image for_png(const std::string& name, const Image& image) {
    if (is_light_buffer(name)) return encode_srgb(image);
    Image out = image;
    if (name == "normal") {
        for (float& v : out.data()) v = 0.5f + 0.5f * v;
    } else if (name == "depth") {
        float max_depth = 0.0f;
        for (float v : out.data()) max_depth = std::max(max_depth, v);
        if (max_depth > 0.0f) {
            for (float& v : out.data()) v /= max_depth;
        }
    } else if (name == "object_id" || name == "material_id") {
        for (float& v : out.data()) v /= 255.0f;
    }
    return out;
}

}  // namespace

Image encode_srgb(const Image& linear) {
    Image out = linear;
    for (float& v : out.data()) {
        const float c = std::clamp(v, 0.0f, 1.0f);
        v = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    }
    return out;
}

Status save_buffers_to_folder(const RenderBuffers& buffers, const std::string& folder,
                              BufferFileFormat format) {
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec)) {
        return io_error(folder + ": no such folder");
    }
    for (const auto& [name, image] : buffers.layers()) {
        const bool png = format == BufferFileFormat::Png && !is_float_buffer(name);
        const std::string path =
            (std::filesystem::path(folder) / (name + (png ? ".png" : ".exr"))).string();
        if (png) {
            EXEMPLAR_RETURN_IF_ERROR(save_image(for_png(name, *image), path));
        } else {
            EXEMPLAR_RETURN_IF_ERROR(save_image(*image, path, {PixelFormat::Float}));
        }
    }
    return Status::ok();
}

Status save_buffers_to_exr(const RenderBuffers& buffers, const std::string& path) {
    return save_exr_layers(buffers.layers(), path, {PixelFormat::Float});
}

}  // namespace exemplar::render
