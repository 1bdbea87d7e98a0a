// The reading and writing layer on its own: input files within limits with errors that name
// the file, the line and the field; JSON nesting; records files; writes that never replace
// what is not a regular file; appends that survive a full disk; a refused thread.
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/cli/io.h"
#include "bench/cli/json_input.h"
#include "bench/cli/output_place.h"
#include "bench/cli/records_file.h"
#include "core/input_file.h"
#include "problems/channel/gp_predictor.h"
#include "problems/channel/grid_predictor.h"
#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The message of the std::invalid_argument `f` throws ("" when it throws none).
template <typename F>
std::string InvalidArgument(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(OneLine, EscapesEveryControlCharacter) {
  EXPECT_EQ(OneLine("a\nb\r\tc\x1b"
                    "d\x7f"),
            "a\\nb\\r\\tc\\x1bd\\x7f");
  EXPECT_EQ(OneLine("plain text, ü"), "plain text, ü");
}

TEST(ReadInputFile, RefusesMissingFilesFoldersAndTooMuchInput) {
  const std::string dir = testing::FreshDirectory("read-input");
  EXPECT_EQ(InvalidArgument([&] { ReadInputFile(dir + "/none", 100, "suite file"); }),
            dir + "/none: cannot read this suite file: No such file or directory");
  EXPECT_EQ(InvalidArgument([&] { ReadInputFile(dir, 100, "suite file"); }),
            dir + ": is a directory, not a suite file");
  testing::WriteText(dir + "/big", std::string(2000, 'x'));
  EXPECT_EQ(InvalidArgument([&] { ReadInputFile(dir + "/big", 1024, "record"); }),
            dir + "/big: 1.95 KiB is too large; a record may hold at most 1 KiB");
  EXPECT_EQ(ReadInputFile(dir + "/big", 2000, "record").size(), 2000u);
  // An endless device is read no further than the limit.
  EXPECT_EQ(InvalidArgument([&] { ReadInputFile("/dev/zero", 1 << 20, "suite file"); }),
            "/dev/zero: more input than allowed (reading stopped there); a suite file may hold "
            "at most 1 MiB");
}

TEST(ParseJsonText, RefusesDeepNestingBeforeParsing) {
  const std::string deep = "[" + std::string(100000, '[') + std::string(100001, ']') + "]";
  EXPECT_EQ(InvalidArgument([&] { ParseJsonText(deep, "f.json"); }),
            "f.json:1: nesting deeper than 64 levels at column 65");
  // Brackets inside strings are text.
  EXPECT_NO_THROW(ParseJsonText("{\"a\": \"" + std::string(1000, '[') + "\"}", "f.json"));
  const std::string at_limit = std::string(64, '[') + std::string(64, ']');
  EXPECT_NO_THROW(ParseJsonText(at_limit, "f.json"));
  EXPECT_NE(InvalidArgument([&] { ParseJsonText("[" + at_limit + "]", "f.json"); }), "");
}

TEST(ParseJsonText, NamesTheLineOfEveryKindOfError) {
  EXPECT_EQ(InvalidArgument([] { ParseJsonText("{\n \"a\": 1,\n \"b\": 1e999}", "f.json"); }),
            "f.json:3: not valid JSON at column 7: number overflow parsing '1e999'");
  // A line of a JSON Lines file, counted from its own line in the file.
  const std::string bad = InvalidArgument([] { ParseJsonText("{\"a\": tru}", "r.jsonl", 7); });
  EXPECT_EQ(bad.rfind("r.jsonl:7: not valid JSON at column ", 0), 0u) << bad;
  EXPECT_THROW(ParseJsonText("{\"a\": [1, 2", "r.jsonl", 3), TruncatedJsonError);
  try {
    ParseJsonText("{\"a\": [1, 2", "r.jsonl", 3);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "r.jsonl");
    EXPECT_EQ(e.line(), 3);
  }
  EXPECT_THROW(ParseJsonText("{\"a\": 1} x", "f"), InputError);
}

TEST(JsonLines, FindsTheLineOfEachValue) {
  const std::string text =
      "{\n  \"a\": [1,\n        2],\n  \"b\": {\"c\": \"x\\\"]\"},\n  \"a\": 5\n}";
  const json doc = ParseJsonText(text, "f");
  const JsonLines lines(text, doc);
  EXPECT_EQ(lines.LineOf(doc), 1);
  EXPECT_EQ(lines.LineOf(doc["b"]), 4);
  EXPECT_EQ(lines.LineOf(doc["b"]["c"]), 4);
  // A key given twice: the document keeps the last value, found on its own line.
  EXPECT_EQ(doc["a"], 5);
  EXPECT_EQ(lines.LineOf(doc["a"]), 5);
  const json other = 1;
  EXPECT_EQ(lines.LineOf(other), 0);
}

