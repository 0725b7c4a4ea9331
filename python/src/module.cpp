// exemplar._exemplar: the extension module behind the `exemplar` package (python/exemplar/).
// The package gives each verb its Python signature and docstring, generated from the option
// table this module exports; everything else lives here.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/version.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

py::array load_image_py(const std::string& path) {
    Result<Image> image = [&] {
        py::gil_scoped_release release;
        return load_image(path);
    }();
    return array_from_image(take(std::move(image)), SampleType::Float32);
}

void save_image_py(const py::object& image, const std::string& path) {
    ImageArg arg = image_from_array(image, "image", Shape::Colour);
    // uint8 arrays are written as 8-bit samples, so that they read back unchanged.
    SaveOptions options;
    if (arg.type == SampleType::UInt8) options.format = PixelFormat::UInt8;
    py::gil_scoped_release release;
    check(save_image(arg.image, path, options));
}

}  // namespace

}  // namespace exemplar::python

PYBIND11_MODULE(_exemplar, module) {
    namespace py = pybind11;
    using namespace exemplar::python;
    module.doc() = "The compiled part of the exemplar package; import exemplar instead.";
    register_errors(module);
    register_run_types(module);
    register_synthesis(module);
    register_render(module);
    register_sketch(module);
    register_animate(module);
    register_flow(module);
    register_fluid(module);
    register_noisy(module);
    register_npr(module);
    register_paint(module);
    module.def("option_specs", &option_specs_for_python,
               "The synthesis options (the library's option table): a list of dicts with name, "
               "doc, unit, type, min, max and default.");
    module.def(
        "load_image", &load_image_py, py::arg("path"),
        "Loads an image file (PNG, JPEG, TIFF, EXR, PNM) as an HxWxC float32 array; 8/16-bit "
        "files are normalized to [0, 1]. Raises IoError or UnsupportedError naming the file.");
    module.def("save_image", &save_image_py, py::arg("image"), py::arg("path"),
               "Writes an HxWxC array to a file, format from the extension, atomically. uint8 "
               "arrays are written as 8-bit samples; float32 as the format's natural choice "
               "(8-bit PNG/JPEG, half EXR, 16-bit TIFF).");
    module.attr("__version__") = std::string(exemplar::version());
}
