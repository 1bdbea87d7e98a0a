// Reading the files a user hands OCPBench (suites, records read by --resume and merge, initial
// guesses, measurement CSVs): within a size limit, with one kind of error that names the file,
// the line and the field. Header-only, so that every layer (core, problems, bench) can use it.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ocpb {

/// `text` on one line: control characters (newline, carriage return, tab, escape, ...) written
/// as \n, \r, \t or \xNN, so that a message quoting an input never spans two lines.
inline std::string OneLine(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

/// An error in an input file, "FILE:LINE: FIELD: rule" (the line left out when it is not known,
/// 0; the field when empty). A std::invalid_argument, so that `ocpbench` exits 2 with it.
class InputError : public std::invalid_argument {
 public:
  InputError(const std::string& file, int line, const std::string& field, const std::string& rule)
      : std::invalid_argument(Format(file, line, field, rule)),
        file_(file),
        line_(line),
        field_(field),
        rule_(rule) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }
  const std::string& rule() const { return rule_; }

 private:
  static std::string Format(const std::string& file,
                            int line,
                            const std::string& field,
                            const std::string& rule) {
    std::string s = file;
    if (line > 0) s += ":" + std::to_string(line);
    s += ": ";
    if (!field.empty()) s += field + ": ";
    return s + rule;
  }
  std::string file_;
  int line_;
  std::string field_;
  std::string rule_;
};

/// The line (from 1) of byte `offset` of `text`.
inline int LineOfOffset(std::string_view text, std::size_t offset) {
  int line = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

/// `bytes` for messages: "512 bytes", "16 MiB", "1.5 GiB".
inline std::string InputSizeText(double bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int i = 0;
  while (bytes >= 1024.0 && i < 5) {
    bytes /= 1024.0;
    ++i;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, i == 0 ? "%.0f %s" : "%.3g %s", bytes, units[i]);
  return buffer;
}

/// The whole text of the input file `path` (`what` names its kind in messages: "suite file").
/// Throws InputError "PATH: rule" when it cannot be opened, is a directory, or holds more than
/// `max_bytes`: a regular file is refused by its size before anything is read; anything else (a
/// pipe, a device such as /dev/zero) is read up to max_bytes + 1 bytes and refused there, so an
/// endless input never exhausts memory.
inline std::string ReadInputFile(const std::string& path,
                                 std::size_t max_bytes,
                                 const std::string& what) {
  const std::string name = OneLine(path);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    throw InputError(name, 0, "", "cannot read this " + what + ": " + std::strerror(errno));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    throw InputError(name, 0, "", "cannot read this " + what + ": " + std::strerror(errno));
  }
  if (S_ISDIR(st.st_mode)) throw InputError(name, 0, "", "is a directory, not a " + what);
  const std::string limit =
      "; a " + what + " may hold at most " + InputSizeText(static_cast<double>(max_bytes));
  if (S_ISREG(st.st_mode) && static_cast<std::size_t>(st.st_size) > max_bytes) {
    throw InputError(
        name, 0, "", InputSizeText(static_cast<double>(st.st_size)) + " is too large" + limit);
  }
  std::string text;
  if (S_ISREG(st.st_mode)) text.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(name, 0, "", "cannot read this " + what + ": " + std::strerror(errno));
    }
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) {
      throw InputError(name, 0, "", "more input than allowed (reading stopped there)" + limit);
    }
  }
  return text;
}

}  // namespace ocpb
