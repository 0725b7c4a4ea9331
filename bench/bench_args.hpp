#pragma once
// Command-line pieces shared by the end-to-end benchmarks (bench_examples, bench_stylit):
// "NAME [threads] [repeats] [options...]", `--set name=value` for any numeric synthesis option,
// `--usage NAME`, and the process CPU time.
#include <sys/resource.h>

#include <cstdio>
#include <string>
#include <utility>

#include "exemplar/synth/options.hpp"

namespace exemplar::bench {

/// User + system CPU seconds of this process so far.
inline double cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto secs = [](const timeval& t) { return static_cast<double>(t.tv_sec) + t.tv_usec * 1e-6; };
    return secs(usage.ru_utime) + secs(usage.ru_stime);
}

/// Reads the optional positional thread and repeat counts after argv[1]; returns the index of
/// the first option argument.
inline int parse_counts(int argc, char** argv, int& threads, int& repeats) {
    if (argc <= 2 || argv[2][0] == '-') return 2;
    threads = std::stoi(argv[2]);
    if (argc <= 3 || argv[3][0] == '-') return 3;
    repeats = std::stoi(argv[3]);
    return 4;
}

/// Calls `handle(flag, value)` for every "--flag value" pair from argv[first] on; false (after a
/// message) when the last flag has no value or `handle` returns false.
template <class Handle>
bool for_each_flag(int argc, char** argv, int first, Handle handle) {
    for (int i = first; i < argc; i += 2) {
        if (i + 1 >= argc) {
            std::fprintf(stderr, "%s: missing value\n", argv[i]);
            return false;
        }
        if (!handle(std::string(argv[i]), std::string(argv[i + 1]))) return false;
    }
    return true;
}

/// `--set name=value`: the option and its value, or nullptr (after a message) if unknown.
inline std::pair<const OptionSpec*, double> parse_set(const std::string& kv) {
    const auto eq = kv.find('=');
    const OptionSpec* spec = eq == std::string::npos ? nullptr : find_option(kv.substr(0, eq));
    if (spec == nullptr) {
        std::fprintf(stderr, "unknown option in --set %s\n", kv.c_str());
        return {nullptr, 0.0};
    }
    return {spec, std::stod(kv.substr(eq + 1))};
}

/// `--usage NAME`: false (after a message) if the name is unknown.
inline bool parse_usage(const std::string& name, UsageStrategy& usage) {
    auto parsed = parse_usage_strategy(name);
    if (!parsed.ok()) {
        std::fprintf(stderr, "%s\n", parsed.status().message().c_str());
        return false;
    }
    usage = *parsed;
    return true;
}

}  // namespace exemplar::bench
