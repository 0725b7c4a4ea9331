#include "exemplar/core/status.hpp"

#include <cstdio>
#include <cstdlib>

#include "exemplar/core/check.hpp"

namespace exemplar {

const char* to_string(ErrorCode code) {
    switch (code) {
        case ErrorCode::Ok: return "ok";
        case ErrorCode::InvalidArgument: return "invalid argument";
        case ErrorCode::IoError: return "i/o error";
        case ErrorCode::Unsupported: return "unsupported";
        case ErrorCode::Cancelled: return "cancelled";
        case ErrorCode::Internal: return "internal error";
    }
    return "unknown";
}

namespace detail {
void check_failed(const char* file, int line, const std::string& what) {
    std::fprintf(stderr, "exemplar: check failed at %s:%d: %s\n", file, line, what.c_str());
    std::abort();
}
}  // namespace detail

}  // namespace exemplar
