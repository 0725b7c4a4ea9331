#include "exemplar/io/folders.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <system_error>

namespace exemplar {

namespace fs = std::filesystem;

namespace {

// Checks that `folder` exists or can be created, for `what` (the file or folder being written):
// its nearest existing ancestor must be a writable folder.
Status check_folder(const fs::path& folder, const std::string& what) {
    std::error_code ec;
    if (folder.empty() || fs::is_directory(folder, ec)) return Status::ok();
    for (fs::path p = folder; !p.empty(); p = p.parent_path()) {
        if (fs::exists(p, ec)) {
            if (!fs::is_directory(p, ec)) {
                return io_error(
                    fmt::format("{}: cannot create folder \"{}\": {} is a file, not "
                                "a folder",
                                what, folder.string(), p.string()));
            }
            if (::access(p.c_str(), W_OK) != 0) {
                return io_error(fmt::format("{}: cannot create folder \"{}\": {} is not writable",
                                            what, folder.string(), p.string()));
            }
            return Status::ok();
        }
        if (p == p.parent_path()) break;
    }
    return Status::ok();  // relative path whose first component is missing: in the working folder
}

// Creates `folder` for `what` (the file or folder being written).
Status make_folder(const fs::path& folder, const std::string& what) {
    std::error_code ec;
    if (folder.empty() || fs::is_directory(folder, ec)) return Status::ok();
    EXEMPLAR_RETURN_IF_ERROR(check_folder(folder, what));
    fs::create_directories(folder, ec);
    if (ec && !fs::is_directory(folder)) {
        return io_error(fmt::format("{}: cannot create folder \"{}\": {}", what, folder.string(),
                                    ec.message()));
    }
    return Status::ok();
}

}  // namespace

Status create_parent_folders(const std::string& path) {
    return make_folder(fs::path(path).parent_path(), path);
}

Status create_folders(const std::string& folder) {
    return make_folder(fs::path(folder), folder);
}

}  // namespace exemplar

namespace exemplar {

Status check_parent_folders(const std::string& path) {
    return check_folder(fs::path(path).parent_path(), path);
}

Status check_folders(const std::string& folder) {
    return check_folder(fs::path(folder), folder);
}

}  // namespace exemplar
