// Whether this test program runs under ThreadSanitizer (scripts/hardening.sh). A few tests that
// repeat one single-threaded operation hundreds of times (every byte of a file changed, hundreds
// of random op sequences) run a share of those repetitions there: TSan looks for races, which
// the first repetitions reach as well as the last, and runs that code 5-15 times slower. The
// Release and ASan runs still run every repetition.
#pragma once

namespace faultline::test {

#if defined(__SANITIZE_THREAD__)
inline constexpr bool kUnderThreadSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
inline constexpr bool kUnderThreadSanitizer = true;
#else
inline constexpr bool kUnderThreadSanitizer = false;
#endif
#else
inline constexpr bool kUnderThreadSanitizer = false;
#endif

// The same for AddressSanitizer: there the longest test (300 random op sequences) took 89 s of
// the cold test command's 40 minutes; a share of them finds what all of them find.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif

} // namespace faultline::test
