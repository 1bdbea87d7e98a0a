// libFuzzer target: the measurement-file loader must turn any input into either measurements or
// a std::invalid_argument, never a crash or another exception.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "problems/channel/measurement_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const ocpb::MeasurementSet set = ocpb::ParseMeasurementsCsv(text, "fuzz");
    // Whatever is accepted satisfies the documented contract.
    if (set.positions.size() < 3 || set.positions.size() != set.values_db.size()) std::abort();
    for (double v : set.values_db) {
      if (!std::isfinite(v)) std::abort();
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
