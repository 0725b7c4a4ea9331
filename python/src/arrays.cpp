#include "arrays.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

namespace exemplar::python {

namespace {

std::string shape_text(const py::array& array) {
    std::string text = "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d) {
        if (d > 0) text += ", ";
        text += std::to_string(array.shape(d));
    }
    return text + (array.ndim() == 1 ? ",)" : ")");
}

// The same rounding as the io module's 8-bit writer (src/io/codecs.hpp, to_level).
std::uint8_t to_level(float v) {
    if (!(v > 0.0f)) return 0;  // also NaN
    if (v >= 1.0f) return 255;
    return static_cast<std::uint8_t>(static_cast<double>(v) * 255.0 + 0.5);
}

// Moves `image` into a capsule that owns it, and returns an array over its pixels.
py::array wrap(Image&& image, std::vector<py::ssize_t> shape) {
    auto* owned = new Image(std::move(image));
    py::capsule owner(owned, [](void* p) { delete static_cast<Image*>(p); });
    return py::array_t<float>(std::move(shape), owned->data().data(), owner);
}

}  // namespace

ImageArg image_from_array(const py::handle& object, const std::string& what, Shape shape) {
    if (!py::isinstance<py::array>(object)) {
        throw InputError(what + ": must be a numpy array (got " +
                         std::string(py::str(py::type::of(object).attr("__name__"))) + ")");
    }
    const auto array = py::reinterpret_borrow<py::array>(object);
    const bool is_float = array.dtype().is(py::dtype::of<float>());
    const bool is_byte = array.dtype().is(py::dtype::of<std::uint8_t>());
    if (!is_float && !is_byte) {
        throw InputError(what + ": dtype " + std::string(py::str(array.dtype())) +
                         " is not supported (must be float32 or uint8; convert with "
                         ".astype(numpy.float32))");
    }
    const py::ssize_t ndim = array.ndim();
    const bool grey = shape == Shape::Grey;
    if (ndim != 3 && !(grey && ndim == 2)) {
        throw InputError(what + ": has shape " + shape_text(array) +
                         (grey ? " (must be HxW or HxWx1)"
                               : " (must be HxWxC; add a channel axis to a grey image with "
                                 "image[..., None])"));
    }
    const py::ssize_t height = array.shape(0), width = array.shape(1);
    const py::ssize_t channels = ndim == 3 ? array.shape(2) : 1;
    if (grey && channels != 1) {
        throw InputError(what + ": has shape " + shape_text(array) +
                         " (must be HxW or HxWx1: one channel)");
    }
    if (height == 0 || width == 0 || channels == 0) {
        throw InputError(what + ": is empty (shape " + shape_text(array) + ")");
    }
    constexpr py::ssize_t kMax = std::numeric_limits<int>::max();
    if (height > kMax || width > kMax || channels > kMax) {
        throw InputError(what + ": has shape " + shape_text(array) + " (too large)");
    }
    if (!(array.flags() & py::array::c_style)) {
        throw InputError(what + ": is not C-contiguous (strides " +
                         [&] {
                             std::string text;
                             for (py::ssize_t d = 0; d < ndim; ++d) {
                                 text += (d > 0 ? ", " : "") + std::to_string(array.strides(d));
                             }
                             return text;
                         }() +
                         "); pass numpy.ascontiguousarray(" + what + ")");
    }

    ImageArg arg;
    arg.type = is_float ? SampleType::Float32 : SampleType::UInt8;
    arg.image =
        Image(static_cast<int>(width), static_cast<int>(height), static_cast<int>(channels));
    float* out = arg.image.data().data();
    const std::size_t count = arg.image.size();
    if (is_float) {
        std::memcpy(out, array.data(), count * sizeof(float));
    } else {
        const auto* in = static_cast<const std::uint8_t*>(array.data());
        // As the io module reads 8-bit files (k / 255.0f), so arrays and files give equal runs.
        for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<float>(in[i]) / 255.0f;
    }
    return arg;
}

py::array array_from_image(Image&& image, SampleType type) {
    std::vector<py::ssize_t> shape = {image.height(), image.width(), image.channels()};
    if (type == SampleType::Float32) return wrap(std::move(image), std::move(shape));
    py::array_t<std::uint8_t> out(shape);
    std::uint8_t* bytes = out.mutable_data();
    const std::span<const float> values = image.data();
    std::transform(values.begin(), values.end(), bytes, to_level);
    return out;
}

Image integer_ids(const py::handle& object, const std::string& what, const std::string& noun,
                  double max_id) {
    const auto array =
        py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
    if (!array || array.ndim() != 2) {
        throw InputError(what + ": must be an HxW array of integer " + noun + "s");
    }
    Image out(static_cast<int>(array.shape(1)), static_cast<int>(array.shape(0)), 1);
    for (std::size_t i = 0; i < out.pixel_count(); ++i) {
        const double v = array.data()[i];
        if (!(v >= 0.0 && v <= max_id) || v != std::floor(v)) {
            throw InputError(what + ": " + std::to_string(v) + " is not a " + noun +
                             " (integers 0.." + std::to_string(static_cast<long long>(max_id)) +
                             ")");
        }
        out.data()[i] = static_cast<float>(v);
    }
    return out;
}

py::array grey_array_from_image(Image&& image) {
    std::vector<py::ssize_t> shape = {image.height(), image.width()};
    return wrap(std::move(image), std::move(shape));
}

}  // namespace exemplar::python
