#pragma once
// Where the checkout and the rcsim executable are, for the tests, harnesses and benchmarks: every
// one of their sources sees this header first (-include, cmake/test_paths.cmake). The paths
// themselves are compiled into one generated source of the build tree, never into a compile flag:
// a flag holding an absolute path differs from clone to clone, and every test would miss the
// compiler cache of an earlier clone (docs/ci.md).
namespace rcsim::testing {
const char* source_dir();    // the checkout's root, absolute
const char* rcsim_binary();  // the rcsim executable of this build tree, absolute
const char* rcsim_killable_binary();  // the same with the kill hook (hooks/killable_main.cpp)
}  // namespace rcsim::testing

#define RCSIM_SOURCE_DIR (::rcsim::testing::source_dir())
#define RCSIM_BINARY (::rcsim::testing::rcsim_binary())
#define RCSIM_KILLABLE_BINARY (::rcsim::testing::rcsim_killable_binary())
