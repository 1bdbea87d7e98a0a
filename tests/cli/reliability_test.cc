// End-to-end reliability at the edges: concurrent writers of one output folder, full disks,
// devices and links as output places, read-only places, and damaged or hostile input files.
#include <fcntl.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

// Cases of the double integrator by the Hamiltonian descent, one per seed.
std::string Suite(int seeds, int N, int iterations) {
  std::string list;
  for (int i = 1; i <= seeds; ++i) list += (i > 1 ? ", " : "") + std::to_string(i);
  return R"({"name": "edge", "groups": [{"problem": "double-integrator", "N": )" +
         std::to_string(N) + R"(, "seeds": [)" + list +
         R"(], "methods": [{"solver": "hamiltonian", "options": {"max_iterations": )" +
         std::to_string(iterations) + "}}]}]}";
}

// A suite whose first case runs long and whose others are quick: shard 0/2 holds the long one.
std::string LongFirstCase() {
  return R"({"name": "edge", "groups": [
    {"problem": "double-integrator", "N": 200000, "methods": [{"solver": "hamiltonian",
     "options": {"max_iterations": 100000}}]},
    {"problem": "double-integrator", "N": 20, "seeds": [1, 2, 3],
     "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 10}}]}]})";
}

using testing::OneErrorLine;

// Every line of a records file, each of which must be a whole JSON record.
std::vector<json> WholeRecords(const std::string& path) {
  std::vector<json> out;
  std::istringstream in(testing::ReadText(path));
  std::string line;
  while (std::getline(in, line)) out.push_back(json::parse(line));
  return out;
}

// Waits (at most 60 s) until a run has claimed `dir`: its lock file exists (the lock is taken
// right after the file is made), and a little longer.
void WaitForLock(const std::string& dir) {
  for (int i = 0; i < 6000 && !fs::exists(dir + "/.ocpbench.lock"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
}

bool StillRunning(int pid) { return ::waitpid(pid, nullptr, WNOHANG) == 0; }

void Stop(int pid) {
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
}

TEST(Reliability, ASecondWriterOfAnOutputFolderIsRefusedWithOneLine) {
  const std::string dir = testing::FreshDirectory("second-writer");
  testing::WriteText(dir + "/suite.json", LongFirstCase());
  const int pid = testing::StartOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir);
  WaitForLock(dir + "/out");
  ASSERT_TRUE(StillRunning(pid)) << testing::ReadText(dir + "/bg.err");
  const std::string busy = "another ocpbench (pid " + std::to_string(pid) + ") is writing there";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", "suite.json", "--out", "out"},
        {"run", "suite.json", "--out", "out", "--resume"},
        {"run", "suite.json", "--out", "out", "--shard", "1/2"}}) {
    const ProgramRun second = RunOcpbenchProgram(args, dir);
    EXPECT_EQ(second.exit_code, 2) << args[0] << ": " << second.err;
    EXPECT_TRUE(OneErrorLine(second)) << second.err;
    EXPECT_NE(second.err.find(busy), std::string::npos) << second.err;
  }
  EXPECT_TRUE(StillRunning(pid));
  Stop(pid);
  // A killed holder leaves no stale lock: the folder can be claimed at once.
  const ProgramRun after = RunOcpbenchProgram({"merge", "out"}, dir);
  EXPECT_EQ(after.exit_code, 2);
  EXPECT_NE(after.err.find("out has no shards.json"), std::string::npos) << after.err;
}

TEST(Reliability, ShardsRunSideBySideButNoShardTwiceAndNoMergeMeanwhile) {
  const std::string dir = testing::FreshDirectory("shards-side-by-side");
  testing::WriteText(dir + "/suite.json", LongFirstCase());
  const int pid =
      testing::StartOcpbenchProgram({"run", "suite.json", "--out", "out", "--shard", "1/2"}, dir);
  WaitForLock(dir + "/out");
  ASSERT_TRUE(StillRunning(pid)) << testing::ReadText(dir + "/bg.err");
  const ProgramRun other =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--shard", "2/2"}, dir);
  EXPECT_EQ(other.exit_code, 0) << other.err;
  EXPECT_EQ(WholeRecords(dir + "/out/records.shard-2-of-2.jsonl").size(), 2u);
  const ProgramRun same =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--shard", "1/2", "--resume"}, dir);
  EXPECT_EQ(same.exit_code, 2) << same.err;
  EXPECT_NE(same.err.find("is writing there"), std::string::npos) << same.err;
  const ProgramRun merge = RunOcpbenchProgram({"merge", "out"}, dir);
  EXPECT_EQ(merge.exit_code, 2) << merge.err;
  EXPECT_TRUE(OneErrorLine(merge)) << merge.err;
  EXPECT_NE(merge.err.find("is writing there"), std::string::npos) << merge.err;
  EXPECT_FALSE(fs::exists(dir + "/out/records.jsonl")) << "merge wrote nothing";
  Stop(pid);
}

