#include "output_files.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "exemplar/io/folders.hpp"
#include "option_help.hpp"

namespace exemplar::cli {

namespace {

namespace fs = std::filesystem;

std::string named(std::string_view flag, const std::string& path) {
    std::string text(flag);
    text.append(" ").append(path);
    return text;
}

// Largest step (in [0, 1] units) of an integer grid all values lie on: 8 for k/255, 16 for
// k/65535, 0 if some value is on neither (float data, or outside [0, 1]).
int integer_grid_bits(const Image& image) {
    // The nearest integer of a value >= 0 as floor(v + 0.5) (a cast, no libm call): it differs
    // from std::round only within an ulp of a half-integer, where both are 0.5 away.
    const auto off_grid = [](double v) {
        return std::fabs(v - static_cast<double>(static_cast<std::int64_t>(v + 0.5)));
    };
    bool on8 = true, on16 = true;
    for (float v : image.data()) {
        if (!(v >= 0.0f && v <= 1.0f)) return 0;
        on8 = on8 && off_grid(static_cast<double>(v) * 255.0) < 1e-3;
        on16 = on16 && off_grid(static_cast<double>(v) * 65535.0) < 0.02;
        if (!on8 && !on16) return 0;
    }
    return on8 ? 8 : 16;
}

// Bit depth a PNG file declares in its header (IHDR byte 24; 1, 2 and 4-bit count as 8), or 0
// for other files. The io module does not report the stored sample format.
int png_bit_depth(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char header[25] = {};
    if (!in.read(header, sizeof header)) return 0;
    if (std::string_view(header, 8) != std::string_view("\x89PNG\r\n\x1a\n", 8) ||
        std::string_view(header + 12, 4) != "IHDR") {
        return 0;
    }
    return header[24] == 16 ? 16 : 8;
}

}  // namespace

Status check_output_path(std::string_view flag, const std::string& path) {
    if (path.empty()) return invalid_argument(std::string(flag) + ": is empty");
    std::error_code ec;
    if (fs::is_directory(path, ec)) return invalid_argument(named(flag, path) + ": is a folder");
    // Missing folders are created by the write; whether they can be is checked now.
    if (const Status can = check_parent_folders(path); !can.is_ok()) {
        return Status(can.code(), std::string(flag) + " " + can.message());
    }
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) folder = ".";
    if (fs::is_directory(folder, ec) && ::access(folder.c_str(), W_OK) != 0) {
        return io_error(named(flag, path) + ": folder " + folder.string() + " is not writable");
    }
    return Status::ok();
}

Status check_output_format(std::string_view flag, const std::string& path, const Image& like,
                           const SaveOptions& options) {
    static std::atomic<unsigned> counter{0};
    Image probe(1, 1, like.channels());
    probe.set_channel_names(like.channel_names());
    std::error_code ec;
    const fs::path temp_folder = fs::temp_directory_path(ec);
    if (ec) return Status::ok();  // nowhere to probe; the real write reports any problem
    std::string probe_name = "exemplar-probe-";
    probe_name.append(std::to_string(::getpid())).append("-").append(std::to_string(counter++));
    probe_name.append(fs::path(path).extension().string());
    const std::string probe_path = (temp_folder / probe_name).string();
    const Status status = save_image(probe, probe_path, options);
    fs::remove(probe_path, ec);
    // Only the format's verdict matters here; trouble with the temporary folder does not.
    if (status.is_ok() || status.code() == ErrorCode::IoError) return Status::ok();
    std::string message = status.message();
    const std::string prefix = probe_path + ": ";
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    return Status(status.code(), named(flag, path) + ": " + message);
}

SaveOptions output_options(const Image& reference, const std::string& reference_path,
                           const std::string& path) {
    SaveOptions options;
    const std::string ext = lowercase_extension(path);
    const bool png = ext == ".png";
    const bool tiff = ext == ".tif" || ext == ".tiff";
    if (!png && !tiff) return options;
    // The finer of what the file declares and what its values need (a 16-bit PNG holding 8-bit
    // data still asks for 16 bits: the vote averages finer than its input).
    const int grid = integer_grid_bits(reference);
    const int bits = png_bit_depth(reference_path) == 16 && grid != 0 ? 16 : grid;
    if (bits == 8) {
        options.format = PixelFormat::UInt8;
    } else if (bits == 16 || png) {
        options.format = PixelFormat::UInt16;
    } else {
        options.format = PixelFormat::Float;
    }
    return options;
}

Image error_map_for_file(const Image& error, const std::string& path, SaveOptions& options) {
    const std::string ext = lowercase_extension(path);
    if (ext == ".exr" || ext == ".tif" || ext == ".tiff") {
        options.format = PixelFormat::Float;
        return error;
    }
    // Scale so that the 99th percentile of the non-zero distances maps to 1 (a few outliers
    // would otherwise leave the map black).
    std::vector<float> positive;
    for (float v : error.data()) {
        if (v > 0.0f && std::isfinite(v)) positive.push_back(v);
    }
    float scale = 1.0f;
    if (!positive.empty()) {
        const auto nth = positive.begin() + static_cast<std::ptrdiff_t>(
                                                static_cast<double>(positive.size() - 1) * 0.99);
        std::nth_element(positive.begin(), nth, positive.end());
        if (*nth > 0.0f) scale = 1.0f / *nth;
    }
    Image scaled = error;
    for (float& v : scaled.data()) v = std::min(1.0f, v * scale);
    return scaled;
}

