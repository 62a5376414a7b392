#pragma once
// Whether this test program was built with AddressSanitizer or
// ThreadSanitizer (the asan and tsan presets). A test whose oracle costs
// far more than the code it checks (brute force over every triangle for
// every ray) may run a smaller case there: the sanitizers look for memory,
// undefined-behaviour and race errors, which the same code paths show on the
// smaller case, and the release run keeps the full one (docs/testing.md).

namespace raycache::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kUnderSanitizers = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kUnderSanitizers = true;
#else
inline constexpr bool kUnderSanitizers = false;
#endif
#else
inline constexpr bool kUnderSanitizers = false;
#endif

}  // namespace raycache::test
