#pragma once
// numpy arrays <-> exemplar::Image. Arrays are HxWxC (HxW for grey inputs), C-contiguous,
// float32 (values as they are) or uint8 (k -> k / 255, as the io module loads 8-bit files).
// Anything else is rejected with an InvalidArgumentError naming the argument, never guessed.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "errors.hpp"
#include "exemplar/core/image.hpp"

namespace exemplar::python {

namespace py = pybind11;

/// Sample type of an array given or returned.
enum class SampleType { Float32, UInt8 };

/// An image converted from an array, with the array's sample type (outputs follow it).
struct ImageArg {
    Image image;
    SampleType type = SampleType::Float32;
};

/// How many dimensions an argument may have.
enum class Shape {
    Colour,  ///< HxWxC only.
    Grey,    ///< HxW or HxWx1 (masks, weight maps, angle fields).
};

/// Converts `object` (a numpy array) into an image; `what` names the argument in errors
/// ("style: dtype float64 is not supported (must be float32 or uint8) ...").
ImageArg image_from_array(const py::handle& object, const std::string& what, Shape shape);

/// An HxW array of integer ids 0..max_id as they are (not scaled like images: uint8 id 3 is 3),
/// as a 1-channel image; `what` names the argument and `noun` one id in errors
/// ("source_labels: 2.5 is not a segment id (integers 0..16777215)").
Image integer_ids(const py::handle& object, const std::string& what, const std::string& noun,
                  double max_id);

/// The image as an HxWxC array: float32 without a copy (the array owns the image's buffer), or
/// uint8 quantized as the io module writes 8-bit files (clamped to [0, 1], rounded, NaN -> 0).
py::array array_from_image(Image&& image, SampleType type);

/// The image as an HxW float32 array (a 1-channel image, without a copy).
py::array grey_array_from_image(Image&& image);

}  // namespace exemplar::python
