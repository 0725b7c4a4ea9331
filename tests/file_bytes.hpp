#pragma once
// Test helper shared by every test area: a file's whole content, for byte-for-byte comparisons
// of what two runs wrote.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace exemplar::testing {

/// The bytes of `path` ("" when it cannot be read).
inline std::string file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace exemplar::testing
