#pragma once
// Job files: reading a JSON object with one-line errors, and key spelling ('_' == '-').

#include <nlohmann/json.hpp>
#include <string>

#include "exemplar/core/status.hpp"

namespace exemplar::cli {

/// Parses `path` as a JSON object. IoError if it is missing, a folder or unreadable;
/// InvalidArgument (naming the file) if it is not valid JSON or not an object.
Result<nlohmann::json> read_json_object(const std::string& path);

/// "FILE: key 'KEY' must be EXPECTED": the error for a job-file value of the wrong type.
Status type_error(const std::string& file, const std::string& key, const char* expected);

/// A job-file key with '_' spelled '-' (both spellings are accepted).
std::string canonical_key(std::string key);

}  // namespace exemplar::cli
