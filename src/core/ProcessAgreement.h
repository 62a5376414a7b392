#pragma once
// Steps that every process of a job runs and that may fail on some of them
// only (a scene file missing on one node): the processes agree on the
// outcome, so they all stop together instead of some waiting forever in the
// next exchange.
#include <functional>
#include <stdexcept>
#include <string>

#include "core/ProcessGroup.h"

namespace raycache {

// Thrown on every process when `step` failed on at least one: the message
// of the lowest failing process, prefixed with which process it was.
class ProcessGroupFailure : public std::runtime_error {
public:
    ProcessGroupFailure(const std::string& what, int exitCode) : std::runtime_error(what), exitCode_(exitCode) {}
    // 2 when the failing process's error was an InputError, else 1.
    int exitCode() const { return exitCode_; }

private:
    int exitCode_;
};

// Runs `step`; collective. With one process its exceptions pass unchanged;
// with several, an exception on any process becomes a ProcessGroupFailure
// on every process ("process 2 of 3: <what>", or just <what> when every
// process failed with the same message).
void runOnEveryProcess(const ProcessGroup& group, const std::function<void()>& step);

}  // namespace raycache
