#pragma once
// Progress of a long run. On a terminal: one bar redrawn in place, with the
// share done, the current step and an estimate of the time left. Otherwise
// (a pipe, a log file, CI): plain lines, one per step, no control characters.
#include <chrono>
#include <functional>
#include <iosfwd>
#include <string>

namespace raycache {

class ProgressBar {
public:
    using Clock = std::function<double()>;  // seconds since an arbitrary origin

    // `totalWork` is in any unit the caller advances by (e.g. megapixels
    // rendered); `interactive` selects the bar (see isTerminal). The clock
    // is injectable for tests; by default a steady clock.
    ProgressBar(std::ostream& out, bool interactive, double totalWork, Clock clock = {});

    // True when the standard output is a terminal.
    static bool stdoutIsTerminal();

    // Starts a step: on a terminal the bar shows `label`; otherwise prints
    // "[ 42%] label" on a line of its own.
    void step(const std::string& label);
    // Adds done work and redraws the bar (terminal only).
    void advance(double work);
    // Prints a line of output without breaking the bar.
    void note(const std::string& line);
    // Clears the bar (terminal) so later output starts on a clean line.
    void finish();

    double fractionDone() const;
    double elapsedSeconds() const;
    // Seconds left, extrapolated from the rate so far; negative while unknown.
    double etaSeconds() const;
    // "1m05s", "42s", "2h03m".
    static std::string formatDuration(double seconds);

private:
    void draw();
    void clearLine();

    std::ostream& out_;
    bool interactive_;
    double total_;
    double done_ = 0.0;
    Clock clock_;
    double start_;
    double lastDraw_ = -1.0;
    std::string label_;
    bool drawn_ = false;
};

}  // namespace raycache
