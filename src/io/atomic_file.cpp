#include "atomic_file.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "exemplar/core/rng.hpp"
#include "exemplar/io/atomic_write.hpp"
#include "exemplar/io/folders.hpp"

namespace exemplar::io_detail {

namespace fs = std::filesystem;

namespace {

// Six characters that differ between calls and processes. Uniqueness is enforced by the
// exclusive open, so this only needs to make collisions unlikely.
std::string random_suffix() {
    static std::atomic<std::uint64_t> counter{0};
    const auto now = static_cast<std::uint64_t>(
        std::chrono::high_resolution_clock::now().time_since_epoch().count());
    std::uint64_t bits = hash_keys(now, counter.fetch_add(1, std::memory_order_relaxed),
                                   reinterpret_cast<std::uintptr_t>(&counter));
    static constexpr char kAlphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    std::string suffix(6, 'x');
    for (char& ch : suffix) {
        ch = kAlphabet[bits % 36];
        bits /= 36;
    }
    return suffix;
}

}  // namespace

TempFile::TempFile(std::string destination) : destination_(std::move(destination)) {
    const fs::path dest(destination_);
    const fs::path folder = dest.parent_path();
    status_ = create_parent_folders(destination_);
    if (!status_.is_ok()) return;
    int last_errno = 0;
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name(1, '.');
        name.append(dest.stem().string()).append(".tmp-").append(random_suffix());
        name.append(dest.extension().string());
        const std::string candidate = (folder / name).string();
        // "x": fail if the file exists, so two writers never share a temporary file.
        if (std::FILE* file = std::fopen(candidate.c_str(), "wbx")) {
            std::fclose(file);
            path_ = candidate;
            return;
        }
        last_errno = errno;
        if (last_errno != EEXIST) break;
    }
    status_ = io_error(fmt::format("{}: cannot write: {}", destination_,
                                   std::generic_category().message(last_errno)));
}

TempFile::~TempFile() {
    if (path_.empty()) return;
    std::error_code ec;
    fs::remove(path_, ec);  // best effort: nothing useful can be done on failure here
}

Status TempFile::commit() {
    if (!status_.is_ok()) return status_;
    std::error_code ec;
    fs::rename(path_, destination_, ec);
    if (ec) {
        return io_error(fmt::format("{}: cannot replace the file: {}", destination_, ec.message()));
    }
    path_.clear();
    return Status::ok();
}

}  // namespace exemplar::io_detail

namespace exemplar {

Status write_file_atomically(std::string_view bytes, const std::string& path) {
    io_detail::TempFile temp(path);
    EXEMPLAR_RETURN_IF_ERROR(temp.status());
    {
        std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        out.close();
        if (!out) return io_error(path + ": cannot write (disk full or not writable)");
    }
    return temp.commit();
}

}  // namespace exemplar
