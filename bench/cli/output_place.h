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

/// The files one command reads and writes, checked against each other before any work: an
/// output never names an input or another output (the same file by any spelling: `..`,
/// symbolic links and hard links are seen through, comparing existing files by device and
/// inode and new ones by their path with every link of the part that exists resolved). Each
/// path comes with what names it in messages: "--json", "the suite file", "ipopt option
/// output_file of groups[0].methods[1]". A symbolic link loop is refused where it is added
/// (std::invalid_argument, exit 2).
class FilePlan {
 public:
  /// A file the command reads.
  void Input(const std::string& path, const std::string& what);
  /// A file the command writes (or replaces, or renames). Outputs with the same non-empty
  /// `shared_by` tag may name one file (the solver logs of a suite's cases: each case's log
  /// replaces the one before); a character device or a FIFO (/dev/null) may be named by any
  /// number of outputs.
  void Output(const std::string& path, const std::string& what, const std::string& shared_by = "");
  /// The `shared_by` tag of a solver's own output file (Ipopt's `output_file`). The solver
  /// writes it in place (OCPBench's own outputs replace the name by a rename), so Check also
  /// refuses an existing such file that has other names (hard links): they would change too.
  static constexpr const char* kSolverLog = "solver log";
  /// The output folder of `ocpbench run` or `merge` (PlanRunFolder, ClaimMergeFolder): every
  /// file there named as a run folder's files are (IsRunFolderFileName) is the run's, whether
  /// it exists yet or not (another shard's records file to come).
  void RunFolder(const std::string& dir);
  /// Throws std::invalid_argument "WHAT PATH: is also WHAT2 PATH2 (RULE)" for the first output
  /// that names an input or another output; then for the first output that names a file of a
  /// run folder ("WHAT PATH: is records.jsonl of the run folder DIR (...)"): a file named as a
  /// run folder's files are, in this plan's RunFolder or in any folder that holds a run's files
  /// (its .ocpbench.lock, a shards.json, or records.jsonl beside suite.json), with links
  /// resolved, unless the output is the run's (or merge's) own; then for a solver's output file
  /// (kSolverLog) that exists with more than one name.
  void Check() const;

  /// The names of the files `run` and `merge` write in a run folder: records.jsonl,
  /// records.shard-I-of-N.jsonl and their earlier versions (records.*.prev), shards.json, the
  /// summaries (SummaryFileNames) and .ocpbench.lock.
  static bool IsRunFolderFileName(const std::string& name);

  /// A solver or transcription option that names a file the solve writes (Ipopt's
  /// `output_file`), by the owner's option name: the one list every command consults.
  static bool IsOutputFileOption(const std::string& option);

  struct Place {
    std::string path;  ///< as given
    std::string what;
    std::string shared_by;
    bool output = false;
    bool exists = false;
    bool write_through = false;  ///< a character device or a FIFO
    unsigned long long device = 0, inode = 0;
    unsigned long long links = 0;  ///< hard links of an existing file
    std::string resolved;          ///< when it does not exist: the absolute path, links resolved
  };

 private:
  std::vector<Place> places_;
  std::vector<std::string> run_folders_;  ///< RunFolder's, resolved
};

/// Renames `path` (an existing file) out of the way so that nothing is lost: to PATH.prev, the
/// one there before (if any) first to PATH.K.prev with K the first free number from 1, so that
/// PATH.prev is always the latest earlier version and PATH.1.prev, PATH.2.prev, ... the older
/// ones, oldest first (every one matching "*.prev"). Returns the name the file has now.
std::string KeepPreviousVersion(const std::string& path);

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

/// What `ocpbench run` does before solving: `plan` (holding the run's inputs: the suite file,
/// the cases' files, AddCaseFiles) gets the run's outputs, the records file, its ".prev" and,
/// without shards, each summary file (with shards: the folder's shards.json), and every file
/// of the folder that another run or merge wrote there (records*, shards.json: no case's
/// solver log may name one), and is checked (FilePlan::Check); then CheckOutputFolder(dir),
/// the folder's lock (kShard for a shard's records file, kExclusive otherwise), and
/// CheckOutputFile for each output. `shard` and `shards` as the records file names them
/// (0 <= shard <= shards).
/// The first part of ClaimRunFolder, all `run --check` does: the outputs added to `plan`, and
/// the plan checked. Returns the outputs.
std::vector<std::string> PlanRunFolder(const std::string& dir,
                                       const std::string& records_path,
                                       int shards,
                                       FilePlan* plan);

OutputFolderLock ClaimRunFolder(
    const std::string& dir, const std::string& records_path, int shard, int shards, FilePlan plan);

/// What `ocpbench merge` does before reading the shards: `plan` (holding the merge's inputs:
/// the shards' records files, shards.json, --suite) gets records.jsonl, its ".prev" and each
/// summary file as outputs and is checked; then the folder's exclusive lock (refused while a
/// shard still runs there) and CheckOutputFile for each output.
OutputFolderLock ClaimMergeFolder(const std::string& dir, FilePlan plan);

}  // namespace ocpb
