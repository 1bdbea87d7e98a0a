#include "bench/cli/output_place.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "bench/cli/io.h"
#include "core/input_file.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void Refuse(const std::string& flag, const std::string& path, const std::string& why) {
  throw std::invalid_argument(flag + " " + (path.empty() ? "''" : OneLine(path)) + ": " + why);
}

// The nearest folder at or above `dir` that exists ("." for a relative path with none).
fs::path NearestExisting(fs::path dir) {
  std::error_code ec;
  while (!dir.empty() && !fs::exists(dir, ec)) dir = dir.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

// Creates and removes a file in `dir`: the one test that sees read-only file systems, ACLs and
// permissions as the writer will (access(2) says yes to root on a read-only mount's folder).
void ProbeWritable(const fs::path& dir, const std::string& flag, const std::string& path) {
  std::string probe = (dir / ".ocpb-probe-XXXXXX").string();
  const int fd = ::mkostemp(probe.data(), O_CLOEXEC);
  if (fd < 0) {
    Refuse(flag,
           path,
           "cannot create a file in " + OneLine(dir.string()) + ": " + std::strerror(errno));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

// Every component fits NAME_MAX of its file system and the whole PATH_MAX.
void CheckNameLengths(const fs::path& path, const fs::path& existing, const std::string& flag) {
  if (path.string().size() >= PATH_MAX) {
    Refuse(flag, path.string(), "the path is longer than the system allows (PATH_MAX)");
  }
  long name_max = ::pathconf(existing.c_str(), _PC_NAME_MAX);
  if (name_max <= 0) name_max = NAME_MAX;
  for (const fs::path& part : path) {
    if (static_cast<long>(part.string().size()) > name_max) {
      Refuse(flag,
             path.string(),
             "the name '" + OneLine(part.string().substr(0, 40)) + "...' is longer than the " +
                 std::to_string(name_max) + " characters the file system allows");
    }
  }
}

// Offset of the lock byte of shard `i` of `n` (0 <= i <= n): 1 + n (n + 1) / 2 + i, one byte
// per (i, n) pair; byte 0 is the folder's.
off_t ShardByte(int i, int n) { return 1 + static_cast<off_t>(n) * (n + 1) / 2 + i; }

// Tries a record lock on one byte; the pid of the holder when another process has it (-1 for
// one that does not say, as on some NFS servers), 0 when taken.
long TryLock(int fd, short type, off_t byte) {
  struct flock lock {};
  lock.l_type = type;
  lock.l_whence = SEEK_SET;
  lock.l_start = byte;
  lock.l_len = 1;
  if (::fcntl(fd, F_SETLK, &lock) == 0) return 0;
  if (errno != EACCES && errno != EAGAIN) return -2;
  struct flock probe {};
  probe.l_type = type;
  probe.l_whence = SEEK_SET;
  probe.l_start = byte;
  probe.l_len = 1;
  if (::fcntl(fd, F_GETLK, &probe) == 0 && probe.l_type != F_UNLCK && probe.l_pid > 0) {
    return probe.l_pid;
  }
  return -1;
}

// A path the system cannot follow for a reason in the path itself: refused as input (exit 2).
[[noreturn]] void RefusePath(const std::string& what, const std::string& path, int error) {
  if (error == ELOOP) {
    Refuse(what, path, "a loop of symbolic links (too many levels of links to follow)");
  }
  if (error == ENAMETOOLONG) {
    Refuse(what, path, "the path or one of its names is longer than the system allows");
  }
  Refuse(what, path, std::strerror(error));
}

FilePlan::Place PlaceOf(const std::string& path, const std::string& what, bool output) {
  FilePlan::Place place;
  place.path = path;
  place.what = what;
  place.output = output;
  if (path.empty()) Refuse(what, path, "an empty path");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    place.exists = true;
    place.write_through = S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode);
    place.device = static_cast<unsigned long long>(st.st_dev);
    place.inode = static_cast<unsigned long long>(st.st_ino);
    place.links = static_cast<unsigned long long>(st.st_nlink);
    return place;
  }
  // A loop of links is refused here; an over-long name is left to the check of the place
  // itself (CheckOutputFile, the input's reader), which names the part and the limit.
  const int error = errno;
  if (error == ELOOP) RefusePath(what, path, error);
  // Not there (yet): the absolute path with every link of the part that exists resolved, so
  // that "d/../x", "./x" and "link-to-folder/x" are one place.
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (ec) absolute = fs::path(path);
  fs::path resolved = fs::weakly_canonical(absolute, ec);
  if (ec) {
    if (ec.value() == ELOOP) RefusePath(what, path, ec.value());
    resolved = absolute.lexically_normal();
  }
  place.resolved = resolved.string();
  return place;
}

// The tag of the outputs a run or a merge writes in its own folder (PlanRunFolder,
// ClaimMergeFolder): the only outputs that may name the folder's own files.
constexpr const char* kRunFolderTag = "the output folder";

// The absolute path of `path` with every link of the part that exists resolved ("" when the
// system cannot say).
fs::path Resolved(const std::string& path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (ec) return {};
  fs::path resolved = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : resolved;
}

// A folder that holds a run's or a merge's files: its lock, a sweep's shards.json, or records
// beside the summary's copy of the suite.
bool LooksLikeRunFolder(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir / ".ocpbench.lock", ec) || fs::exists(dir / "shards.json", ec)) return true;
  return fs::exists(dir / "records.jsonl", ec) && fs::exists(dir / "suite.json", ec);
}

