// Tasks run in worker processes on one machine (`ocpbench run --jobs N`). Processes, not
// threads: a case's CPU time is its process's (CLOCK_PROCESS_CPUTIME_ID), so each worker runs
// one case at a time and every case's CPU time stays its own; a case that crashes its process
// takes only that case with it.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace ocpb {

struct WorkerPoolTasks {
  size_t count = 0;  ///< tasks 0 .. count - 1, handed out in this order
  /// Runs task i in a worker process and returns its result as one line (no '\n').
  std::function<std::string(size_t)> run;
  /// Called in this process with each result, in completion order; `running` is the number of
  /// tasks still running in workers.
  std::function<void(size_t task, std::string line, size_t running)> done;
  /// The result line of a task whose worker died while running it (`why`: "killed by signal
  /// 11", "exited with code 3"); it is passed to `done` like any other.
  std::function<std::string(size_t task, const std::string& why)> died;
  /// Optional: called in this process about once a second while no result arrives (`running`
  /// tasks in workers), so that a progress line keeps time while long tasks run.
  std::function<void(size_t running)> idle;
};

/// Runs every task in `jobs` worker processes (at most `count`), forked from this one (which
/// must not hold threads that the workers would need), handing each idle worker the next task.
/// A worker that dies is replaced while tasks remain. Workers die with this process (a killed
/// run leaves none behind). Returns when every task's result went through `done`. Throws
/// std::runtime_error when no worker process can be started.
void RunInWorkerProcesses(const WorkerPoolTasks& tasks, int jobs);

}  // namespace ocpb
