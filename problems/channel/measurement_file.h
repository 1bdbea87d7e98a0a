// Channel measurements from a CSV file (`ocpbench channel predict --measurements FILE`).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace ocpb {

/// Measured channel values at positions in the workspace.
struct MeasurementSet {
  std::vector<Eigen::Vector2d> positions;  ///< metres
  std::vector<double> values_db;           ///< channel gain in dB (received dBm for 0 dBm sent)
};

/// Parses the CSV format
///
///   # comments and blank lines are ignored
///   x_m,y_m,gain_db          <- this header, exactly, first non-comment line
///   12.5,30.1,-78.2
///   ...
///
/// Every row has three finite numbers; at least 3 and at most 1,000,000 rows. Throws
/// InputError (an std::invalid_argument) "SOURCE:LINE: COLUMN: rule" on the first violation.
/// Coincident positions are accepted here; the predictor documents how it treats them.
MeasurementSet ParseMeasurementsCsv(std::string_view text, const std::string& source);

/// The largest measurement file LoadMeasurementsCsv reads: 64 MiB (a million rows of three
/// numbers, with room for comments), refused by its size before reading.
inline constexpr std::size_t kMaxMeasurementFileBytes = std::size_t{64} << 20;

/// Throws std::invalid_argument "SOURCE: measurement K at (x, y) lies outside the workspace
/// [x_lo, x_hi] x [y_lo, y_hi]" for the first position outside the rectangle (edges included);
/// K counts the data rows from 1.
void CheckMeasurementsInside(const MeasurementSet& set,
                             const Eigen::Vector2d& lo,
                             const Eigen::Vector2d& hi,
                             const std::string& source);

/// Reads (ReadInputFile: at most kMaxMeasurementFileBytes, so an endless input such as
/// /dev/zero is refused) and parses a file; throws InputError when it cannot be read.
MeasurementSet LoadMeasurementsCsv(const std::string& path);

}  // namespace ocpb