bool SameFile(const FilePlan::Place& a, const FilePlan::Place& b) {
  if (a.exists != b.exists) return false;
  if (a.exists) return a.device == b.device && a.inode == b.inode;
  return a.resolved == b.resolved;
}

}  // namespace

void FilePlan::Input(const std::string& path, const std::string& what) {
  places_.push_back(PlaceOf(path, what, false));
}

void FilePlan::Output(const std::string& path,
                      const std::string& what,
                      const std::string& shared_by) {
  Place place = PlaceOf(path, what, true);
  place.shared_by = shared_by;
  places_.push_back(std::move(place));
}

void FilePlan::RunFolder(const std::string& dir) { run_folders_.push_back(Resolved(dir).string()); }

bool FilePlan::IsRunFolderFileName(const std::string& name) {
  // records.jsonl, records.shard-I-of-N.jsonl, their earlier versions (.prev, .K.prev).
  const auto ends_with = [&name](const std::string& end) {
    return name.size() >= end.size() &&
           name.compare(name.size() - end.size(), end.size(), end) == 0;
  };
  if (name.rfind("records.", 0) == 0 && (ends_with(".jsonl") || ends_with(".prev"))) return true;
  if (name == "shards.json" || name == ".ocpbench.lock") return true;
  for (const std::string& summary : SummaryFileNames()) {
    if (name == summary) return true;
  }
  return false;
}

