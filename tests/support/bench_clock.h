// Clocks of the benchmarks (tests/bench): wall seconds since a time point,
// and CPU seconds of the whole process or of the calling thread -- figures
// that other jobs on a shared machine disturb less than the wall clock.
#pragma once

#include <chrono>
#include <ctime>

namespace hull::bench {

inline double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

inline double CpuSecondsOf(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// All threads of the process.
inline double CpuSeconds() { return CpuSecondsOf(CLOCK_PROCESS_CPUTIME_ID); }
// The calling thread only.
inline double ThreadCpuSeconds() { return CpuSecondsOf(CLOCK_THREAD_CPUTIME_ID); }

}  // namespace hull::bench
