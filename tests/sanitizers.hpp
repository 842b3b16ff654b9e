#pragma once
// Whether this build runs under a sanitizer, for GCC (__SANITIZE_ADDRESS__, __SANITIZE_THREAD__)
// and clang (__has_feature), which the sanitizer tree (scripts/build-sanitize.sh) is built with:
// RCSIM_UNDER_ASAN and RCSIM_UNDER_SANITIZER are 1 or 0.
#if defined(__SANITIZE_ADDRESS__)
#define RCSIM_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RCSIM_UNDER_ASAN 1
#endif
#endif
#ifndef RCSIM_UNDER_ASAN
#define RCSIM_UNDER_ASAN 0
#endif

#if defined(__SANITIZE_THREAD__)
#define RCSIM_UNDER_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define RCSIM_UNDER_TSAN 1
#endif
#endif
#ifndef RCSIM_UNDER_TSAN
#define RCSIM_UNDER_TSAN 0
#endif

#define RCSIM_UNDER_SANITIZER (RCSIM_UNDER_ASAN || RCSIM_UNDER_TSAN)
