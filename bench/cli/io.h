// Writing results so that nothing already written is ever lost or left half-written, and
// nothing that is not a regular file (a device, a link, a pipe) is ever replaced.
#pragma once

#include <string>

namespace ocpb {

/// What writing a file at a path does, decided by what is there now (ClassifyOutput).
struct OutputTarget {
  enum class Kind {
    kReplace,       ///< nothing, or a regular file: a temporary file renamed over it
    kWriteThrough,  ///< a character device or a FIFO (/dev/null, /dev/stdout): written into
    kRefused,       ///< a directory, a block device, a socket, a link to nothing
  };
  Kind kind = Kind::kReplace;
  std::string path;  ///< what is written: the path, or the file a symbolic link points to
  std::string why;   ///< kRefused: the rule, for messages ("is a directory")
};

/// Follows symbolic links (a link itself is never replaced: the file it points to is written)
/// and sorts what is there into the three ways of writing.
OutputTarget ClassifyOutput(const std::string& path);

/// Writes `text` to `path` by ClassifyOutput: a regular file (or a new one) through a temporary
/// file in the same directory, fsync and an atomic rename (a replaced file keeps its
/// permissions; parent directories are created); a character device or FIFO by writing into
/// it. Throws std::runtime_error naming the path for a refused place or a failed write (the
/// old file is then unchanged).
void WriteFileAtomically(const std::string& path, const std::string& text);

/// Appends one line (a JSON record) to `path` and flushes it to disk (fsync) before returning,
/// so a killed run keeps every finished record whole. Creates parent directories. When the
/// write, the fsync or the close fails (a full disk, a file-size limit), a regular file is cut
/// back to its size before the call, its last whole record, and std::runtime_error says so.
void AppendLineDurably(const std::string& path, const std::string& line);

}  // namespace ocpb
