// Output places (`--json` files, `--out` folders, the folder `merge` writes): checked before any
// work, so that an unusable place is an exit-2 error before solving rather than a failure after
// it, and claimed by one writer at a time.
#pragma once

#include <string>
#include <vector>

namespace ocpb {

/// Throws std::invalid_argument "FLAG PATH: rule" unless a file can be written at `path` the
/// way WriteFileAtomically will write it (bench/cli/io.h): a directory, a block device, a
/// socket or a link to nothing there is refused; a character device or a FIFO (/dev/null) is
/// accepted, to be written into; for a regular file or a new one, its name must fit the file
/// system (NAME_MAX, PATH_MAX) and its folder, or the nearest folder above it that exists (the
/// rest is created when written), must accept a new file (tried by creating and removing one:
/// this catches read-only file systems and permissions alike). Creates nothing that stays.
void CheckOutputFile(const std::string& path, const std::string& flag);

/// Creates `dir` (and its parents) when needed and throws std::invalid_argument "FLAG DIR:
/// rule" unless it is a folder that accepts new files.
void CheckOutputFolder(const std::string& dir, const std::string& flag);

/// Who may write to an output folder at the same time as the lock's holder.
enum class FolderAccess {
  kExclusive,  ///< nobody: a run without --shard, merge, channel maps (the folder's own files)
  kShard,      ///< other shards of the same split, not the same shard twice, nor a kExclusive
};

/// An output folder claimed by this process: a POSIX record lock on DIR/.ocpbench.lock (byte 0
/// for the folder, shared by the shards of a run and exclusive otherwise; one byte for each
/// shard i/n), released when the object is destroyed or the process ends, however it ends (a
/// SIGKILL'ed run leaves no stale lock: --resume claims the folder again). The lock file stays
/// (removing it would let two processes hold locks on two different files). Works on NFS (the
/// record locks go through its lock manager).
class OutputFolderLock {
 public:
  OutputFolderLock() = default;
  OutputFolderLock(OutputFolderLock&& other) noexcept;
  OutputFolderLock& operator=(OutputFolderLock&& other) noexcept;
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;
  ~OutputFolderLock();

  /// Claims `dir` (which must exist): throws std::invalid_argument "FLAG DIR: another ocpbench
  /// (pid P) is writing there; wait for it to finish or choose another folder" when a holder
  /// excludes this access. `shard` / `shards` name the shard for kShard (0 <= shard <= shards,
  /// whichever numbering the caller uses).
  static OutputFolderLock Acquire(const std::string& dir,
                                  const std::string& flag,
                                  FolderAccess access,
                                  int shard = 0,
                                  int shards = 1);

 private:
  int fd_ = -1;
};

/// The files `ocpbench run` (without shards) and `merge` write beside the records
/// (WriteRunSummaries in bench/cli/run_outputs.cc; a file added there belongs here too).
const std::vector<std::string>& SummaryFileNames();

/// What `ocpbench run` does before solving: CheckOutputFolder(dir), the folder's lock (kShard
/// for a shard's records file, kExclusive otherwise), and CheckOutputFile for the records file,
/// its ".prev" (--overwrite keeps the old one there) and, without shards, each summary file
/// (with shards: the folder's shards.json, bench/cli/shard_manifest.h).
/// `shard` and `shards` as the records file names them (0 <= shard <= shards).
OutputFolderLock ClaimRunFolder(const std::string& dir,
                                const std::string& records_path,
                                int shard,
                                int shards);

/// What `ocpbench merge` does before reading the shards: the folder's exclusive lock (refused
/// while a shard still runs there) and CheckOutputFile for records.jsonl, its ".prev" and each
/// summary file.
OutputFolderLock ClaimMergeFolder(const std::string& dir);

}  // namespace ocpb