std::string RecordLine(const std::string& key, const std::string& extra = "") {
  return R"({"schema_version": 2, "key": ")" + key + R"(", "status": "converged")" + extra + "}";
}

TEST(ParseRecords, DropsOnlyALastLineCutShort) {
  const std::string two = RecordLine("a") + "\n" + RecordLine("b") + "\n";
  RecordFile f = ParseRecords(two + RecordLine("c").substr(0, 20), "r.jsonl");
  EXPECT_TRUE(f.dropped_partial);
  EXPECT_EQ(f.records.size(), 2u);
  EXPECT_EQ(f.line_numbers, (std::vector<int>{1, 2}));
  // A last line that is whole but not JSON is damage, not a kill's doing.
  EXPECT_EQ(InvalidArgument([&] {
              ParseRecords(two + "garbage", "r.jsonl");
            }).rfind("r.jsonl:3: not valid JSON", 0),
            0u);
  EXPECT_EQ(InvalidArgument([&] { ParseRecords(two + "[1]\n", "r.jsonl"); }),
            "r.jsonl:3: not a JSON record (an object)");
}

TEST(ParseRecords, NamesTheFileTheLineAndTheField) {
  const std::string first = RecordLine("a") + "\n\n";  // an empty line still counts
  EXPECT_EQ(
      InvalidArgument([&] { ParseRecords(first + RecordLine("b", R"(, "seed": "one")"), "r"); }),
      "r:3: seed: must be an integer >= 0");
  EXPECT_EQ(InvalidArgument([&] {
              ParseRecords(first + RecordLine("b", R"(, "iterations": 18446744073709551615)"), "r");
            }),
            "r:3: iterations: must be an integer");
  EXPECT_EQ(InvalidArgument([&] {
              ParseRecords(first + RecordLine("b", R"(, "history": [{"J": "x"}])") + "\n", "r");
            }),
            "r:3: history[0].J: must be a number or null");
  const std::string deep =
      RecordLine("b", R"(, "s_map": )" + std::string(70, '[') + std::string(70, ']'));
  EXPECT_EQ(InvalidArgument([&] {
              ParseRecords(first + deep + "\n", "r");
            }).rfind("r:3: nesting deeper than 64 levels", 0),
            0u);
}

TEST(ParseRecords, DropDuplicateKeysKeepsTheFirstRecordOfEachCase) {
  RecordFile f = ParseRecords(RecordLine("a", R"(, "iterations": 1)") + "\n" + RecordLine("b") +
                                  "\n" + RecordLine("a", R"(, "iterations": 2)") + "\n",
                              "r");
  EXPECT_EQ(f.DropDuplicateKeys(), 1);
  ASSERT_EQ(f.records.size(), 2u);
  EXPECT_EQ(f.records[0].key, "a");
  EXPECT_EQ(f.records[0].iterations, 1);
  EXPECT_EQ(f.records[1].key, "b");
  EXPECT_EQ(f.line_numbers, (std::vector<int>{1, 2}));
  EXPECT_EQ(f.lines.size(), 2u);
  EXPECT_EQ(f.DropDuplicateKeys(), 0);
}

TEST(ReadRecords, RefusesAFileBeyondTheMemoryEstimateBeforeReadingIt) {
  const std::string dir = testing::FreshDirectory("huge-records");
  const std::string path = dir + "/records.jsonl";
  { std::ofstream(path) << ""; }
  fs::resize_file(path, std::uintmax_t{1} << 42);  // 4 TiB, sparse: nothing is really written
  const std::string error = InvalidArgument([&] { ReadRecords(path); });
  EXPECT_NE(error.find(path + ": records: 4.4 TB of records read whole need about 17.6 TB"),
            std::string::npos)
      << error;
}

TEST(WriteFileAtomically, WritesIntoAFifoAndNeverReplacesIt) {
  const std::string dir = testing::FreshDirectory("fifo");
  const std::string fifo = dir + "/pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo);
    received.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  });
  WriteFileAtomically(fifo, "record\n");
  reader.join();
  EXPECT_EQ(received, "record\n");
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
}

TEST(WriteFileAtomically, ReplacesWhatALinkPointsToAndKeepsTheLinkAndThePermissions) {
  const std::string dir = testing::FreshDirectory("link");
  testing::WriteText(dir + "/target.json", "old");
  ASSERT_EQ(::chmod((dir + "/target.json").c_str(), 0600), 0);
  fs::create_symlink("target.json", dir + "/link.json");
  WriteFileAtomically(dir + "/link.json", "new");
  EXPECT_TRUE(fs::is_symlink(dir + "/link.json"));
  EXPECT_EQ(testing::ReadText(dir + "/target.json"), "new");
  EXPECT_EQ(fs::status(dir + "/target.json").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
  // /dev/null through a link: written into, neither the link nor the device replaced.
  fs::create_symlink("/dev/null", dir + "/null");
  WriteFileAtomically(dir + "/null", "discarded");
  EXPECT_TRUE(fs::is_symlink(dir + "/null"));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // A link to nothing, a folder: refused, nothing made.
  fs::create_symlink("nowhere.json", dir + "/dangling");
  EXPECT_THROW(WriteFileAtomically(dir + "/dangling", "x"), std::runtime_error);
  EXPECT_FALSE(fs::exists(dir + "/nowhere.json"));
  EXPECT_THROW(WriteFileAtomically(dir, "x"), std::runtime_error);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 4)
      << "no temporary file is left behind";
}

