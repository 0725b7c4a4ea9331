#include "workspace.hpp"

#include <algorithm>
#include <fstream>
#include <system_error>

#include "exemplar/io/atomic_write.hpp"

namespace exemplar::studio {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxPathBytes = 512;

// The client's name for error messages: quoted, cut, control characters shown as '?'.
std::string quoted(std::string_view name) {
    std::string out = "\"";
    for (char c : name.substr(0, 80)) out += static_cast<unsigned char>(c) < 0x20 ? '?' : c;
    if (name.size() > 80) out += "...";
    return out + "\"";
}

Status refuse(std::string_view name, const std::string& why) {
    return invalid_argument(quoted(name) + ": " + why);
}

// Is `path` equal to `root` or below it, component by component (both canonical)?
bool within(const fs::path& path, const fs::path& root) {
    auto p = path.begin();
    for (auto r = root.begin(); r != root.end(); ++r, ++p) {
        if (p == path.end() || *p != *r) return false;
    }
    return true;
}

}  // namespace

Result<UploadType> sniff_upload_type(std::string_view bytes) {
    static constexpr std::string_view kPng("\x89PNG\r\n\x1a\n", 8);
    static constexpr std::string_view kJpeg("\xff\xd8\xff", 3);
    if (bytes.starts_with(kPng)) return UploadType::Png;
    if (bytes.starts_with(kJpeg)) return UploadType::Jpeg;
    return invalid_argument("is not a PNG or JPEG file (by its first bytes)");
}

Result<Workspace> Workspace::open(const std::string& root, bool create) {
    std::error_code ec;
    if (create) fs::create_directories(root, ec);
    if (!fs::is_directory(root, ec)) return io_error(root + ": workspace is not a folder");
    fs::path canonical = fs::canonical(root, ec);
    if (ec) return io_error(root + ": " + ec.message());
    return Workspace(std::move(canonical));
}

Result<fs::path> Workspace::resolve(std::string_view relative) const {
    // Refused by name, before the file system is asked anything.
    if (relative.empty()) return refuse(relative, "empty path");
    if (relative.size() > kMaxPathBytes) return refuse(relative, "path longer than 512 bytes");
    if (relative.front() == '/') return refuse(relative, "absolute paths are refused");
    for (char c : relative) {
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
            return refuse(relative, "control characters are refused");
        }
        if (c == '\\') return refuse(relative, "backslashes are refused");
    }
    std::size_t start = 0;
    while (start <= relative.size()) {
        const std::size_t end = std::min(relative.find('/', start), relative.size());
        const std::string_view part = relative.substr(start, end - start);
        if (part.empty()) return refuse(relative, "empty path component");
        if (part == "..") return refuse(relative, "\"..\" is refused");
        if (part.front() == '.') return refuse(relative, "hidden names (leading '.') are refused");
        start = end + 1;
    }
    // Symbolic links of the existing part resolved: the result must still be inside.
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(root_ / fs::path(relative), ec);
    if (ec) return refuse(relative, ec.message());
    if (!within(canonical, root_) || canonical == root_) {
        return refuse(relative, "is outside the workspace");
    }
    return canonical;
}

Result<std::string> Workspace::read(std::string_view relative, std::size_t max_bytes) const {
    auto path = resolve(relative);
    if (!path.ok()) return path.status();
    std::error_code ec;
    if (!fs::is_regular_file(*path, ec)) return io_error(quoted(relative) + ": no such file");
    const std::uintmax_t size = fs::file_size(*path, ec);
    if (ec) return io_error(quoted(relative) + ": " + ec.message());
    if (size > max_bytes) return io_error(quoted(relative) + ": too large to read");
    std::string bytes(static_cast<std::size_t>(size), '\0');
    std::ifstream in(*path, std::ios::binary);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!in) return io_error(quoted(relative) + ": cannot read");
    return bytes;
}

Status Workspace::write(std::string_view relative, std::string_view bytes) const {
    auto path = resolve(relative);
    if (!path.ok()) return path.status();
    return write_file_atomically(bytes, path->string());
}

std::vector<WorkspaceFile> Workspace::list(std::size_t limit) const {
    std::vector<WorkspaceFile> files;
    std::error_code ec;
    auto it = fs::recursive_directory_iterator(root_, ec);
    for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (!name.empty() && name.front() == '.') {
            if (it->is_directory(ec)) it.disable_recursion_pending();
            continue;
        }
        if (!it->is_regular_file(ec) || it->is_symlink(ec)) continue;
        files.push_back({fs::relative(it->path(), root_, ec).generic_string(), it->file_size(ec)});
        if (files.size() >= limit) break;
    }
    std::sort(files.begin(), files.end(),
              [](const WorkspaceFile& a, const WorkspaceFile& b) { return a.path < b.path; });
    return files;
}

}  // namespace exemplar::studio
