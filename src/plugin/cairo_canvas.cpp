// The Cairo canvases: linked in (libexemplar.so, the Python module) or loaded from the plugin on
// first use (the `exemplar` command).

#include "cairo_canvas.hpp"

// Defined by cairo_plugin.cpp where that is linked in; null in the `exemplar` executable.
extern "C" const exemplar::plugin::cairo::Entry* exemplar_cairo_entry() __attribute__((weak));

namespace exemplar::plugin::cairo {

Result<const Entry*> canvases() {
    return linked_or_loaded(exemplar_cairo_entry, kPlugin);
}

}  // namespace exemplar::plugin::cairo
