// libFuzzer target: the --initial-guess loader must turn any file into either controls or a
// std::invalid_argument naming the file, never a crash, a hang or another exception. The input
// goes through a file, the way `ocpbench solve --initial-guess FILE` reads it.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "bench/cli/initial_guess.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = [] {
    const char* tmp = std::getenv("TMPDIR");
    return std::string(tmp ? tmp : "/tmp") + "/ocpb-initial-guess-fuzz-" +
           std::to_string(::getpid()) + ".json";
  }();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const ocpb::ControlTrajectory guess = ocpb::ReadInitialGuess(path);
    // Whatever is accepted is a usable control: finite values on a grid of >= 1 interval.
    if (guess.nu() < 1 || guess.grid().intervals() < 1) std::abort();
    const ocpb::Vec u = guess(guess.grid().t0());
    for (Eigen::Index i = 0; i < u.size(); ++i) {
      if (!std::isfinite(u[i])) std::abort();
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
