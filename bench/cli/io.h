// Writing results so that nothing already written is ever lost or left half-written.
#pragma once

#include <string>

namespace ocpb {

/// Writes `text` to `path` through a temporary file in the same directory and an atomic
/// rename; creates parent directories. Throws std::runtime_error with the path on failure.
void WriteFileAtomically(const std::string& path, const std::string& text);

/// Appends one line (a JSON record) to `path` and flushes it to disk (fsync) before returning,
/// so a killed run keeps every finished record whole. Creates parent directories.
void AppendLineDurably(const std::string& path, const std::string& line);

/// Reads a whole file; throws std::invalid_argument "cannot read FILE" when it cannot.
std::string ReadFile(const std::string& path);

}  // namespace ocpb
