// The progress of `ocpbench run` on stderr: on a terminal, one line rewritten in place; in a
// file (a Slurm task's output, a log), one plain line at most every `interval_seconds`. It counts
// every case of the run, whichever worker process ran it. While long cases run, Tick keeps its
// "elapsed" current: every second on a terminal, every minute in a file.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace ocpb {

class RunProgress {
 public:
  /// `total`: cases this run has to do; `prefix`: shown first ("shard 2/8: "), may be empty.
  RunProgress(size_t total, int jobs, std::string prefix, double interval_seconds = 10);

  /// A case finished (`last`: "problem / solver"); `running` cases are still running.
  void CaseDone(size_t running, const std::string& last);
  /// No case finished lately (`running` still running): shows the line again when it is older
  /// than a second (terminal) or a minute (file, and never more often than `interval_seconds`).
  void Tick(size_t running);
  /// Clears the terminal line.
  void Finish();
  /// Seconds since the start.
  double Elapsed() const;

 private:
  void Show(size_t running, const std::string& last);

  size_t total_, done_ = 0;
  int jobs_;
  std::string prefix_;
  double interval_;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  double last_shown_ = 0;
  std::string last_;  // the last case that finished
};

/// H:MM:SS.
std::string ClockText(double seconds);

}  // namespace ocpb
