#include "stylize_job.hpp"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "exemplar/synth/options.hpp"
#include "json_file.hpp"

namespace exemplar::cli {

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// Every key of the job file `path` goes to `visit(raw_key, canonical_key, value, resolve)`.
using Resolver = std::function<std::string(const std::string&)>;
using KeyVisitor =
    std::function<Status(const std::string&, const std::string&, const json&, const Resolver&)>;

Status visit_job_file(const std::string& path, const KeyVisitor& visit) {
    auto parsed = read_json_object(path);
    if (!parsed.ok()) return parsed.status();
    const json& doc = *parsed;
    const fs::path base = fs::path(path).parent_path();
    const Resolver resolve = [&](const std::string& p) {
        if (p.empty() || fs::path(p).is_absolute()) return p;
        return (base / p).lexically_normal().string();
    };
    for (const auto& [raw_key, value] : doc.items()) {
        EXEMPLAR_RETURN_IF_ERROR(visit(raw_key, canonical_key(raw_key), value, resolve));
    }
    return Status::ok();
}

// The keys of `fields`; Unsupported (not an error yet) if `key` is not one of them.
Status read_field(const std::string& path, const JobFields& fields, const std::string& raw_key,
                  const std::string& key, const json& value, const Resolver& resolve) {
    if (auto it = fields.paths.find(key); it != fields.paths.end()) {
        if (!value.is_string()) return type_error(path, raw_key, "a string (a file path)");
        *it->second = resolve(value.get<std::string>());
    } else if (auto list = fields.path_lists.find(key); list != fields.path_lists.end()) {
        const bool strings =
            value.is_string() ||
            (value.is_array() && !value.empty() &&
             std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_string(); }));
        if (!strings) return type_error(path, raw_key, "a file path or an array of file paths");
        list->second->clear();
        for (const json& v : value.is_string() ? json::array({value}) : value) {
            list->second->push_back(resolve(v.get<std::string>()));
        }
    } else if (auto w = fields.words.find(key); w != fields.words.end()) {
        if (!value.is_string()) return type_error(path, raw_key, "a string");
        *w->second = value.get<std::string>();
    } else if (auto n = fields.numbers.find(key); n != fields.numbers.end()) {
        if (!value.is_number()) return type_error(path, raw_key, "a number");
        *n->second = value.get<double>();
    } else if (auto i = fields.integers.find(key); i != fields.integers.end()) {
        if (!value.is_number_integer()) return type_error(path, raw_key, "an integer");
        *i->second = value.get<long long>();
    } else if (auto f = fields.flags.find(key); f != fields.flags.end()) {
        if (!value.is_boolean()) return type_error(path, raw_key, "true or false");
        *f->second = value.get<bool>();
    } else {
        return Status(ErrorCode::Unsupported, key);
    }
    return Status::ok();
}

}  // namespace

Status read_job_file(const std::string& path, const JobFields& fields,
                     std::vector<std::string>* given) {
    return visit_job_file(path, [&](const std::string& raw_key, const std::string& key,
                                    const json& value, const Resolver& resolve) {
        const Status status = read_field(path, fields, raw_key, key, value, resolve);
        if (status.code() == ErrorCode::Unsupported) {
            return invalid_argument(path + ": unknown key '" + raw_key + "'");
        }
        if (status.is_ok() && given != nullptr) given->push_back(key);
        return status;
    });
}

