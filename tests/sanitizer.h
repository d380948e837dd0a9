// What the tests allow for AddressSanitizer's build (scripts/test.sh's sanitizer pass: Debug,
// -O1, every memory access checked): the factor by which a time bound is widened there, and the
// tests of speed that run in Release only.
#pragma once

namespace luz::test {

/// How much longer than in Release the code under test may take: 10 in a build under ASan.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr double kSlowdown = 10;
#else
inline constexpr double kSlowdown = 1;
#endif

}  // namespace luz::test

/// Opens a test whose subject is speed (a large input in seconds, a time bound): under the
/// sanitizers it would time them, so it runs in the Release pass only. Its input's other
/// checks have smaller cases that run in both passes.
#if defined(__SANITIZE_ADDRESS__)
#define LUZ_SPEED_TEST() GTEST_SKIP() << "a test of speed: it runs in the Release build"
#else
#define LUZ_SPEED_TEST() static_cast<void>(0)
#endif
