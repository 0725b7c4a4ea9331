// Linked into every test executable. The plugins (OpenCV, Embree, Cairo, OpenEXR, libtiff, the
// MP4 codecs) sit next to the `exemplar` executable at the top of the build tree, not next to the
// tests in tests/<area>/, so the tests point EXEMPLAR_PLUGIN_DIR at them before main() runs,
// unless whoever runs them has set it.

#include <cstdlib>

namespace {

[[maybe_unused]] const bool plugin_dir_set =
    ::setenv("EXEMPLAR_PLUGIN_DIR", EXEMPLAR_BUILD_PLUGIN_DIR, 0) == 0;

}  // namespace
