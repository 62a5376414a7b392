#include "core/ProcessAgreement.h"

#include <algorithm>
#include <stdexcept>

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
    GatheredBytes all;
    group.allGather(mine, all);
    const auto same = [](std::span<const std::byte> a, std::span<const std::byte> b) {
        return std::equal(a.begin(), a.end(), b.begin(), b.end());
    };
    // Bad options fail the same way everywhere: then no process is named.
    bool everyProcessAlike = true;
    for (std::size_t r = 1; r < all.count(); ++r) everyProcessAlike = everyProcessAlike && same(all.of(r), all.of(0));
    for (std::size_t r = 0; r < all.count(); ++r) {
        const std::span<const std::byte> part = all.of(r);
        if (part.empty()) throw std::out_of_range("empty process message");
        const auto code = static_cast<std::uint8_t>(part[0]);
        if (code == 0) continue;
        const std::string what(reinterpret_cast<const char*>(part.data()) + 1, part.size() - 1);
        if (everyProcessAlike) throw ProcessGroupFailure(what, code);
        throw ProcessGroupFailure("process " + std::to_string(r) + " of " + std::to_string(all.count()) + ": " + what,
                                  code);
    }
}

}  // namespace raycache
