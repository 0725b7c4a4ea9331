#pragma once
/// \file
/// Error values returned by the library. The library never throws across its public API for
/// recoverable errors (bad input, I/O failure, cancellation) and never exits or prints; it returns
/// a `Status` or a `Result<T>` whose message names the file or parameter, the value and the valid
/// range, e.g. `patch_size: 4 is invalid (must be odd, 3..31)`.

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace exemplar {

/// Category of an error; callers (the CLI) map these to exit codes.
enum class ErrorCode {
    Ok = 0,
    InvalidArgument,  ///< A parameter is out of range or inputs are inconsistent.
    IoError,          ///< A file is missing, unreadable, corrupt or could not be written.
    Unsupported,      ///< A format or feature is not supported.
    Cancelled,        ///< The run was cancelled through its CancelToken.
    Internal,         ///< An invariant was violated (a bug).
};

/// Human-readable name of an error code ("invalid argument", ...).
const char* to_string(ErrorCode code);

/// Success, or an error code with a one-line message.
class [[nodiscard]] Status {
public:
    Status() = default;
    Status(ErrorCode code, std::string message) : code_(code), message_(std::move(message)) {}

    static Status ok() { return {}; }

    bool is_ok() const { return code_ == ErrorCode::Ok; }
    explicit operator bool() const { return is_ok(); }
    ErrorCode code() const { return code_; }
    const std::string& message() const { return message_; }

private:
    ErrorCode code_ = ErrorCode::Ok;
    std::string message_;
};

/// Shorthands for building errors.
inline Status invalid_argument(std::string message) {
    return {ErrorCode::InvalidArgument, std::move(message)};
}
inline Status io_error(std::string message) {
    return {ErrorCode::IoError, std::move(message)};
}
inline Status unsupported(std::string message) {
    return {ErrorCode::Unsupported, std::move(message)};
}
inline Status cancelled() {
    return {ErrorCode::Cancelled, "cancelled"};
}

/// A value of type T or an error Status. Access the value only when `ok()`.
template <typename T>
class [[nodiscard]] Result {
public:
    Result(T value) : value_(std::move(value)) {}          // NOLINT(google-explicit-constructor)
    Result(Status status) : status_(std::move(status)) {}  // NOLINT(google-explicit-constructor)

    bool ok() const { return value_.has_value(); }
    explicit operator bool() const { return ok(); }
    const Status& status() const { return status_; }
    T& value() & { return *value_; }
    const T& value() const& { return *value_; }
    T&& value() && { return std::move(*value_); }
    T* operator->() { return &*value_; }
    const T* operator->() const { return &*value_; }
    T& operator*() { return *value_; }
    const T& operator*() const { return *value_; }

private:
    std::optional<T> value_;
    Status status_;
};

}  // namespace exemplar

/// Propagate a non-ok Status from an expression returning Status.
#define EXEMPLAR_RETURN_IF_ERROR(expr)                          \
    do {                                                        \
        ::exemplar::Status exemplar_status_ = (expr);           \
        if (!exemplar_status_.is_ok()) return exemplar_status_; \
    } while (false)