// Runs ocpbench in `cwd` with a file-size limit (RLIMIT_FSIZE) of `bytes`.
ProgramRun RunWithFileSizeLimit(const std::vector<std::string>& args,
                                const std::string& cwd,
                                rlim_t bytes) {
  const std::string err = testing::FreshDirectory("limited-io") + "/err";
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(cwd.c_str()) != 0) ::_exit(127);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fe, STDERR_FILENO);
    const int fo = ::open("/dev/null", O_WRONLY);
    ::dup2(fo, STDOUT_FILENO);
    const rlimit limit{bytes, bytes};  // set after the error file is open
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
    std::vector<char*> argv;
    std::string exe = OCPBENCH_EXE;
    argv.push_back(exe.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ProgramRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.err = testing::ReadText(err);
  return run;
}

// After a failed append: exit 3 with one line, the file at its last whole record, and a
// --resume (with room again) that completes the suite with every case once.
void ExpectWholeRecordsAndResume(const ProgramRun& run,
                                 const std::string& dir,
                                 const std::string& out,
                                 const std::string& reason) {
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_TRUE(OneErrorLine(run)) << run.err;
  EXPECT_NE(run.err.find(reason + " (the file keeps its records up to the last whole one)"),
            std::string::npos)
      << run.err;
  const std::string records = dir + "/" + out + "/records.jsonl";
  const std::string text = testing::ReadText(records);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const size_t kept = WholeRecords(records).size();  // throws on a partial line
  EXPECT_GE(kept, 1u);
  EXPECT_LT(kept, 4u);
}

TEST(Reliability, AFileSizeLimitLeavesTheRecordsFileAtItsLastWholeRecord) {
  const std::string dir = testing::FreshDirectory("file-size-limit");
  testing::WriteText(dir + "/suite.json", Suite(4, 200, 20));
  const ProgramRun run =
      RunWithFileSizeLimit({"run", "suite.json", "--out", "out"}, dir, 60 * 1024);
  ExpectWholeRecordsAndResume(run, dir, "out", "File too large");
  const ProgramRun resumed =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  std::set<std::string> keys;
  for (const json& r : WholeRecords(dir + "/out/records.jsonl")) keys.insert(r["key"]);
  EXPECT_EQ(keys.size(), 4u);
  EXPECT_EQ(WholeRecords(dir + "/out/records.jsonl").size(), 4u);
}

// A small tmpfs (root only: mount(2)); nullptr-like "" when it cannot be made.
class SmallTmpfs {
 public:
  SmallTmpfs(const std::string& dir, const std::string& options) : dir_(dir) {
    fs::create_directories(dir);
    mounted_ = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) == 0;
  }
  ~SmallTmpfs() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  bool mounted() const { return mounted_; }

 private:
  std::string dir_;
  bool mounted_ = false;
};

TEST(Reliability, AFullDiskLeavesTheRecordsFileAtItsLastWholeRecord) {
  const std::string dir = testing::FreshDirectory("full-disk");
  const SmallTmpfs disk(dir + "/disk", "size=64k");
  if (!disk.mounted()) GTEST_SKIP() << "mounting a tmpfs needs root; the rlimit test covers it";
  testing::WriteText(dir + "/suite.json", Suite(4, 200, 20));
  const ProgramRun run = RunOcpbenchProgram({"run", "suite.json", "--out", "disk/out"}, dir);
  ExpectWholeRecordsAndResume(run, dir, "disk/out", "No space left on device");
}

