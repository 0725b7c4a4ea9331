#include "progress_bar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace exemplar::cli {

ProgressBar::ProgressBar(std::ostream& out, std::string label, bool enabled)
    : out_(out), label_(std::move(label)), enabled_(enabled), start_(Clock::now()) {}

ProgressBar::~ProgressBar() {
    finish();
}

void ProgressBar::update(const ProgressEvent& e) {
    char detail[64];
    std::snprintf(detail, sizeof detail, "level %d/%d  iter %d/%d", e.level + 1, e.levels,
                  e.iteration + 1, e.iterations);
    update(e.fraction, detail);
}

void ProgressBar::update(double fraction, const std::string& detail) {
    if (!enabled_) return;
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0) return;  // short runs stay silent
    if (drawn_ && now - last_draw_ < std::chrono::milliseconds(100) && fraction < 1.0) return;
    last_draw_ = now;
    constexpr int kWidth = 24;
    const double f = std::clamp(fraction, 0.0, 1.0);
    const int filled = static_cast<int>(std::lround(f * kWidth));
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.append(static_cast<std::size_t>(kWidth - filled), '.');
    char line[200];
    const double eta = f > 0.01 ? elapsed * (1.0 - f) / f : 0.0;
    std::snprintf(line, sizeof line, "\r%s [%s] %3d%%  %s  ETA %ds  ", label_.c_str(), bar.c_str(),
                  static_cast<int>(f * 100.0), detail.c_str(), static_cast<int>(std::lround(eta)));
    out_ << line << std::flush;
    drawn_ = true;
}

void ProgressBar::finish() {
    if (drawn_) out_ << '\n' << std::flush;
    drawn_ = false;
}

}  // namespace exemplar::cli
