#include "tests/cli/run_ocpbench.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace ocpb::testing {
namespace {

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

pid_t Spawn(const std::vector<std::string>& args,
            const std::string& cwd,
            const std::string& out,
            const std::string& err) {
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(127);
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fo, STDOUT_FILENO);
    ::dup2(fe, STDERR_FILENO);
    const int fi = ::open("/dev/null", O_RDONLY);
    ::dup2(fi, STDIN_FILENO);
    std::vector<char*> argv;
    std::string exe = OCPBENCH_EXE;
    argv.push_back(exe.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

// Copies the records the run just wrote (a --json file; the records files of the --out or merge
// directory) to $OCPB_RECORD_SNAPSHOTS/<n>/, for the records_match_schema test that validates every
// record the tests made ocpbench write against results/record.schema.json. A copy, so that a test
// that damages a records file afterwards (resume tests) checks what ocpbench wrote, not what the
// test did to it. Nothing when the variable is unset (a test binary run by hand).
void SnapshotRecords(const std::vector<std::string>& args, const std::string& cwd) {
  const char* root = std::getenv("OCPB_RECORD_SNAPSHOTS");
  if (root == nullptr || args.empty()) return;
  // compare --json writes a comparison, not a record, and reads the records it is given.
  if (args[0] == "compare") return;
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  auto in_cwd = [&cwd](const std::string& p) {
    return cwd.empty() || fs::path(p).is_absolute() ? fs::path(p) : fs::path(cwd) / p;
  };
  for (size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] == "--json") files.push_back(in_cwd(args[i + 1]));
  }
  std::vector<fs::path> dirs;
  for (size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[0] == "run" && args[i] == "--out") dirs.push_back(in_cwd(args[i + 1]));
  }
  if (args[0] == "merge" && args.size() >= 2) dirs.push_back(in_cwd(args[1]));
  std::error_code ec;
  for (const fs::path& d : dirs) {
    for (const auto& e : fs::directory_iterator(d, ec)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("records", 0) == 0 && e.path().extension() == ".jsonl") {
        files.push_back(e.path());
      }
    }
  }
  static int counter = 0;
  const fs::path target =
      fs::path(root) / (std::to_string(::getpid()) + "-" + std::to_string(counter++));
  for (const fs::path& f : files) {
    if (!fs::is_regular_file(f, ec)) continue;
    fs::create_directories(target, ec);
    fs::copy_file(f, target / f.filename(), fs::copy_options::overwrite_existing, ec);
  }
}

}  // namespace

std::string FreshDirectory(const std::string& name) {
  const char* tmp = std::getenv("TMPDIR");
  std::filesystem::path dir = std::filesystem::path(tmp ? tmp : "/tmp") /
                              ("ocpbench-test-" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

ProgramRun RunOcpbenchProgram(const std::vector<std::string>& args, const std::string& cwd) {
  const std::string base = FreshDirectory("run-io");
  const std::string out = base + "/out", err = base + "/err";
  const pid_t pid = Spawn(args, cwd, out, err);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ProgramRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.out = Slurp(out);
  run.err = Slurp(err);
  // Exit 2 writes nothing (invalid input): whatever is there is the test's own input.
  if (run.exit_code != 2) SnapshotRecords(args, cwd);
  return run;
}

int StartOcpbenchProgram(const std::vector<std::string>& args, const std::string& cwd) {
  return Spawn(args, cwd, cwd + "/bg.out", cwd + "/bg.err");
}

std::vector<std::string> Plus(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const std::vector<std::string>& QuickIpoptSolve() {
  static const std::vector<std::string> args = {"solve",
                                                "--problem",
                                                "double-integrator",
                                                "--solver",
                                                "ipopt",
                                                "--transcription",
                                                "euler",
                                                "--N",
                                                "10"};
  return args;
}

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string ReadText(const std::string& path) { return Slurp(path); }

bool OneErrorLine(const ProgramRun& run) {
  return run.err.rfind("ocpbench: error: ", 0) == 0 &&
         std::count(run.err.begin(), run.err.end(), '\n') == 1;
}

std::map<std::string, std::string> SnapshotFiles(const std::string& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_symlink() || !e.is_regular_file()) continue;
    if (e.path().filename() == ".ocpbench.lock") continue;
    out[std::filesystem::relative(e.path(), dir).string()] = ReadText(e.path().string());
  }
  return out;
}

}  // namespace ocpb::testing
