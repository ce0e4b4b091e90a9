// Whether the test program (and so the brume and brume-vdb-read it runs from the same build) was
// built with AddressSanitizer (scripts/test --sanitize, docs/reliability.md "Sanitizers"). Kept out
// of test_support.h, which every test includes: only the tests that must know include this.
#pragma once

namespace brume::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAsanBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAsanBuild = true;
#else
inline constexpr bool kAsanBuild = false;
#endif
#else
inline constexpr bool kAsanBuild = false;
#endif

}  // namespace brume::test
