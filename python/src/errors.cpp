#include "errors.hpp"

namespace exemplar::python {

namespace {

struct ErrorClasses {
    PyObject* base = nullptr;
    PyObject* invalid_argument = nullptr;
    PyObject* io = nullptr;
    PyObject* unsupported = nullptr;
    PyObject* cancelled = nullptr;
    PyObject* internal = nullptr;
};

// Owned by the module (added as its attributes), alive as long as the interpreter.
ErrorClasses classes;

PyObject* make_class(py::module_& module, const char* name, const char* doc,
                     std::initializer_list<PyObject*> bases) {
    py::tuple base_tuple(bases.size());
    std::size_t i = 0;
    for (PyObject* base : bases) base_tuple[i++] = py::reinterpret_borrow<py::object>(base);
    const std::string qualified = std::string("exemplar.") + name;
    PyObject* type =
        PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base_tuple.ptr(), /*dict=*/nullptr);
    if (type == nullptr) throw py::error_already_set();
    module.add_object(name, py::reinterpret_borrow<py::object>(type));
    return type;
}

PyObject* class_of(ErrorCode code) {
    switch (code) {
        case ErrorCode::InvalidArgument: return classes.invalid_argument;
        case ErrorCode::IoError: return classes.io;
        case ErrorCode::Unsupported: return classes.unsupported;
        case ErrorCode::Cancelled: return classes.cancelled;
        case ErrorCode::Ok:
        case ErrorCode::Internal: break;
    }
    return classes.internal;
}

}  // namespace

void register_errors(py::module_& module) {
    classes.base = make_class(module, "Error", "Base class of every error exemplar raises.",
                              {PyExc_Exception});
    classes.invalid_argument = make_class(
        module, "InvalidArgumentError",
        "An option out of its range, or inputs that do not fit together (sizes, channels, "
        "dtype, shape).",
        {classes.base, PyExc_ValueError});
    classes.io = make_class(module, "IoError",
                            "A file is missing, unreadable, corrupt or could not be written.",
                            {classes.base, PyExc_OSError});
    classes.unsupported =
        make_class(module, "UnsupportedError", "A format or feature is not supported.",
                   {classes.base, PyExc_ValueError});
    classes.cancelled = make_class(
        module, "Cancelled",
        "The run was cancelled: the progress callback returned False, or the CancelToken was set.",
        {classes.base});
    classes.internal =
        make_class(module, "InternalError", "An invariant of the library was violated (a bug).",
                   {classes.base, PyExc_RuntimeError});
    py::register_exception_translator([](std::exception_ptr error) {
        try {
            if (error) std::rethrow_exception(error);
        } catch (const StatusError& e) {
            PyErr_SetString(class_of(e.status().code()), e.status().message().c_str());
        }
    });
}

}  // namespace exemplar::python
