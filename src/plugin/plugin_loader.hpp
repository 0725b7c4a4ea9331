#pragma once
// Loading exemplar's plugins: shared objects that hold the code using a heavy third-party
// library (OpenCV, Embree, Cairo, FFmpeg through OpenCV's videoio), loaded with dlopen on first
// use so that a process pays for those libraries only when it needs them (docs/architecture.md,
// "Plugins"). Each plugin exports one C function returning its entry table, a struct whose
// first member is `int abi_version`.

#include <filesystem>
#include <vector>

#include "exemplar/core/status.hpp"

namespace exemplar::plugin {

/// The environment variable that, when set and not empty, names the only folder searched for
/// plugins (tests point it at the build tree, or at an empty folder).
inline constexpr const char* kPluginDirVariable = "EXEMPLAR_PLUGIN_DIR";

/// One plugin: its file, the C symbol it exports, the interface version this build expects and
/// what is missing without it (the start of the error message, e.g. "video support").
struct PluginSpec {
    const char* file_name;
    const char* entry_symbol;
    int abi_version;
    const char* feature;
};

/// The folders searched for plugins, in order: `$EXEMPLAR_PLUGIN_DIR` alone if it is set and
/// not empty; otherwise the folder of the binary that holds this code (the executable, as the
/// modules are linked statically: the build tree keeps the plugins next to `exemplar`), then
/// that folder joined with EXEMPLAR_PLUGIN_RELATIVE_DIR (the install layout: `bin/exemplar`
/// finds `lib/exemplar/<plugin>`).
std::vector<std::filesystem::path> plugin_folders();

/// The entry table of `spec`'s plugin, loaded from the first of `plugin_folders()` that holds
/// it on the first call for that file (thread-safe) and kept for the life of the process; later
/// calls return the same table or the same error. Unsupported `<feature> is not available
/// (<file>: <reason>)` if it is missing, cannot be loaded (the reason is dlerror's) or comes
/// from another build (its abi_version differs).
Result<const void*> load_entry(const PluginSpec& spec);

/// `load_entry` for an entry table type whose first member is `int abi_version`.
template <class Entry>
Result<const Entry*> load(const PluginSpec& spec) {
    auto entry = load_entry(spec);
    if (!entry.ok()) return entry.status();
    return static_cast<const Entry*>(*entry);
}

/// The entry table from `linked_in`, the plugin's entry point, when the plugin's code is linked
/// into this binary (libexemplar.so, the Python module: callers declare it as a weak symbol,
/// null elsewhere), else `load<Entry>(spec)`.
template <class Entry>
Result<const Entry*> linked_or_loaded(const Entry* (*linked_in)(), const PluginSpec& spec) {
    if (linked_in != nullptr) return linked_in();
    return load<Entry>(spec);
}

}  // namespace exemplar::plugin
