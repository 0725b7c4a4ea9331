#pragma once
// One library call from Python: the GIL is released while it works; progress events come back
// to a Python callback (the GIL re-acquired for it); Ctrl-C, a callback returning False or
// raising, or a CancelToken set from another thread cancel the call through the library's
// CancelToken.

#include <pybind11/pybind11.h>

#include <optional>
#include <utility>

#include "errors.hpp"
#include "exemplar/core/run_context.hpp"

namespace exemplar::python {

namespace py = pybind11;

/// A CancelToken Python code can hold and set from any thread (exemplar.CancelToken).
struct PyCancelToken {
    CancelToken token;
};

/// The `threads`, `progress` and `cancel` keywords of a call, taken out of its keywords before
/// reject_unknown; the PythonRun is made from them once the inputs are converted.
struct RunKeywords {
    py::object threads, progress, cancel;
};

/// Pops `threads`, `progress` and `cancel` (None where not given).
RunKeywords pop_run_keywords(py::dict& kwargs);

/// The RunContext of one call, built from the `threads`, `progress` and `cancel` keywords.
class PythonRun {
public:
    /// `progress`: None or a callable taking an exemplar.Progress; `cancel`: None or an
    /// exemplar.CancelToken; `threads` >= 0 (0 = all cores).
    PythonRun(int threads, py::object progress, py::object cancel);
    /// The same from the popped keywords (threads through threads_keyword).
    explicit PythonRun(const RunKeywords& keywords);
    PythonRun(const PythonRun&) = delete;
    PythonRun& operator=(const PythonRun&) = delete;

    const RunContext& context() const { return context_; }

    /// Runs `work(context)` without the GIL, then raises what stopped it: the callback's
    /// exception (or KeyboardInterrupt) first, else the library's error. Returns its value.
    template <typename Work>
    auto operator()(Work&& work) {
        std::optional<decltype(work(context_))> result;
        {
            py::gil_scoped_release release;
            result.emplace(work(context_));
        }
        if (python_error_) throw *python_error_;
        return take(std::move(*result));
    }

private:
    void on_progress(const ProgressEvent& event);

    RunContext context_;
    CancelToken own_token_;
    CancelToken* token_ = &own_token_;
    py::object progress_;
    py::object cancel_owner_;  // keeps a caller's CancelToken alive during the call
    std::optional<py::error_already_set> python_error_;
};

/// The threads keyword: >= 0, else InvalidArgumentError (the CLI's message for --threads).
int check_threads(int threads);

/// The threads keyword as given (None = 0, all cores): an int >= 0.
int threads_keyword(const py::object& threads);

/// Adds exemplar.Progress and exemplar.CancelToken to `module`.
void register_run_types(py::module_& module);

}  // namespace exemplar::python
