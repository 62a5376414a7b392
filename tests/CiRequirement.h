#pragma once
// Tests that need OpenGL or Xvfb skip, with the reason, on a developer machine
// that lacks them; on CI (the CI environment variable set, as CI services do)
// those are installed by scripts/install-deps.sh, so a missing one means the
// test silently stopped testing anything, and it fails instead.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string_view>

namespace raycache::test {

// CI=true (or any value other than empty, 0 or false).
inline bool runningInCi() {
    const char* value = std::getenv("CI");
    if (!value) return false;
    const std::string_view v(value);
    return !v.empty() && v != "0" && v != "false";
}

}  // namespace raycache::test

// Skips the current test with `message`, or fails it under CI. A statement;
// the switch keeps an enclosing if/else unambiguous, as gtest's own macros do.
#define RAYCACHE_SKIP_OR_FAIL_IN_CI(message)                           \
    switch (0)                                                         \
    case 0:                                                            \
    default:                                                           \
        if (::raycache::test::runningInCi())                           \
            GTEST_FAIL() << "required on CI (CI is set): " << message; \
        else                                                           \
            GTEST_SKIP() << message