TEST(Reliability, DevicesFifosAndLinksAreWrittenThroughNeverReplaced) {
  const std::string dir = testing::FreshDirectory("devices");
  const std::vector<std::string> solve = {
      "solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--N", "20"};
  auto with_json = [&](const std::string& path) {
    std::vector<std::string> a = solve;
    a.push_back("--json");
    a.push_back(path);
    return a;
  };
  // The common way to discard output.
  const ProgramRun null = RunOcpbenchProgram(with_json("/dev/null"), dir);
  EXPECT_EQ(null.exit_code, 0) << null.err;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // A private copy of /dev/null (root only), and a link to it: still a device and a link.
  if (::mknod((dir + "/null").c_str(), S_IFCHR | 0666, ::makedev(1, 3)) == 0) {
    EXPECT_EQ(RunOcpbenchProgram(with_json("null"), dir).exit_code, 0);
    EXPECT_TRUE(fs::is_character_file(dir + "/null"));
  }
  fs::create_symlink("/dev/null", dir + "/to-null");
  EXPECT_EQ(RunOcpbenchProgram(with_json("to-null"), dir).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(dir + "/to-null"));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // A link to a regular file: the file gets the record, the link stays.
  testing::WriteText(dir + "/target.json", "old");
  fs::create_symlink("target.json", dir + "/record.json");
  EXPECT_EQ(RunOcpbenchProgram(with_json("record.json"), dir).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(dir + "/record.json"));
  EXPECT_EQ(json::parse(testing::ReadText(dir + "/target.json"))["problem"], "double-integrator");
  // A link to nothing: refused before solving.
  fs::create_symlink("missing.json", dir + "/dangling.json");
  const ProgramRun dangling = RunOcpbenchProgram(with_json("dangling.json"), dir);
  EXPECT_EQ(dangling.exit_code, 2);
  EXPECT_TRUE(OneErrorLine(dangling)) << dangling.err;
  EXPECT_NE(dangling.err.find("is a symbolic link to nothing"), std::string::npos);
  EXPECT_TRUE(dangling.out.empty()) << "nothing was solved: " << dangling.out;
}

TEST(Reliability, AReadOnlyPlaceIsRefusedBeforeAnyWork) {
  const std::string dir = testing::FreshDirectory("read-only");
  const SmallTmpfs ro(dir + "/ro", "size=64k,mode=0755");
  if (ro.mounted()) {
    ASSERT_EQ(::mount(nullptr, (dir + "/ro").c_str(), nullptr, MS_REMOUNT | MS_RDONLY, nullptr), 0);
  } else {
    ASSERT_EQ(::chmod((dir + "/ro").c_str(), 0555), 0);  // not root: permissions suffice
  }
  testing::WriteText(dir + "/suite.json", Suite(1, 20, 5));
  const ProgramRun run = RunOcpbenchProgram({"run", "suite.json", "--out", "ro/out"}, dir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_TRUE(OneErrorLine(run)) << run.err;
  EXPECT_NE(run.err.find("--out ro/out: cannot create the folder"), std::string::npos) << run.err;
  const ProgramRun solve = RunOcpbenchProgram({"solve",
                                               "--problem",
                                               "double-integrator",
                                               "--solver",
                                               "hamiltonian",
                                               "--json",
                                               "ro/record.json"},
                                              dir);
  EXPECT_EQ(solve.exit_code, 2) << solve.err;
  EXPECT_NE(solve.err.find("--json ro/record.json: cannot create a file in ro"), std::string::npos)
      << solve.err;
  EXPECT_TRUE(solve.out.empty()) << "nothing was solved: " << solve.out;
}

// A records file read by --resume, and a shard file read by merge, damaged in the ways the
// issue names: every one an exit 2 naming the file and the line, never a crash.
TEST(Reliability, DamagedRecordsAndShardFilesNameTheFileTheLineAndTheField) {
  const std::string dir = testing::FreshDirectory("damaged-records");
  testing::WriteText(dir + "/suite.json", Suite(3, 20, 5));
  ASSERT_EQ(RunOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir).exit_code, 0);
  const std::vector<json> records = WholeRecords(dir + "/out/records.jsonl");
  ASSERT_EQ(records.size(), 3u);
  const std::string first = records[0].dump() + "\n";
  const std::string deep = "{\"key\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  json wrong = records[1];
  wrong["cpu_seconds"] = "fast";
  const struct {
    std::string line2;
    std::string expected;
  } damages[] = {
      {deep, "out/records.jsonl:2: nesting deeper than 64 levels at column 72"},
      {wrong.dump(), "out/records.jsonl:2: cpu_seconds: must be a number or null"},
      {"{\"key\": 1e999}", "out/records.jsonl:2: not valid JSON at column"},
      {"{\"key\": \"k\", \"seed\": -3}", "out/records.jsonl:2: seed: must be an integer >= 0"},
  };
  for (const auto& d : damages) {
    testing::WriteText(dir + "/out/records.jsonl",
                       first + d.line2 + "\n" + records[2].dump() + "\n");
    const ProgramRun run =
        RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << run.err;
    EXPECT_NE(run.err.find(d.expected), std::string::npos) << run.err;
  }
  fs::create_directories(dir + "/shards");
  testing::WriteText(dir + "/shards/records.shard-1-of-2.jsonl", first);
  testing::WriteText(dir + "/shards/records.shard-2-of-2.jsonl", deep + "\n" + first);
  const ProgramRun merge = RunOcpbenchProgram({"merge", "shards", "--suite", "suite.json"}, dir);
  EXPECT_EQ(merge.exit_code, 2) << merge.err;
  EXPECT_TRUE(OneErrorLine(merge)) << merge.err;
  EXPECT_NE(merge.err.find("records.shard-2-of-2.jsonl:1: nesting deeper than 64 levels"),
            std::string::npos)
      << merge.err;
  EXPECT_FALSE(fs::exists(dir + "/shards/records.jsonl"));
}