Result<StylizeJob> load_job_file(const std::string& path) {
    StylizeJob job;
    JobFields fields;
    fields.paths = {
        {"style", &job.style},
        {"output", &job.output},
        {"target-mask", &job.target_mask},
        {"source-mask", &job.source_mask},
        {"source-labels", &job.source_labels},
        {"target-labels", &job.target_labels},
        {"source-orientation", &job.source_orientation},
        {"target-orientation", &job.target_orientation},
        {"init", &job.init},
        {"init-nnf", &job.init_nnf},
        {"inpaint", &job.inpaint},
        {"save-nnf", &job.save_nnf},
        {"save-error", &job.save_error},
    };
    fields.words = {
        {"usage", &job.usage}, {"vote", &job.vote}, {"quality", &job.quality}, {"size", &job.size}};

    const Status status = visit_job_file(
        path,
        [&](const std::string& raw_key, const std::string& key, const json& value,
            const Resolver& resolve) -> Status {
            const Status field = read_field(path, fields, raw_key, key, value, resolve);
            if (field.code() != ErrorCode::Unsupported) return field;
            if (key == "guides") {
                if (!value.is_array()) return type_error(path, raw_key, "an array of guides");
                for (const json& g : value) {
                    if (!g.is_object() || !g.contains("source") || !g.contains("target") ||
                        !g["source"].is_string() || !g["target"].is_string()) {
                        return type_error(path, raw_key,
                                          "an array of {\"source\": ..., \"target\": ..., "
                                          "\"weight\": ...} objects");
                    }
                    GuideSpec spec;
                    for (const auto& [gk_raw, gv] : g.items()) {
                        const std::string gk = canonical_key(gk_raw);
                        if (gk == "source" || gk == "target") continue;
                        if (gk == "weight") {
                            if (!gv.is_number())
                                return type_error(path, "guides.weight", "a number");
                            spec.weight = gv.get<float>();
                        } else if (gk == "weight-map") {
                            if (!gv.is_string())
                                return type_error(path, "guides.weight-map", "a path");
                            spec.weight_map = resolve(gv.get<std::string>());
                        } else {
                            return invalid_argument(path + ": unknown key 'guides." + gk_raw +
                                                    "' (guides take source, target, weight, "
                                                    "weight-map)");
                        }
                    }
                    spec.source = resolve(g["source"].get<std::string>());
                    spec.target = resolve(g["target"].get<std::string>());
                    job.guides.push_back(std::move(spec));
                }
            } else if (key == "style-weights") {
                if (!value.is_array()) return type_error(path, raw_key, "an array of numbers");
                for (const json& v : value) {
                    if (!v.is_number()) return type_error(path, raw_key, "an array of numbers");
                    job.style_weights.push_back(v.get<float>());
                }
            } else if (key == "threads") {
                if (!value.is_number_integer()) return type_error(path, raw_key, "an integer");
                job.threads = value.get<int>();
            } else if (key == "quiet") {
                if (!value.is_boolean()) return type_error(path, raw_key, "true or false");
                job.quiet = value.get<bool>();
            } else if (find_option(key) != nullptr) {
                if (!value.is_number()) return type_error(path, raw_key, "a number");
                job.numeric[std::string(find_option(key)->name)] = value.get<double>();
            } else {
                return invalid_argument(path + ": unknown key '" + raw_key + "'");
            }
            return Status::ok();
        });
    if (!status.is_ok()) return status;
    return job;
}

StylizeJob merge_jobs(const StylizeJob& base, const StylizeJob& over) {
    StylizeJob out = base;
    auto take = [](std::string& dst, const std::string& src) {
        if (!src.empty()) dst = src;
    };
    take(out.style, over.style);
    take(out.output, over.output);
    take(out.usage, over.usage);
    take(out.vote, over.vote);
    take(out.quality, over.quality);
    take(out.target_mask, over.target_mask);
    take(out.source_mask, over.source_mask);
    take(out.source_labels, over.source_labels);
    take(out.target_labels, over.target_labels);
    take(out.source_orientation, over.source_orientation);
    take(out.target_orientation, over.target_orientation);
    take(out.init, over.init);
    take(out.init_nnf, over.init_nnf);
    take(out.inpaint, over.inpaint);
    take(out.save_nnf, over.save_nnf);
    take(out.save_error, over.save_error);
    take(out.size, over.size);
    if (!over.guides.empty()) out.guides = over.guides;
    if (!over.style_weights.empty()) out.style_weights = over.style_weights;
    for (const auto& [k, v] : over.numeric) out.numeric[k] = v;
    if (over.threads) out.threads = over.threads;
    if (over.quiet) out.quiet = over.quiet;
    return out;
}

}  // namespace exemplar::cli
