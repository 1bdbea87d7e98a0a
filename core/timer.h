// CPU and wall clocks for solver timing.
#pragma once

#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <utility>

namespace ocpb {

namespace detail {
/// The clock CpuSeconds() reads on this thread instead of the process CPU clock (ScopedCpuClock).
inline const std::function<double()>*& CpuClockOverride() {
  static thread_local const std::function<double()>* clock = nullptr;
  return clock;
}
}  // namespace detail

/// Process CPU time (all threads) in seconds; on a thread with a ScopedCpuClock, its clock.
inline double CpuSeconds() {
  if (const std::function<double()>* clock = detail::CpuClockOverride()) return (*clock)();
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Tests: while it lives, CpuSeconds() on the thread that made it returns `clock()` (restored on
/// destruction; scopes nest). A clock driven by a work counter makes the tests of CPU limits
/// deterministic: they can assert that a solve stopped at the first check after its limit.
class ScopedCpuClock {
 public:
  explicit ScopedCpuClock(std::function<double()> clock)
      : clock_(std::move(clock)), previous_(detail::CpuClockOverride()) {
    detail::CpuClockOverride() = &clock_;
  }
  ~ScopedCpuClock() { detail::CpuClockOverride() = previous_; }
  ScopedCpuClock(const ScopedCpuClock&) = delete;
  ScopedCpuClock& operator=(const ScopedCpuClock&) = delete;

 private:
  std::function<double()> clock_;
  const std::function<double()>* previous_;
};

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

/// A CPU limit on a Stopwatch: Reached() once clock->cpu() >= seconds (never for an infinite
/// limit or without a clock, and then without reading the clock).
struct CpuLimit {
  const Stopwatch* clock = nullptr;
  double seconds = INFINITY;
  bool Reached() const { return clock && std::isfinite(seconds) && clock->cpu() >= seconds; }
};

}  // namespace ocpb