TEST(Reliability, ResumeDropsDuplicateRecordsOfACase) {
  const std::string dir = testing::FreshDirectory("duplicates");
  testing::WriteText(dir + "/suite.json", Suite(2, 20, 5));
  ASSERT_EQ(RunOcpbenchProgram({"run", "suite.json", "--out", "out"}, dir).exit_code, 0);
  const std::string path = dir + "/out/records.jsonl";
  const std::string text = testing::ReadText(path);
  testing::WriteText(path, text + text);  // two runs that wrote one file, before the lock
  const ProgramRun resumed =
      RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("dropped 2 duplicate records"), std::string::npos) << resumed.err;
  EXPECT_EQ(testing::ReadText(path), text);
}

TEST(Reliability, EndlessAndHugeInputsAreRefusedBySizeBeforeTheyAreRead) {
  const std::string dir = testing::FreshDirectory("endless");
  const std::vector<std::string> solve = {
      "solve", "--problem", "double-integrator", "--solver", "hamiltonian"};
  std::vector<std::string> guess = solve;
  guess.insert(guess.end(), {"--initial-guess", "/dev/zero"});
  const ProgramRun g = RunOcpbenchProgram(guess, dir);
  EXPECT_EQ(g.exit_code, 2) << g.err;
  EXPECT_NE(g.err.find("--initial-guess /dev/zero: more input than allowed"), std::string::npos)
      << g.err;
  const ProgramRun m =
      RunOcpbenchProgram({"channel", "predict", "--measurements", "/dev/zero"}, dir);
  EXPECT_EQ(m.exit_code, 2) << m.err;
  EXPECT_NE(m.err.find("a measurement file may hold at most 64 MiB"), std::string::npos) << m.err;
  // A records file of 4 TiB (sparse): refused by its size, in an instant.
  testing::WriteText(dir + "/suite.json", Suite(1, 20, 5));
  fs::create_directories(dir + "/out");
  { std::ofstream(dir + "/out/records.jsonl") << "x"; }
  fs::resize_file(dir + "/out/records.jsonl", std::uintmax_t{1} << 42);
  const auto start = std::chrono::steady_clock::now();
  const ProgramRun r = RunOcpbenchProgram({"run", "suite.json", "--out", "out", "--resume"}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("beyond this machine's memory budget"), std::string::npos) << r.err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

TEST(Reliability, InitialGuessErrorsNameTheLineAndTheField) {
  const std::string dir = testing::FreshDirectory("guess-lines");
  testing::WriteText(
      dir + "/nan.json",
      "{\n \"trajectory\": {\n  \"t\": [0, 0.5, 1],\n  \"u\": [[0,\n    \"x\"]]\n }\n}");
  testing::WriteText(dir + "/rule.json",
                     "{\"trajectory\": {\"t\": [0, 5], \"u\": [[0]],\n \"u_rule\": 5}}");
  testing::WriteText(dir + "/overflow.json", "{\"trajectory\":\n {\"t\": [0, 1e999]}}");
  const struct {
    const char* file;
    const char* expected;
  } cases[] = {
      {"nan.json", "--initial-guess nan.json:5: trajectory.u[0][1]: is not a finite number"},
      {"rule.json", "--initial-guess rule.json:2: trajectory.u_rule: must be a string"},
      {"overflow.json", "--initial-guess overflow.json:2: not valid JSON at column"},
  };
  for (const auto& c : cases) {
    const ProgramRun run = RunOcpbenchProgram({"solve",
                                               "--problem",
                                               "double-integrator",
                                               "--solver",
                                               "hamiltonian",
                                               "--initial-guess",
                                               c.file},
                                              dir);
    EXPECT_EQ(run.exit_code, 2) << c.file << ": " << run.err;
    EXPECT_TRUE(OneErrorLine(run)) << run.err;
    EXPECT_NE(run.err.find(c.expected), std::string::npos) << run.err;
  }
}

}  // namespace
}  // namespace ocpb
