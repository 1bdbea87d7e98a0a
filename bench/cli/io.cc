#include "bench/cli/io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/input_file.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void Fail(const std::string& what, const std::string& path, int error) {
  throw std::runtime_error(what + " " + OneLine(path) + ": " + std::strerror(error));
}

void CreateParent(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) Fail("cannot create the folder of", path, ec.value());
}

// Writes all of `text`; false (errno set) when a write fails.
bool WriteAll(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    done += static_cast<size_t>(n);
  }
  return true;
}

// The permissions a new file gets: 0666 less the process's umask (read back by setting it).
mode_t NewFileMode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

void WriteThrough(const std::string& path, const std::string& text) {
  // No O_CREAT, no O_TRUNC: the device or pipe is written into, never made or replaced.
  const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) Fail("cannot write", path, errno);
  if (!WriteAll(fd, text)) {
    const int error = errno;
    ::close(fd);
    Fail("cannot write", path, error);
  }
  if (::close(fd) != 0) Fail("cannot write", path, errno);
}

void Replace(const std::string& path, const std::string& text) {
  CreateParent(path);
  const fs::path parent = fs::path(path).parent_path();
  // A short name of our own in the same folder (never derived from the target's name, which
  // may already be as long as the file system allows); O_EXCL, so it follows no link.
  std::string tmp = (parent.empty() ? fs::path(".") : parent) / ".ocpb-write-XXXXXX";
  const int fd = ::mkostemp(tmp.data(), O_CLOEXEC);
  if (fd < 0) Fail("cannot write a temporary file beside", path, errno);
  struct stat old {};
  const mode_t mode = ::stat(path.c_str(), &old) == 0 ? (old.st_mode & 07777) : NewFileMode();
  auto fail = [&](const char* what, int error) {
    ::close(fd);
    ::unlink(tmp.c_str());
    Fail(what, path, error);
  };
  if (::fchmod(fd, mode) != 0) fail("cannot write", errno);
  if (!WriteAll(fd, text)) fail("cannot write", errno);
  if (::fsync(fd) != 0) fail("cannot write", errno);
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(tmp.c_str());
    Fail("cannot write", path, error);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(tmp.c_str());
    Fail("cannot replace", path, error);
  }
}

}  // namespace

OutputTarget ClassifyOutput(const std::string& path) {
  OutputTarget out;
  out.path = path;
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return out;  // nothing there (or not yet reachable)
  if (S_ISLNK(st.st_mode)) {
    std::error_code ec;
    const fs::path target = fs::canonical(path, ec);
    if (ec || ::stat(target.c_str(), &st) != 0) {
      out.kind = OutputTarget::Kind::kRefused;
      out.why = "is a symbolic link to nothing (give the file itself)";
      return out;
    }
    out.path = target.string();
  }
  if (S_ISREG(st.st_mode)) return out;
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
    out.kind = OutputTarget::Kind::kWriteThrough;
    return out;
  }
  out.kind = OutputTarget::Kind::kRefused;
  out.why = S_ISDIR(st.st_mode)   ? "is a directory, not a file"
            : S_ISBLK(st.st_mode) ? "is a block device (results are written to files only)"
                                  : "is a socket (results are written to files only)";
  return out;
}

void WriteFileAtomically(const std::string& path, const std::string& text) {
  const OutputTarget target = ClassifyOutput(path);
  switch (target.kind) {
    case OutputTarget::Kind::kRefused:
      throw std::runtime_error("cannot write " + OneLine(path) + ": it " + target.why);
    case OutputTarget::Kind::kWriteThrough:
      WriteThrough(target.path, text);
      return;
    case OutputTarget::Kind::kReplace:
      Replace(target.path, text);
      return;
  }
}

void AppendLineDurably(const std::string& path, const std::string& line) {
  CreateParent(path);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) Fail("cannot append to", path, errno);
  struct stat st {};
  const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
  const off_t before = regular ? st.st_size : 0;
  // Back to the last whole record: what a failed append leaves behind.
  auto fail = [&](int error, bool open) {
    if (regular) {
      if (open) {
        (void)::ftruncate(fd, before);
      } else {
        (void)::truncate(path.c_str(), before);
      }
    }
    if (open) ::close(fd);
    throw std::runtime_error(
        "cannot append to " + OneLine(path) + ": " + std::strerror(error) +
        (regular ? " (the file keeps its records up to the last whole one)" : ""));
  };
  // One write() of the whole line: with O_APPEND it lands contiguously at the end.
  if (!WriteAll(fd, line + "\n")) fail(errno, true);
  if (regular && ::fsync(fd) != 0) fail(errno, true);
  if (::close(fd) != 0) fail(errno, false);
}

}  // namespace ocpb
