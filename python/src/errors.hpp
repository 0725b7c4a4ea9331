#pragma once
// Library errors as Python exceptions. Each ErrorCode has one exception class, all subclasses of
// exemplar.Error, with the library's one-line message unchanged:
//   InvalidArgument -> InvalidArgumentError (also a ValueError)
//   IoError         -> IoError (also an OSError)
//   Unsupported     -> UnsupportedError (also a ValueError)
//   Cancelled       -> Cancelled
//   Internal        -> InternalError (also a RuntimeError)

#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

#include "exemplar/core/status.hpp"

namespace exemplar::python {

namespace py = pybind11;

/// Thrown by the bindings for a library error; translated into its Python exception.
class StatusError : public std::runtime_error {
public:
    explicit StatusError(Status status)
        : std::runtime_error(status.message()), status_(std::move(status)) {}
    const Status& status() const { return status_; }

private:
    Status status_;
};

/// Bad input found by the bindings themselves (dtype, shape, layout): InvalidArgumentError.
class InputError : public StatusError {
public:
    explicit InputError(std::string message) : StatusError(invalid_argument(std::move(message))) {}
};

/// Throws StatusError if `status` is an error.
inline void check(const Status& status) {
    if (!status.is_ok()) throw StatusError(status);
}

/// Returns the value of `result`, or throws its StatusError.
template <typename T>
T take(Result<T>&& result) {
    if (!result.ok()) throw StatusError(result.status());
    return std::move(result).value();
}

/// Creates the exception classes in `module` and translates StatusError into them.
void register_errors(py::module_& module);

}  // namespace exemplar::python
