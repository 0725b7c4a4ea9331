#include "run.hpp"

#include <string>

#include "keywords.hpp"

namespace exemplar::python {

namespace {

/// What a progress callback receives (a copy: the event's stage is a view).
struct Progress {
    std::string stage;
    int level = 0;
    int levels = 0;
    int iteration = 0;
    int iterations = 0;
    double fraction = 0.0;
};

}  // namespace

PythonRun::PythonRun(int threads, py::object progress, py::object cancel)
    : progress_(std::move(progress)) {
    context_.threads = check_threads(threads);
    if (!cancel.is_none()) {
        if (!py::isinstance<PyCancelToken>(cancel)) {
            throw py::type_error("cancel: must be an exemplar.CancelToken (got " +
                                 std::string(py::str(py::type::of(cancel).attr("__name__"))) + ")");
        }
        token_ = &cancel.cast<PyCancelToken&>().token;
        cancel_owner_ = std::move(cancel);
    }
    if (!progress_.is_none() && !PyCallable_Check(progress_.ptr())) {
        throw py::type_error("progress: must be callable (got " +
                             std::string(py::str(py::type::of(progress_).attr("__name__"))) + ")");
    }
    context_.cancel = token_;
    // Always installed: Ctrl-C is noticed at the next event even without a callback.
    context_.progress = [this](const ProgressEvent& event) { on_progress(event); };
}

PythonRun::PythonRun(const RunKeywords& keywords)
    : PythonRun(threads_keyword(keywords.threads), keywords.progress, keywords.cancel) {}

RunKeywords pop_run_keywords(py::dict& kwargs) {
    RunKeywords keywords;
    keywords.progress = pop(kwargs, "progress");
    keywords.cancel = pop(kwargs, "cancel");
    keywords.threads = pop(kwargs, "threads");
    return keywords;
}

void PythonRun::on_progress(const ProgressEvent& event) {
    py::gil_scoped_acquire gil;
    if (python_error_) return;  // already cancelling
    try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (progress_.is_none()) return;
        const py::object answer =
            progress_(Progress{std::string(event.stage), event.level, event.levels, event.iteration,
                               event.iterations, event.fraction});
        // Only an explicit False cancels: a callback that returns nothing lets the run go on.
        if (answer.is(py::bool_(false))) token_->cancel();
    } catch (py::error_already_set& error) {
        python_error_.emplace(std::move(error));
        token_->cancel();
    }
}

int check_threads(int threads) {
    if (threads < 0) {
        throw InputError("threads: " + std::to_string(threads) +
                         " is invalid (must be >= 0; 0 = all cores)");
    }
    return threads;
}

int threads_keyword(const py::object& threads) {
    return threads.is_none() ? 0 : check_threads(integer(threads, "threads"));
}

void register_run_types(py::module_& module) {
    py::class_<Progress>(module, "Progress",
                         "One progress report of a running call, passed to its progress "
                         "callback.")
        .def_readonly("stage", &Progress::stage, "What the call is doing: 'search', 'vote', ...")
        .def_readonly("level", &Progress::level, "Pyramid level, 0 = coarsest.")
        .def_readonly("levels", &Progress::levels, "Number of pyramid levels.")
        .def_readonly("iteration", &Progress::iteration, "EM iteration within the level.")
        .def_readonly("iterations", &Progress::iterations, "EM iterations on this level.")
        .def_readonly("fraction", &Progress::fraction,
                      "Overall completion of the whole call in [0, 1]; never decreases.")
        .def("__repr__", [](const Progress& p) {
            return "<exemplar.Progress " + p.stage + " " + std::to_string(p.fraction) + ">";
        });
    py::class_<PyCancelToken>(module, "CancelToken",
                              "A flag that stops a running call: pass it as cancel=token, call "
                              "token.cancel() from another thread; the call then raises "
                              "exemplar.Cancelled. A token stays set once set.")
        .def(py::init<>())
        .def(
            "cancel", [](PyCancelToken& t) { t.token.cancel(); },
            "Asks every call using this token to stop (thread-safe).")
        .def_property_readonly(
            "cancelled", [](const PyCancelToken& t) { return t.token.cancelled(); },
            "True once cancel() was called.");
}

}  // namespace exemplar::python
