// The OpenCV operations: linked in (libexemplar.so, the Python module) or loaded from the
// plugin on first use (the `exemplar` command).

#include "opencv_kernels.hpp"

// Defined by opencv_plugin.cpp where that is linked in; null in the `exemplar` executable.
extern "C" const exemplar::plugin::opencv::Entry* exemplar_opencv_entry() __attribute__((weak));

namespace exemplar::plugin::opencv {

Result<const Entry*> kernels() {
    return linked_or_loaded(exemplar_opencv_entry, kPlugin);
}

}  // namespace exemplar::plugin::opencv
