// The memory a case (or an input it reads) may use, and the one refusal when an estimate says
// it would not fit. Header-only, so that every layer can check its own input-driven sizes.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <string>

namespace ocpb {

/// Half the physical memory (sysconf), 4 GiB when the system does not say: what one case, or
/// one input file read whole, may take.
inline double MemoryBudgetBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 4.0 * (1 << 30);
  return 0.5 * static_cast<double>(pages) * static_cast<double>(page_size);
}

/// `bytes` in decimal units for messages: "826 MB", "2.04 GB".
inline std::string MemoryText(double bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  int i = 0;
  while (bytes >= 1000.0 && i < 6) {
    bytes /= 1000.0;
    ++i;
  }
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.3g %s", bytes, units[i]);
  return buffer;
}

/// Throws std::invalid_argument "FIELD: WHAT need about X by OCPBench's estimate, beyond this
/// machine's memory budget of Y (half its physical memory)" when `need_bytes` exceeds
/// MemoryBudgetBytes(). `what` says what the estimate covers ("20000 measurements (the GP
/// prediction's covariance and its factor)").
inline void CheckMemoryEstimate(double need_bytes,
                                const std::string& field,
                                const std::string& what) {
  const double budget = MemoryBudgetBytes();
  if (!(need_bytes <= budget)) {
    throw std::invalid_argument(field + ": " + what + " need about " + MemoryText(need_bytes) +
                                " by OCPBench's estimate, beyond this machine's memory budget of " +
                                MemoryText(budget) + " (half its physical memory)");
  }
}

}  // namespace ocpb
