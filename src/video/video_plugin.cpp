// Loads the video codec plugin with dlopen on first use (see video_codec.hpp for why).

#include "video_plugin.hpp"

#include <dlfcn.h>
#include <fmt/format.h>
#include <link.h>

#include <cstdlib>
#include <string>
#include <system_error>

namespace exemplar::video::codec {

namespace fs = std::filesystem;

namespace {

// The file of the binary holding this code. The dynamic loader's link map names shared objects
// by path but the main program by "", so the executable is asked of the kernel.
fs::path own_binary() {
    static const char anchor = 0;
    Dl_info info{};
    link_map* map = nullptr;
    if (dladdr1(&anchor, &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) != 0 &&
        map != nullptr && map->l_name != nullptr && map->l_name[0] != '\0') {
        return fs::absolute(map->l_name);
    }
    std::error_code ec;
    fs::path executable = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : executable;
}

Status unavailable(const std::string& reason) {
    return unsupported(
        fmt::format("video support is not available ({}: {})", kPluginFileName, reason));
}

Result<const Entry*> load_once() {
    const std::vector<fs::path> folders = plugin_folders();
    fs::path file;
    for (const fs::path& folder : folders) {
        std::error_code ec;
        if (fs::is_regular_file(folder / kPluginFileName, ec)) {
            file = folder / kPluginFileName;
            break;
        }
    }
    if (file.empty()) {
        std::string searched;
        for (const fs::path& folder : folders) {
            searched += (searched.empty() ? "" : ", ") + folder.string();
        }
        const char* variable = std::getenv(kPluginDirVariable);
        const bool overridden = variable != nullptr && variable[0] != '\0';
        return unavailable(
            fmt::format("not found in {}{}", searched.empty() ? "?" : searched,
                        overridden ? fmt::format(" (set by {})", kPluginDirVariable) : ""));
    }

    // Never closed: the codecs' objects live as long as the sequences and writers using them.
    void* library = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
        const char* reason = dlerror();
        return unavailable(reason != nullptr ? reason : "dlopen failed");
    }
    auto entry_function = reinterpret_cast<EntryFunction>(dlsym(library, kEntrySymbol));
    if (entry_function == nullptr) {
        return unavailable(
            fmt::format("{}: no symbol {}, not an exemplar plugin", file.string(), kEntrySymbol));
    }
    const Entry* entry = entry_function();
    if (entry == nullptr || entry->abi_version != kCodecAbiVersion) {
        return unavailable(fmt::format(
            "{}: interface version {}, this exemplar needs {} (the plugin is from another build)",
            file.string(), entry == nullptr ? 0 : entry->abi_version, kCodecAbiVersion));
    }
    return entry;
}

}  // namespace

std::vector<fs::path> plugin_folders() {
    if (const char* folder = std::getenv(kPluginDirVariable);
        folder != nullptr && folder[0] != '\0') {
        return {fs::path(folder)};
    }
    const fs::path binary = own_binary();
    if (binary.empty()) return {};
    const fs::path folder = binary.parent_path();
    return {folder, (folder / EXEMPLAR_PLUGIN_RELATIVE_DIR).lexically_normal()};
}

Result<const Entry*> load_plugin() {
    static const Result<const Entry*> plugin = load_once();
    return plugin;
}

}  // namespace exemplar::video::codec
