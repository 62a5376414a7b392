#include "core/ProcessAgreement.h"

#include <algorithm>

#include "core/Errors.h"

namespace raycache {

void runOnEveryProcess(const ProcessGroup& group, const std::function<void()>& step) {
    if (group.size() == 1) {
        step();
        return;
    }
    // 0: succeeded, 1: runtime failure, 2: input error (the CLI's exit codes).
    std::uint8_t outcome = 0;
    std::string message;
    try {
        step();
    } catch (const InputError& e) {
        outcome = 2;
        message = e.what();
    } catch (const std::exception& e) {
        outcome = 1;
        message = e.what();
    }
    Bytes mine;
    appendBytes(mine, outcome);
    appendBytes(mine, std::span<const char>(message.data(), message.size()));
    const std::vector<Bytes> all = group.allGather(mine);
    // Bad options fail the same way everywhere: then no process is named.
    const bool everyProcessAlike = std::all_of(all.begin(), all.end(), [&](const Bytes& b) { return b == all[0]; });
    for (std::size_t r = 0; r < all.size(); ++r) {
        const auto code = static_cast<std::uint8_t>(all[r].at(0));
        if (code == 0) continue;
        const std::string what(reinterpret_cast<const char*>(all[r].data()) + 1, all[r].size() - 1);
        if (everyProcessAlike) throw ProcessGroupFailure(what, code);
        throw ProcessGroupFailure("process " + std::to_string(r) + " of " + std::to_string(all.size()) + ": " + what,
                                  code);
    }
}

}  // namespace raycache
