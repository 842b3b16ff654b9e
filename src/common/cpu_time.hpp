#pragma once
// CPU time of the calling thread, for speed figures that do not depend on other load on the machine.
#include <ctime>

namespace rcsim {

inline double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace rcsim
