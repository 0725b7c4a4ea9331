// Finds and loads plugins with dlopen on first use (see plugin_loader.hpp for why).

#include "plugin_loader.hpp"

#include <dlfcn.h>
#include <fmt/format.h>
#include <link.h>

#include <cstdlib>
#include <map>
#include <mutex>
#include <string>
#include <system_error>

namespace exemplar::plugin {

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

Result<const void*> load_once(const PluginSpec& spec) {
    const auto unavailable = [&](const std::string& reason) {
        return unsupported(
            fmt::format("{} is not available ({}: {})", spec.feature, spec.file_name, reason));
    };
    const std::vector<fs::path> folders = plugin_folders();
    fs::path file;
    for (const fs::path& folder : folders) {
        std::error_code ec;
        if (fs::is_regular_file(folder / spec.file_name, ec)) {
            file = folder / spec.file_name;
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

    // Never closed: objects made by the plugin live as long as their users.
    void* library = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
        const char* reason = dlerror();
        return unavailable(reason != nullptr ? reason : "dlopen failed");
    }
    using EntryFunction = const void* (*)();
    auto entry_function = reinterpret_cast<EntryFunction>(dlsym(library, spec.entry_symbol));
    if (entry_function == nullptr) {
        return unavailable(fmt::format("{}: no symbol {}, not an exemplar plugin", file.string(),
                                       spec.entry_symbol));
    }
    const void* entry = entry_function();
    const int version = entry == nullptr ? 0 : *static_cast<const int*>(entry);
    if (version != spec.abi_version) {
        return unavailable(fmt::format(
            "{}: interface version {}, this exemplar needs {} (the plugin is from another build)",
            file.string(), version, spec.abi_version));
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

Result<const void*> load_entry(const PluginSpec& spec) {
    static std::mutex mutex;
    static std::map<std::string, Result<const void*>> loaded;
    const std::lock_guard<std::mutex> lock(mutex);
    auto it = loaded.find(spec.file_name);
    if (it == loaded.end()) it = loaded.emplace(spec.file_name, load_once(spec)).first;
    return it->second;
}

}  // namespace exemplar::plugin
