#include "json_file.hpp"

#include <filesystem>
#include <fstream>

namespace exemplar::cli {

Status type_error(const std::string& file, const std::string& key, const char* expected) {
    return invalid_argument(file + ": key '" + key + "' must be " + expected);
}

Result<nlohmann::json> read_json_object(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(path, ec)) return io_error(path + ": no such file");
    if (fs::is_directory(path, ec)) return io_error(path + ": is a folder, not a job file");
    std::ifstream in(path);
    if (!in) return io_error(path + ": cannot open job file");
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
        std::string what = e.what();
        for (char& c : what) {
            if (c == '\n') c = ' ';
        }
        return invalid_argument(path + ": not valid JSON (" + what + ")");
    }
    if (!doc.is_object()) return invalid_argument(path + ": must hold a JSON object");
    return doc;
}

std::string canonical_key(std::string key) {
    for (char& c : key) {
        if (c == '_') c = '-';
    }
    return key;
}

}  // namespace exemplar::cli