TEST(CheckOutputFile, RefusesUnusablePlacesAndCreatesNothing) {
  const std::string dir = testing::FreshDirectory("check-output");
  testing::WriteText(dir + "/file", "x");
  EXPECT_EQ(InvalidArgument([&] { CheckOutputFile(dir, "--json"); }),
            "--json " + dir + ": is a directory, not a file");
  EXPECT_EQ(InvalidArgument([&] { CheckOutputFile(dir + "/file/r.json", "--json"); }),
            "--json " + dir + "/file/r.json: " + dir + "/file is a file, not a folder");
  EXPECT_NE(InvalidArgument([&] {
              CheckOutputFile(dir + "/" + std::string(300, 'n'), "--json");
            }).find("is longer than the 255 characters the file system allows"),
            std::string::npos);
  EXPECT_EQ(InvalidArgument([&] { CheckOutputFile("/dev/null", "--json"); }), "");
  EXPECT_EQ(InvalidArgument([&] { CheckOutputFile(dir + "/new/deeper/r.json", "--json"); }), "");
  EXPECT_FALSE(fs::exists(dir + "/new")) << "a check creates nothing";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1)
      << "the probe file is removed";
}

// Runs `body` in a child process with a file-size limit of `bytes` (SIGXFSZ ignored, as
// ocpb::Main does); returns the child's exit code (128 + signal when killed).
template <typename F>
int InChildWithFileSizeLimit(rlim_t bytes, F&& body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{bytes, bytes};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(90);
    ::_exit(body());
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(AppendLineDurably, AFailedAppendLeavesTheFileAtItsLastWholeRecord) {
  const std::string dir = testing::FreshDirectory("append-limit");
  const std::string path = dir + "/records.jsonl";
  const std::string first = RecordLine("a"), second = RecordLine(std::string(3000, 'b'));
  AppendLineDurably(path, first);
  const int code = InChildWithFileSizeLimit(2048, [&] {
    try {
      AppendLineDurably(path, second);
    } catch (const std::runtime_error& e) {
      const std::string m = e.what();
      return m.find("File too large (the file keeps its records up to the last whole one)") !=
                     std::string::npos
                 ? 0
                 : 2;
    }
    return 1;
  });
  EXPECT_EQ(code, 0) << "1: the append did not fail; 2: another message";
  EXPECT_EQ(testing::ReadText(path), first + "\n");
}

// A thread the system refuses is neither a termination nor an error: the prediction goes on
// with the threads it has, gives the same numbers, and says so in its method.
TEST(PredictOnGrid, AThreadTheSystemCannotStartLeavesTheOthersToDoTheWork) {
  ChannelParameters p;
  MeasurementSet m;
  for (int i = 0; i < 10; ++i) {
    m.positions.emplace_back(3.0 + 4.0 * i, 7.0 + 3.0 * i);
    m.values_db.push_back(-60.0 - i);
  }
  const GpChannelPredictor predictor(p, m);
  const GridSpec grid = GridSpec::Workspace(50.0, 50.0, 0.5);
  GridPredictionOptions one;
  one.num_threads = 1;
  const GridPrediction alone = PredictOnGrid(predictor, grid, one);
  for (const int threads : {2, 4, 256}) {
    GridPredictionOptions options;
    options.num_threads = threads;
    const pid_t pid = ::fork();
    if (pid == 0) {
      // No new threads for this process: root is exempt from RLIMIT_NPROC, so drop to nobody.
      if (::getuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(90);
      const rlimit none{0, 0};
      if (::setrlimit(RLIMIT_NPROC, &none) != 0) ::_exit(91);
      try {
        const GridPrediction got = PredictOnGrid(predictor, grid, options);
        if (got.method.find("(the system started only 1)") == std::string::npos) ::_exit(2);
        if (got.mean_db != alone.mean_db || got.variance_db2 != alone.variance_db2 ||
            got.s != alone.s) {
          ::_exit(3);
        }
      } catch (...) {
        ::_exit(4);
      }
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << " (terminate?)";
    EXPECT_EQ(WEXITSTATUS(status), 0)
        << threads << " threads; 2: the method does not say so; 3: other numbers; 4: threw";
  }
}

}  // namespace
}  // namespace ocpb
