#pragma once
// Atomic replacement of files: write to a temporary file in the destination's folder, then
// rename it onto the destination. A rename within one folder is atomic on POSIX file systems,
// so readers see either the old file or the complete new one, never a half-written file.

#include <string>

#include "exemplar/core/status.hpp"

namespace exemplar::io_detail {

/// A new, empty temporary file next to `destination`, named ".<stem>.tmp-XXXXXX<extension>" so
/// that it is hidden and keeps the extension writers use to choose the format (for "out.png":
/// ".out.tmp-k3x9q2.png"). It is removed when the object is destroyed unless `commit()` moved it
/// onto the destination.
class TempFile {
public:
    /// Creates the file exclusively; on failure `status()` names the destination and the reason.
    explicit TempFile(std::string destination);
    ~TempFile();
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    const Status& status() const { return status_; }
    const std::string& path() const { return path_; }

    /// Renames the temporary file onto the destination, replacing it.
    Status commit();

private:
    std::string destination_;
    std::string path_;  ///< Empty if creation failed or after a successful commit.
    Status status_;
};

}  // namespace exemplar::io_detail
