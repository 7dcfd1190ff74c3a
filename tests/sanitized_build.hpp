#pragma once
// Whether this test binary runs under a sanitizer (ASan, TSan or UBSan).
// There the heaviest tests run fewer seeds, parts or lines: a sanitizer
// build proves the code paths are free of memory errors and undefined
// behaviour, which a few runs of a loop prove as well as all of them; the
// Release build keeps the full count and the statistical claims.
// GCC defines __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__ (the top
// CMakeLists.txt defines the first for clang too); clang answers
// __has_feature, UBSan included. GCC 12 cannot tell a UBSan-only build,
// which this project does not make.

namespace tnv::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(undefined_behavior_sanitizer)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif
#else
inline constexpr bool kSanitizedBuild = false;
#endif

}  // namespace tnv::test
