#pragma once
// The studio's sandbox (docs/studio.md, "Workspace sandbox"): every path a client names is
// relative to one folder and resolved here, and nothing outside that folder is read or written.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "exemplar/core/status.hpp"

namespace exemplar::studio {

/// Image types an upload may have, recognized by their first bytes.
enum class UploadType { Png, Jpeg };

/// The type whose signature `bytes` starts with (PNG: 89 50 4E 47 0D 0A 1A 0A; JPEG: FF D8 FF),
/// or InvalidArgument naming what was expected.
Result<UploadType> sniff_upload_type(std::string_view bytes);

/// A file of the workspace, for listings.
struct WorkspaceFile {
    std::string path;  ///< Relative, '/'-separated.
    std::uintmax_t bytes = 0;
};

/// A folder that client paths are confined to.
class Workspace {
public:
    /// The workspace at `root`, which must be an existing folder (created if missing when
    /// `create` is true). IoError names the folder.
    static Result<Workspace> open(const std::string& root, bool create = true);

    /// The canonical root.
    const std::filesystem::path& root() const { return root_; }

    /// The absolute path of `relative` inside the workspace. InvalidArgument for names refused
    /// without looking (empty, over 512 bytes, absolute, backslashes, control characters, empty,
    /// "." or ".." components, hidden components starting with '.'), and when the canonical path
    /// (symbolic links resolved) leaves the root ("... is outside the workspace"). The message
    /// names the path. The server answers every refusal with 403.
    Result<std::filesystem::path> resolve(std::string_view relative) const;

    /// The bytes of a regular file inside the workspace, at most `max_bytes`.
    Result<std::string> read(std::string_view relative, std::size_t max_bytes) const;

    /// Writes `bytes` atomically to `relative`, creating its folders inside the workspace.
    Status write(std::string_view relative, std::string_view bytes) const;

    /// Visible regular files (no hidden component), sorted, at most `limit`.
    std::vector<WorkspaceFile> list(std::size_t limit = 10000) const;

private:
    explicit Workspace(std::filesystem::path root) : root_(std::move(root)) {}
    std::filesystem::path root_;
};

}  // namespace exemplar::studio
