// What the tests allow for AddressSanitizer's build (scripts/test.sh's sanitizer pass: Debug,
// -O1, every memory access checked): the factor by which a time bound is widened there.
#pragma once

namespace luz::test {

/// How much longer than in Release the code under test may take: 10 in a build under ASan.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr double kSlowdown = 10;
#else
inline constexpr double kSlowdown = 1;
#endif

}  // namespace luz::test