void FilePlan::Check() const {
  for (size_t i = 0; i < places_.size(); ++i) {
    const Place& out = places_[i];
    if (!out.output || out.write_through) continue;
    for (size_t j = 0; j < places_.size(); ++j) {
      const Place& other = places_[j];
      if (i == j || !SameFile(out, other)) continue;
      // Report each pair once, from the output added last when both are outputs.
      if (other.output && j > i) continue;
      if (other.output && !out.shared_by.empty() && out.shared_by == other.shared_by) continue;
      if (other.output && out.path == other.path && out.what == other.what) continue;
      Refuse(out.what,
             out.path,
             "is also " + other.what + " " + OneLine(other.path) +
                 (other.output ? " (two outputs in one file: one would replace the other)"
                               : " (an output never replaces an input)"));
    }
  }
  // No output but a run's (or a merge's) own names a file of a run folder: this command's
  // run folder (RunFolder), or any folder that holds a run's files, seen through links.
  for (const Place& out : places_) {
    if (!out.output || out.write_through || out.shared_by == kRunFolderTag) continue;
    const fs::path file = Resolved(out.path);
    if (file.empty() || !IsRunFolderFileName(file.filename().string())) continue;
    const fs::path dir = file.parent_path();
    const bool ours =
        std::find(run_folders_.begin(), run_folders_.end(), dir.string()) != run_folders_.end();
    if (!ours && !LooksLikeRunFolder(dir)) continue;
    Refuse(out.what,
           out.path,
           "is " + OneLine(file.filename().string()) + " of the run folder " +
               OneLine(dir.string()) +
               " (records, their earlier versions, shards.json, the summaries and the lock of a "
               "run folder are written by `ocpbench run` and `merge` only)");
  }
  // A solver writes its output file in place: a file with other names (hard links) would
  // change under each of them, whichever file that is (a run's records, an input).
  for (const Place& out : places_) {
    if (!out.output || out.write_through || out.shared_by != kSolverLog) continue;
    if (!out.exists || out.links <= 1) continue;
    Refuse(out.what,
           out.path,
           "has " + std::to_string(out.links) +
               " names (hard links): the solver writes its output file in place, which would "
               "change the file under every other name too; name a file of its own");
  }
}

bool FilePlan::IsOutputFileOption(const std::string& option) { return option == "output_file"; }

std::string KeepPreviousVersion(const std::string& path) {
  const std::string prev = path + ".prev";
  std::error_code ec;
  if (fs::symlink_status(prev, ec).type() != fs::file_type::not_found) {
    for (int k = 1;; ++k) {
      // PATH.K.prev: still "*.prev" (the pattern .gitignore and cleanup scripts know).
      const std::string older = path + "." + std::to_string(k) + ".prev";
      if (fs::symlink_status(older, ec).type() != fs::file_type::not_found) continue;
      fs::rename(prev, older);
      break;
    }
  }
  fs::rename(path, prev);
  return prev;
}

void CheckOutputFile(const std::string& path, const std::string& flag) {
  if (path.empty()) Refuse(flag, path, "an empty path");
  const OutputTarget target = ClassifyOutput(path);
  if (target.kind == OutputTarget::Kind::kRefused) Refuse(flag, path, target.why);
  if (target.kind == OutputTarget::Kind::kWriteThrough) return;
  const fs::path file(target.path);
  if (file.filename().empty() || file.filename() == "." || file.filename() == "..") {
    Refuse(flag, path, "names a folder, not a file");
  }
  const fs::path parent = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  const fs::path existing = NearestExisting(parent);
  std::error_code ec;
  if (!fs::is_directory(existing, ec)) {
    Refuse(flag, path, OneLine(existing.string()) + " is a file, not a folder");
  }
  CheckNameLengths(file, existing, flag);
  ProbeWritable(existing, flag, path);
}

void CheckOutputFolder(const std::string& dir, const std::string& flag) {
  if (dir.empty()) Refuse(flag, dir, "an empty path");
  const fs::path path(dir);
  const fs::path existing = NearestExisting(path);
  std::error_code ec;
  if (!fs::is_directory(existing, ec)) {
    Refuse(flag, dir, OneLine(existing.string()) + " is a file, not a folder");
  }
  CheckNameLengths(path, existing, flag);
  fs::create_directories(path, ec);
  if (ec) Refuse(flag, dir, "cannot create the folder: " + ec.message());
  if (!fs::is_directory(path, ec)) Refuse(flag, dir, "is a file, not a folder");
  ProbeWritable(path, flag, dir);
}

OutputFolderLock::OutputFolderLock(OutputFolderLock&& other) noexcept : fd_(other.fd_) {
  other.fd_ = -1;
}

OutputFolderLock& OutputFolderLock::operator=(OutputFolderLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

OutputFolderLock::~OutputFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the record locks
}

