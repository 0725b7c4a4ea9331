#pragma once
// A one-line progress bar on a terminal stream, shown only once a run has lasted ~1 s.

#include <chrono>
#include <ostream>
#include <string>

#include "exemplar/core/run_context.hpp"

namespace exemplar::cli {

class ProgressBar {
public:
    ProgressBar(std::ostream& out, std::string label, bool enabled);
    ~ProgressBar();

    /// Updates the bar (rate-limited to ~10 redraws per second).
    void update(const ProgressEvent& event);
    /// Same with a free-form detail after the percentage and before the ETA.
    void update(double fraction, const std::string& detail);
    /// Ends the line if anything was drawn.
    void finish();

private:
    using Clock = std::chrono::steady_clock;
    std::ostream& out_;
    std::string label_;
    bool enabled_;
    bool drawn_ = false;
    Clock::time_point start_;
    Clock::time_point last_draw_;
};

}  // namespace exemplar::cli