Status check_output_paths(const SynthesisOutputs& outputs) {
    const std::vector<std::pair<const char*, const std::string*>> files = {
        {"--output", &outputs.output},
        {"--save-nnf", &outputs.save_nnf},
        {"--save-error", &outputs.save_error}};
    for (std::size_t i = 0; i < files.size(); ++i) {
        const auto& [flag, path] = files[i];
        if (path->empty()) continue;
        EXEMPLAR_RETURN_IF_ERROR(check_output_path(flag, *path));
        for (std::size_t j = 0; j < i; ++j) {
            if (!files[j].second->empty() && same_file(*files[j].second, *path)) {
                return invalid_argument(std::string(flag) + " " + *path + ": is also the " +
                                        files[j].first + " file");
            }
        }
    }
    if (!outputs.save_nnf.empty() && lowercase_extension(outputs.save_nnf) != ".exr") {
        return invalid_argument("--save-nnf " + outputs.save_nnf +
                                ": must be an .exr file (the NNF holds float source positions)");
    }
    return Status::ok();
}

Status check_output_formats(const SynthesisOutputs& outputs, const Image& reference,
                            const SaveOptions& save) {
    EXEMPLAR_RETURN_IF_ERROR(check_output_format("--output", outputs.output, reference, save));
    if (!outputs.save_error.empty()) {
        SaveOptions options;
        const Image like = error_map_for_file(Image(1, 1, 1), outputs.save_error, options);
        EXEMPLAR_RETURN_IF_ERROR(
            check_output_format("--save-error", outputs.save_error, like, options));
    }
    return Status::ok();
}

Status save_nnf_and_error(const SynthesisResult& result, const SynthesisOutputs& outputs) {
    if (!outputs.save_nnf.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(save_image(nnf_to_image(result.nnf), outputs.save_nnf,
                                            SaveOptions{PixelFormat::Float}));
    }
    if (!outputs.save_error.empty()) {
        SaveOptions options;
        const Image error = error_map_for_file(result.error, outputs.save_error, options);
        EXEMPLAR_RETURN_IF_ERROR(save_image(error, outputs.save_error, options));
    }
    return Status::ok();
}

std::string nnf_note(const SynthesisResult& result, const SynthesisOutputs& outputs) {
    if (outputs.save_nnf.empty()) return "";
    const std::string p = std::to_string(result.nnf_patch_size);
    const std::string v = std::to_string(result.vote_size);
    const std::string c =
        result.vote_coherence > 0.0f ? format_number(result.vote_coherence) : std::string();
    return "exemplar: note: " + outputs.save_nnf + " was made with patch size " + p +
           " and voted with the central " + v + "x" + v + " of each patch" +
           (result.vote_seams ? ", seams blended" : "") +
           (c.empty() ? "" : ", weighing coherence " + c) + " (apply-nnf --patch-size " + p +
           " --vote-size " + v + (result.vote_seams ? " --vote-seams" : "") +
           (c.empty() ? "" : " --vote-coherence " + c) + ")\n";
}

std::string guide_compression_note(const SynthesisResult& result, float guide_pca) {
    const SynthesisResult::GuideCompression& c = result.guide_compression;
    if (!(guide_pca > 0.0f)) return "";
    if (c.channels_after == c.channels_before) {
        return "exemplar: note: guide-pca: guides used as given (no channel could be dropped, or "
               "a guide has a weight map)\n";
    }
    std::ostringstream note;
    note.precision(4);
    note << "exemplar: note: guide-pca: " << c.channels_before << " guide channels compressed to "
         << c.channels_after << " principal components (" << 100.0 * c.explained_variance
         << "% of their weighted variance)\n";
    return note.str();
}

std::string unlabelled_levels_note(const SynthesisResult& result) {
    const std::vector<int>& levels = result.unlabelled_levels;
    if (levels.empty()) return "";
    const bool finest = std::find(levels.begin(), levels.end(), 0) != levels.end();
    std::ostringstream note;
    note << "exemplar: " << (finest ? "warning" : "note") << ": labels not enforced on "
         << levels.size() << (levels.size() == 1 ? " level" : " levels")
         << (finest ? ", the finest among them" : " (coarse levels only)")
         << ": a source segment has no whole patch there (narrower than a patch); "
            "target pixels of its label took patches of any label\n";
    return note.str();
}

bool same_file(const std::string& a, const std::string& b) {
    std::error_code ea, eb;
    const fs::path ca = fs::weakly_canonical(a, ea);
    const fs::path cb = fs::weakly_canonical(b, eb);
    if (ea || eb) return fs::path(a).lexically_normal() == fs::path(b).lexically_normal();
    return ca == cb;
}

Status finish_frame_range(std::ostream& out, std::optional<video::Mp4Writer>& mp4,
                          const std::string& mp4_path, int written, int count, bool quiet) {
    if (mp4) {
        EXEMPLAR_RETURN_IF_ERROR(mp4->finish());
        if (!quiet) out << mp4_path << '\n';
    }
    if (!quiet) {
        out << written << " frame" << (written == 1 ? "" : "s") << " written, " << count - written
            << " already done\n";
    }
    return Status::ok();
}

}  // namespace exemplar::cli
