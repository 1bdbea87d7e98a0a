// CPU and wall clocks for solver timing.
#pragma once

#include <chrono>
#include <ctime>

namespace ocpb {

/// Process CPU time (all threads) in seconds.
inline double CpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Measures CPU and wall time from construction.
class Stopwatch {
 public:
  Stopwatch() : cpu0_(CpuSeconds()), wall0_(std::chrono::steady_clock::now()) {}
  double cpu() const { return CpuSeconds() - cpu0_; }
  double wall() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
  }

 private:
  double cpu0_;
  std::chrono::steady_clock::time_point wall0_;
};

}  // namespace ocpb
