#pragma once
// The parts of the extension module exemplar._exemplar; module.cpp calls each once.

#include <pybind11/pybind11.h>

namespace exemplar::python {

namespace py = pybind11;

/// stylize, apply_nnf, stylit and their result type (synthesis.cpp).
void register_synthesis(py::module_& module);

/// render (render.cpp).
void register_render(py::module_& module);

/// beautify and its result type (sketch.cpp).
void register_sketch(py::module_& module);

/// animate (animate.cpp).
void register_animate(py::module_& module);

/// flow (flow.cpp).
void register_flow(py::module_& module);

/// fluid_frame, fluid_simulate and the fluid option table (fluid.cpp).
void register_fluid(py::module_& module);

/// noisy_frame and the noisy option table (noisy.cpp).
void register_noisy(py::module_& module);

/// npr_frame, its NprState and the npr option table (npr.cpp).
void register_npr(py::module_& module);

/// directions and paint (paint.cpp).
void register_paint(py::module_& module);

}  // namespace exemplar::python
