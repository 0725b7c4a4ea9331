#pragma once
// The end-to-end benchmarks read real data from ../shared/data beside the repository (the
// developers' set-up; origins and licences in its SOURCES.md). It is optional: users who clone
// the repository alone do not have it, and the benchmarks say so instead of failing obscurely.
#include <cstdio>
#include <filesystem>
#include <string>

namespace exemplar::bench {

/// `relative` under ../shared/data.
inline std::string shared_data(const std::string& relative) {
    return std::string(EXEMPLAR_SHARED_DATA_DIR) + "/" + relative;
}

/// True if `path` exists; otherwise a message that the optional data is absent, and false.
inline bool shared_data_present(const std::string& path) {
    if (std::filesystem::exists(path)) return true;
    std::fprintf(stderr,
                 "%s: absent. This benchmark reads optional data from ../shared/data beside the "
                 "repository (not part of it); the test suite does not need it.\n",
                 path.c_str());
    return false;
}

}  // namespace exemplar::bench
