#include "bench/cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <iostream>

#include <fmt/format.h>

namespace ocpb {

std::string ClockText(double seconds) {
  const int s = static_cast<int>(seconds + 0.5);
  return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}

RunProgress::RunProgress(size_t total, int jobs, std::string prefix, double interval_seconds)
    : total_(total),
      jobs_(jobs),
      prefix_(std::move(prefix)),
      interval_(interval_seconds),
      tty_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {
  if (tty_ && total_ > 0) Show(std::min<size_t>(total_, static_cast<size_t>(jobs_)), "");
}

double RunProgress::Elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void RunProgress::CaseDone(size_t running, const std::string& last) {
  ++done_;
  last_ = last;
  const double now = Elapsed();
  if (tty_ || now - last_shown_ >= interval_) {
    Show(running, last);
    last_shown_ = now;
  }
}

void RunProgress::Tick(size_t running) {
  const double now = Elapsed();
  if (now - last_shown_ >= (tty_ ? 1.0 : std::max(interval_, 60.0))) {
    Show(running, last_);
    last_shown_ = now;
  }
}

void RunProgress::Show(size_t running, const std::string& last) {
  const double elapsed = Elapsed();
  // Throughput so far, so that N workers are counted: the rest at the rate the run has had.
  const std::string remaining =
      done_ > 0 ? ClockText(elapsed / static_cast<double>(done_) * (total_ - done_)) : "?";
  const std::string text = fmt::format(
      "{}{} of {} cases done, {} running ({} {})  elapsed {}  "
      "remaining ~{}{}",
      prefix_,
      done_,
      total_,
      running,
      jobs_,
      jobs_ == 1 ? "process" : "worker processes",
      ClockText(elapsed),
      remaining,
      last.empty() ? "" : "  last: " + last);
  if (tty_) {
    std::cerr << "\r\033[K" << text << std::flush;
  } else {
    std::cerr << "ocpbench: " << text << "\n";
  }
}

void RunProgress::Finish() {
  if (tty_) std::cerr << "\r\033[K" << std::flush;
}

}  // namespace ocpb