OutputFolderLock OutputFolderLock::Acquire(
    const std::string& dir, const std::string& flag, FolderAccess access, int shard, int shards) {
  const std::string path = (fs::path(dir) / ".ocpbench.lock").string();
  OutputFolderLock lock;
  // O_NOFOLLOW: a link planted in the folder is not followed into someone else's file.
  lock.fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (lock.fd_ < 0)
    Refuse(flag, dir, "cannot create its lock file: " + std::string(std::strerror(errno)));
  auto busy = [&](long pid) {
    if (pid == -2) {
      Refuse(flag, dir, "cannot lock it: " + std::string(std::strerror(errno)));
    }
    Refuse(flag,
           dir,
           "another ocpbench" + (pid > 0 ? " (pid " + std::to_string(pid) + ")" : std::string()) +
               " is writing there; wait for it to finish or choose another folder");
  };
  if (access == FolderAccess::kExclusive) {
    if (const long pid = TryLock(lock.fd_, F_WRLCK, 0)) busy(pid);
  } else {
    if (const long pid = TryLock(lock.fd_, F_RDLCK, 0)) busy(pid);
    if (const long pid = TryLock(lock.fd_, F_WRLCK, ShardByte(shard, shards))) busy(pid);
  }
  return lock;
}

const std::vector<std::string>& SummaryFileNames() {
  static const std::vector<std::string> names = {
      "summary.md", "records.csv", "derived.jsonl", "suite.json"};
  return names;
}

namespace {

// Every file of `dir` (when it exists) that a run or a merge of OCPBench writes: the records
// files of any shard and their previous versions, shards.json, the summaries, the lock.
std::vector<std::string> FolderFiles(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (FilePlan::IsRunFolderFileName(it->path().filename().string())) {
      out.push_back(it->path().string());
    }
  }
  return out;
}

}  // namespace

std::vector<std::string> PlanRunFolder(const std::string& dir,
                                       const std::string& records_path,
                                       int shards,
                                       FilePlan* plan) {
  std::vector<std::string> outputs = {records_path, records_path + ".prev"};
  if (shards > 1) {
    outputs.push_back((fs::path(dir) / "shards.json").string());
  } else {
    for (const std::string& name : SummaryFileNames()) {
      outputs.push_back((fs::path(dir) / name).string());
    }
  }
  for (const std::string& path : outputs) plan->Output(path, "--out", kRunFolderTag);
  for (const std::string& path : FolderFiles(dir)) plan->Output(path, "--out", kRunFolderTag);
  plan->RunFolder(dir);
  plan->Check();
  return outputs;
}

OutputFolderLock ClaimRunFolder(
    const std::string& dir, const std::string& records_path, int shard, int shards, FilePlan plan) {
  const bool sharded = shards > 1;
  const std::vector<std::string> outputs = PlanRunFolder(dir, records_path, shards, &plan);
  CheckOutputFolder(dir, "--out");
  OutputFolderLock lock = OutputFolderLock::Acquire(
      dir, "--out", sharded ? FolderAccess::kShard : FolderAccess::kExclusive, shard, shards);
  CheckOutputFile(records_path, "--out");
  if (ClassifyOutput(records_path).kind == OutputTarget::Kind::kWriteThrough) {
    Refuse("--out", records_path, "is not a regular file (--resume reads a records file back)");
  }
  for (const std::string& path : outputs) CheckOutputFile(path, "--out");
  return lock;
}

OutputFolderLock ClaimMergeFolder(const std::string& dir, FilePlan plan) {
  const std::string records = (fs::path(dir) / "records.jsonl").string();
  std::vector<std::string> outputs = {records, records + ".prev"};
  for (const std::string& name : SummaryFileNames()) {
    outputs.push_back((fs::path(dir) / name).string());
  }
  for (const std::string& path : outputs) plan.Output(path, "merge", kRunFolderTag);
  plan.RunFolder(dir);
  plan.Check();
  OutputFolderLock lock = OutputFolderLock::Acquire(dir, "merge", FolderAccess::kExclusive);
  for (const std::string& path : outputs) CheckOutputFile(path, "merge");
  return lock;
}

}  // namespace ocpb
