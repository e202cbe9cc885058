#pragma once

// Whether this test program is built with AddressSanitizer (the asan preset): its code, and the
// aesim program it runs, then take several times as long and reserve terabytes of address space.
// GCC says so with a macro, clang through __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define AESIM_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define AESIM_TEST_UNDER_ASAN 1
#endif
#endif

namespace aesim::testing {
#ifdef AESIM_TEST_UNDER_ASAN
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif
}  // namespace aesim::testing
