// Middlebury `.flo` files (Baker et al. 2011, "A Database and Evaluation Methodology for
// Optical Flow", flow-code/README) and flow fields in EXR files.

#include "exemplar/io/flow_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "atomic_file.hpp"
#include "exemplar/io/image_io.hpp"

namespace exemplar {

namespace {

static_assert(std::endian::native == std::endian::little,
              ".flo files are little-endian; big-endian hosts need byte swapping here");

constexpr float kFloMagic = 202021.25f;  // the bytes "PIEH"
constexpr int kMaxSide = 65536;
constexpr std::uintmax_t kHeaderBytes = 12;

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

Status check_flow_image(const Image& flow, const std::string& path) {
    if (flow.empty() || flow.channels() != 2) {
        return invalid_argument(fmt::format(
            "{}: a flow field needs 2 channels (u, v) and a non-empty size, got {}x{} with {}",
            path, flow.width(), flow.height(), flow.channels()));
    }
    return Status::ok();
}

}  // namespace

Image as_flow(Image image) {
    if (image.channels() == 2) image.set_channel_names({"u", "v"});
    return image;
}

Result<Image> load_flo(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        return io_error(fmt::format("{}: no such file", path));
    }
    const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    if (ec || !in) return io_error(fmt::format("{}: cannot open for reading", path));

    // Header: magic, width, height.
    char header[kHeaderBytes];
    if (file_bytes < kHeaderBytes || !in.read(header, kHeaderBytes)) {
        return io_error(fmt::format("{}: truncated .flo file ({} bytes, the header alone has {})",
                                    path, file_bytes, kHeaderBytes));
    }
    float magic = 0.0f;
    std::int32_t width = 0, height = 0;
    std::memcpy(&magic, header, 4);
    std::memcpy(&width, header + 4, 4);
    std::memcpy(&height, header + 8, 4);
    if (magic != kFloMagic) {
        return io_error(
            fmt::format("{}: not a .flo file (bad magic number, expected \"PIEH\")", path));
    }
    if (width <= 0 || height <= 0 || width > kMaxSide || height > kMaxSide) {
        return io_error(fmt::format("{}: corrupt .flo header: size {}x{} (each side must be 1..{})",
                                    path, width, height, kMaxSide));
    }

    // Payload: exactly width * height (u, v) pairs.
    const std::uintmax_t expected = kHeaderBytes + static_cast<std::uintmax_t>(width) *
                                                       static_cast<std::uintmax_t>(height) * 2 *
                                                       sizeof(float);
    if (file_bytes != expected) {
        return io_error(fmt::format("{}: {} .flo file: {} bytes, but a {}x{} flow needs {}", path,
                                    file_bytes < expected ? "truncated" : "oversized", file_bytes,
                                    width, height, expected));
    }
    Image flow(width, height, 2);
    const auto payload = static_cast<std::streamsize>(flow.size() * sizeof(float));
    if (!in.read(reinterpret_cast<char*>(flow.data().data()), payload)) {
        return io_error(fmt::format("{}: read error in the flow data", path));
    }
    return as_flow(std::move(flow));
}

Status save_flo(const Image& flow, const std::string& path) {
    EXEMPLAR_RETURN_IF_ERROR(check_flow_image(flow, path));
    io_detail::TempFile temp(path);
    EXEMPLAR_RETURN_IF_ERROR(temp.status());
    {
        std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
        const std::int32_t width = flow.width(), height = flow.height();
        out.write(reinterpret_cast<const char*>(&kFloMagic), 4);
        out.write(reinterpret_cast<const char*>(&width), 4);
        out.write(reinterpret_cast<const char*>(&height), 4);
        out.write(reinterpret_cast<const char*>(flow.data().data()),
                  static_cast<std::streamsize>(flow.size() * sizeof(float)));
        out.flush();
        if (!out) return io_error(fmt::format("{}: write error", path));
    }
    return temp.commit();
}

Result<Image> load_flow(const std::string& path, const std::string& layer) {
    if (lower_extension(path) == ".flo") {
        if (!layer.empty()) {
            return invalid_argument(
                fmt::format("{}: a .flo file has no layers (asked for layer \"{}\")", path, layer));
        }
        return load_flo(path);
    }
    auto image = load_image_layer(path, layer);
    if (!image.ok()) return image.status();
    if (image->channels() != 2) {
        return io_error(
            fmt::format("{}: layer \"{}\" has {} channels; a flow field needs exactly 2 (u, v)",
                        path, layer, image->channels()));
    }
    return as_flow(std::move(image).value());
}

Status save_flow(const Image& flow, const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".flo") return save_flo(flow, path);
    if (ext != ".exr") {
        return unsupported(
            fmt::format("{}: cannot write flow as \"{}\" (use .flo or .exr)", path, ext));
    }
    EXEMPLAR_RETURN_IF_ERROR(check_flow_image(flow, path));
    SaveOptions options;
    options.format = PixelFormat::Float;
    return save_image(as_flow(flow), path, options);
}

}  // namespace exemplar
