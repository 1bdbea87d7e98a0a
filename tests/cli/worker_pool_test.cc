// Worker processes of `run --jobs`: every task runs once in another process, results come back
// whole, a worker that dies costs only its task (reported) and is replaced.
#include <signal.h>
#include <unistd.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/cli/worker_pool.h"

namespace ocpb {
namespace {

TEST(WorkerPool, RunsEveryTaskOnceInOtherProcesses) {
  const pid_t self = ::getpid();
  std::map<size_t, std::string> results;
  std::set<std::string> pids;
  size_t most_running = 0;
  WorkerPoolTasks tasks;
  tasks.count = 25;
  // A long line (longer than one socket read) checks that results arrive whole.
  tasks.run = [](size_t i) {
    return std::to_string(::getpid()) + " " + std::to_string(i * i) + " " +
           std::string(100000 + i, 'x');
  };
  tasks.died = [](size_t, const std::string& why) { return "died " + why; };
  tasks.done = [&](size_t i, std::string line, size_t running) {
    EXPECT_FALSE(results.count(i)) << "task " << i << " reported twice";
    most_running = std::max(most_running, running);
    pids.insert(line.substr(0, line.find(' ')));
    results[i] = std::move(line);
  };
  RunInWorkerProcesses(tasks, 3);
  ASSERT_EQ(results.size(), 25u);
  for (const auto& [i, line] : results) {
    const size_t a = line.find(' '), b = line.find(' ', a + 1);
    EXPECT_EQ(line.substr(a + 1, b - a - 1), std::to_string(i * i));
    EXPECT_EQ(line.size() - b - 1, 100000 + i);
  }
  EXPECT_FALSE(pids.count(std::to_string(self)));
  EXPECT_LE(pids.size(), 3u);
  EXPECT_GE(pids.size(), 1u);
  EXPECT_LE(most_running, 2u);
}

// While a task runs longer than a second, the pool calls `idle` with the tasks still running
// (what keeps `run`'s progress line current); a pool without `idle` waits as before.
TEST(WorkerPool, CallsIdleWhileATaskRuns) {
  WorkerPoolTasks tasks;
  tasks.count = 1;
  tasks.run = [](size_t) {
    ::usleep(1500 * 1000);
    return std::string("done");
  };
  tasks.died = [](size_t, const std::string& why) { return why; };
  std::string result;
  tasks.done = [&](size_t, std::string line, size_t) { result = std::move(line); };
  std::vector<size_t> idle_running;
  tasks.idle = [&](size_t running) { idle_running.push_back(running); };
  RunInWorkerProcesses(tasks, 1);
  EXPECT_EQ(result, "done");
  ASSERT_GE(idle_running.size(), 1u);
  for (size_t running : idle_running) EXPECT_EQ(running, 1u);
}

TEST(WorkerPool, AWorkerThatDiesCostsOnlyItsTask) {
  std::map<size_t, std::string> results;
  WorkerPoolTasks tasks;
  tasks.count = 8;
  tasks.run = [](size_t i) -> std::string {
    if (i == 2) ::_exit(7);
    if (i == 5) ::raise(SIGKILL);
    return "ok " + std::to_string(i);
  };
  tasks.died = [](size_t i, const std::string& why) {
    return "task " + std::to_string(i) + " " + why;
  };
  tasks.done = [&](size_t i, std::string line, size_t) { results[i] = std::move(line); };
  RunInWorkerProcesses(tasks, 2);
  ASSERT_EQ(results.size(), 8u);
  EXPECT_EQ(results[2], "task 2 exited with code 7");
  EXPECT_EQ(results[5].rfind("task 5 killed by signal 9", 0), 0u) << results[5];
  for (size_t i : {0u, 1u, 3u, 4u, 6u, 7u}) EXPECT_EQ(results[i], "ok " + std::to_string(i));
}

TEST(WorkerPool, MoreWorkersThanTasksAndNoTasks) {
  size_t done = 0;
  WorkerPoolTasks tasks;
  tasks.count = 2;
  tasks.run = [](size_t i) { return std::to_string(i); };
  tasks.died = [](size_t, const std::string& why) { return why; };
  tasks.done = [&](size_t, std::string, size_t) { ++done; };
  RunInWorkerProcesses(tasks, 16);
  EXPECT_EQ(done, 2u);
  tasks.count = 0;
  RunInWorkerProcesses(tasks, 4);
  EXPECT_EQ(done, 2u);
}

}  // namespace
}  // namespace ocpb
