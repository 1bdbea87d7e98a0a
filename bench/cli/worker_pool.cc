#include "bench/cli/worker_pool.h"

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

namespace ocpb {
namespace {

// How long the pool waits for a result before it calls WorkerPoolTasks::idle.
constexpr int kIdleMilliseconds = 1000;

// Sends all of `text` (MSG_NOSIGNAL: a dead peer is an error, not SIGPIPE). False on failure.
bool SendAll(int fd, const std::string& text) {
  size_t sent = 0;
  while (sent < text.size()) {
    const ssize_t n = ::send(fd, text.data() + sent, text.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    sent += static_cast<size_t>(n);
  }
  return true;
}

// One line from `fd` into `line` (without '\n'); false at end of file or on an error.
bool ReceiveLine(int fd, std::string* buffer, std::string* line) {
  for (;;) {
    const size_t nl = buffer->find('\n');
    if (nl != std::string::npos) {
      *line = buffer->substr(0, nl);
      buffer->erase(0, nl + 1);
      return true;
    }
    char chunk[4096];
    const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    buffer->append(chunk, static_cast<size_t>(n));
  }
}

// The worker's side: "TASK\n" in, "TASK RESULT\n" out, until "quit" or end of file.
[[noreturn]] void WorkerMain(int fd, const WorkerPoolTasks& tasks) {
  std::string buffer, line;
  while (ReceiveLine(fd, &buffer, &line)) {
    if (line == "quit") break;
    const size_t task = std::stoul(line);
    std::string result;
    try {
      result = tasks.run(task);
    } catch (const std::exception& e) {
      result = tasks.died(task, std::string("threw: ") + e.what());
    }
    if (!SendAll(fd, fmt::format("{} {}\n", task, result))) break;
  }
  std::fflush(nullptr);
  ::_exit(0);  // no static destructors or exit handlers of the parent's state in a worker
}

struct Worker {
  pid_t pid = -1;
  int fd = -1;
  std::string buffer;
  std::optional<size_t> task;  // the task it runs
};

std::string DescribeExit(int status) {
  if (WIFSIGNALED(status)) {
    return fmt::format("killed by signal {} ({})", WTERMSIG(status), ::strsignal(WTERMSIG(status)));
  }
  if (WIFEXITED(status)) return fmt::format("exited with code {}", WEXITSTATUS(status));
  return "ended";
}

class Pool {
 public:
  Pool(const WorkerPoolTasks& tasks, int jobs) : tasks_(tasks), jobs_(jobs) {}
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;
  // Leaving early (a result that could not be written throws out of `done`): no worker stays.
  ~Pool() {
    for (Worker& w : workers_) {
      if (w.fd < 0) continue;
      ::close(w.fd);
      ::kill(w.pid, SIGKILL);
      while (::waitpid(w.pid, nullptr, 0) < 0 && errno == EINTR) {
      }
    }
  }

  void Run() {
    const size_t wanted = std::min(static_cast<size_t>(jobs_), tasks_.count);
    for (size_t w = 0; w < wanted; ++w) {
      workers_.push_back(Start());
      Assign(&workers_.back());
    }
    while (finished_ < tasks_.count) {
      std::vector<pollfd> fds;
      for (const Worker& w : workers_) fds.push_back({w.fd, POLLIN, 0});
      const int ready = ::poll(fds.data(), fds.size(), tasks_.idle ? kIdleMilliseconds : -1);
      if (ready < 0) {
        if (errno == EINTR) continue;
        throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
      }
      if (ready == 0) {
        tasks_.idle(running_);
        continue;
      }
      for (size_t i = 0; i < fds.size(); ++i) {
        if (fds[i].revents != 0) Serve(i);
      }
      std::erase_if(workers_, [](const Worker& w) { return w.fd < 0; });
      // Replace the workers that died while tasks remain (not inside Serve: that would move
      // the workers it is serving).
      for (; replacements_ > 0; --replacements_) {
        if (next_ >= tasks_.count) continue;
        workers_.push_back(Start());
        Assign(&workers_.back());
      }
    }
    for (Worker& w : workers_) Stop(&w);
  }

 private:
  Worker Start() {
    int sv[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM, 0, sv) != 0) {
      throw std::runtime_error(std::string("socketpair: ") + std::strerror(errno));
    }
    std::fflush(nullptr);  // nothing buffered is written twice
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) {
      ::close(sv[0]);
      ::close(sv[1]);
      throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    }
    if (pid == 0) {
      ::close(sv[0]);
      // Without the other workers' sockets a worker sees the end of its own when we go.
      for (const Worker& w : workers_) ::close(w.fd);
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(0);
      WorkerMain(sv[1], tasks_);
    }
    ::close(sv[1]);
    Worker w;
    w.pid = pid;
    w.fd = sv[0];
    return w;
  }

  // Gives the worker the next task, or tells it to quit when none is left.
  void Assign(Worker* w) {
    if (next_ < tasks_.count) {
      w->task = next_++;
      ++running_;
      if (!SendAll(w->fd, fmt::format("{}\n", *w->task))) Lost(w);
    } else {
      SendAll(w->fd, "quit\n");
    }
  }

  void Serve(size_t index) {
    Worker* w = &workers_[index];
    std::string line;
    char chunk[65536];
    ssize_t n;
    do {
      n = ::recv(w->fd, chunk, sizeof chunk, 0);
    } while (n < 0 && errno == EINTR);
    if (n <= 0) {
      Lost(w);
      return;
    }
    w->buffer.append(chunk, static_cast<size_t>(n));
    for (size_t nl = w->buffer.find('\n'); nl != std::string::npos; nl = w->buffer.find('\n')) {
      line = w->buffer.substr(0, nl);
      w->buffer.erase(0, nl + 1);
      const size_t space = line.find(' ');
      if (!w->task || space == std::string::npos ||
          line.substr(0, space) != std::to_string(*w->task)) {
        throw std::runtime_error("worker process " + std::to_string(w->pid) +
                                 " answered out of turn");
      }
      const size_t task = *w->task;
      w->task.reset();
      --running_;
      ++finished_;
      tasks_.done(task, line.substr(space + 1), running_);
      Assign(w);
      if (w->fd < 0) return;  // it died before taking the next task
    }
  }

  // The worker's socket ended: it exited or died. Its task, if any, gets a `died` result and a
  // new worker takes over while tasks remain.
  void Lost(Worker* w) {
    ::close(w->fd);
    w->fd = -1;
    int status = 0;
    while (::waitpid(w->pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!w->task) return;
    const size_t task = *w->task;
    w->task.reset();
    --running_;
    ++finished_;
    tasks_.done(task, tasks_.died(task, DescribeExit(status)), running_);
    ++replacements_;
  }

  void Stop(Worker* w) {
    if (w->fd < 0) return;
    SendAll(w->fd, "quit\n");
    ::close(w->fd);
    w->fd = -1;
    int status = 0;
    while (::waitpid(w->pid, &status, 0) < 0 && errno == EINTR) {
    }
  }

  const WorkerPoolTasks& tasks_;
  const int jobs_;
  std::vector<Worker> workers_;
  size_t next_ = 0, running_ = 0, finished_ = 0;
  size_t replacements_ = 0;  // workers lost while running a task, to be replaced
};

}  // namespace

void RunInWorkerProcesses(const WorkerPoolTasks& tasks, int jobs) {
  if (tasks.count == 0) return;
  Pool(tasks, jobs < 1 ? 1 : jobs).Run();
}

}  // namespace ocpb
