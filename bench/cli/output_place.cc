#include "bench/cli/output_place.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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
  throw std::invalid_argument(flag + " " + OneLine(path) + ": " + why);
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

}  // namespace

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

OutputFolderLock ClaimRunFolder(const std::string& dir,
                                const std::string& records_path,
                                int shard,
                                int shards) {
  CheckOutputFolder(dir, "--out");
  const bool sharded = shards > 1;
  OutputFolderLock lock = OutputFolderLock::Acquire(
      dir, "--out", sharded ? FolderAccess::kShard : FolderAccess::kExclusive, shard, shards);
  CheckOutputFile(records_path, "--out");
  if (ClassifyOutput(records_path).kind == OutputTarget::Kind::kWriteThrough) {
    Refuse("--out", records_path, "is not a regular file (--resume reads a records file back)");
  }
  CheckOutputFile(records_path + ".prev", "--out");
  if (sharded) {
    CheckOutputFile((fs::path(dir) / "shards.json").string(), "--out");
  } else {
    for (const std::string& name : SummaryFileNames()) {
      CheckOutputFile((fs::path(dir) / name).string(), "--out");
    }
  }
  return lock;
}

OutputFolderLock ClaimMergeFolder(const std::string& dir) {
  OutputFolderLock lock = OutputFolderLock::Acquire(dir, "merge", FolderAccess::kExclusive);
  const std::string records = (fs::path(dir) / "records.jsonl").string();
  CheckOutputFile(records, "merge");
  CheckOutputFile(records + ".prev", "merge");
  for (const std::string& name : SummaryFileNames()) {
    CheckOutputFile((fs::path(dir) / name).string(), "merge");
  }
  return lock;
}

}  // namespace ocpb
