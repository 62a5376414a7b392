#include "core/ProgressBar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

namespace raycache {

ProgressBar::ProgressBar(std::ostream& out, bool interactive, double totalWork, Clock clock)
    : out_(out), interactive_(interactive), total_(std::max(totalWork, 1e-9)), clock_(std::move(clock)) {
    if (!clock_) {
        const auto origin = std::chrono::steady_clock::now();
        clock_ = [origin] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - origin).count(); };
    }
    start_ = clock_();
}

bool ProgressBar::stdoutIsTerminal() {
    return isatty(fileno(stdout)) == 1;
}

double ProgressBar::fractionDone() const {
    return std::clamp(done_ / total_, 0.0, 1.0);
}

double ProgressBar::elapsedSeconds() const {
    return clock_() - start_;
}

double ProgressBar::etaSeconds() const {
    const double f = fractionDone();
    if (f <= 0.0) return -1.0;
    return elapsedSeconds() * (1.0 - f) / f;
}

std::string ProgressBar::formatDuration(double seconds) {
    const long s = std::lround(std::max(0.0, seconds));
    char buffer[32];
    if (s >= 3600)
        std::snprintf(buffer, sizeof buffer, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
    else if (s >= 60)
        std::snprintf(buffer, sizeof buffer, "%ldm%02lds", s / 60, s % 60);
    else
        std::snprintf(buffer, sizeof buffer, "%lds", s);
    return buffer;
}

void ProgressBar::step(const std::string& label) {
    label_ = label;
    if (interactive_) {
        draw();
        return;
    }
    char percent[16];
    std::snprintf(percent, sizeof percent, "[%3d%%] ", static_cast<int>(std::floor(100.0 * fractionDone())));
    out_ << percent << label << std::endl;
}

void ProgressBar::advance(double work) {
    done_ += std::max(0.0, work);
    if (!interactive_) return;
    // Redraw at most ten times a second.
    const double now = clock_();
    if (lastDraw_ >= 0.0 && now - lastDraw_ < 0.1 && fractionDone() < 1.0) return;
    draw();
}

void ProgressBar::note(const std::string& line) {
    clearLine();
    out_ << line << std::endl;
    if (interactive_ && drawn_) draw();
}

void ProgressBar::finish() {
    clearLine();
    drawn_ = false;
}

void ProgressBar::clearLine() {
    if (interactive_ && drawn_) out_ << "\r\033[K" << std::flush;
}

void ProgressBar::draw() {
    constexpr int kWidth = 30;
    const double f = fractionDone();
    const int filled = static_cast<int>(std::lround(f * kWidth));
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    const double eta = etaSeconds();
    char head[64];
    std::snprintf(head, sizeof head, "[%s] %3d%% ", bar.c_str(), static_cast<int>(std::floor(100.0 * f)));
    std::string text = std::string(head) + "elapsed " + formatDuration(elapsedSeconds()) + ", ETA " +
                       (eta < 0.0 ? std::string("--") : formatDuration(eta)) + "  " + label_;
    if (text.size() > 110) text.resize(110);
    out_ << "\r\033[K" << text << std::flush;
    lastDraw_ = clock_();
    drawn_ = true;
}

}  // namespace raycache
