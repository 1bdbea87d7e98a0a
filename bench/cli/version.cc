#include "bench/cli/version.h"

#include <IpoptConfig.h>
#include <nlopt.hpp>

#include <fmt/format.h>

namespace ocpb {

std::string CompilerVersion() {
#if defined(__clang__)
  return fmt::format("clang {}.{}.{}", __clang_major__, __clang_minor__, __clang_patchlevel__);
#elif defined(__GNUC__)
  return fmt::format("g++ {}.{}.{}", __GNUC__, __GNUC_MINOR__, __GNUC_PATCHLEVEL__);
#else
  return "unknown";
#endif
}

std::string IpoptVersion() {
#ifdef IPOPT_VERSION
  return IPOPT_VERSION;
#else
  return "unknown";
#endif
}

std::string NloptVersion() {
  return fmt::format(
      "{}.{}.{}", nlopt::version_major(), nlopt::version_minor(), nlopt::version_bugfix());
}

std::string VersionString() {
  return fmt::format("ocpbench {} (commit {}, {}, Ipopt {}, NLopt {})",
                     OCPB_VERSION,
                     GitCommit(),
                     CompilerVersion(),
                     IpoptVersion(),
                     NloptVersion());
}

}  // namespace ocpb
