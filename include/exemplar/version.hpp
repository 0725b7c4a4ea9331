#pragma once
/// \file
/// The library's version, for programs that link it (the CMake package `exemplar` and the
/// pkg-config module `exemplar` carry the same number).

#include <string_view>

namespace exemplar {

/// "MAJOR.MINOR.PATCH" of the linked library.
std::string_view version();

}  // namespace exemplar
