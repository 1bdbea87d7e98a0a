#include "problems/channel/measurement_file.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/input_file.h"

namespace ocpb {
namespace {

constexpr size_t kMaxRows = 1000000;

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

bool ParseNumber(std::string_view field, double* out) {
  field = Trim(field);
  if (field.empty()) return false;
  // std::from_chars for double is in GCC 12's libstdc++; it rejects leading '+', so allow it.
  if (field.front() == '+') field.remove_prefix(1);
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, *out);
  return ec == std::errc() && ptr == end && std::isfinite(*out);
}

}  // namespace

MeasurementSet ParseMeasurementsCsv(std::string_view text, const std::string& source) {
  MeasurementSet set;
  bool header_seen = false;
  size_t line_no = 0;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    const std::string_view raw = text.substr(0, nl);
    text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
    ++line_no;
    const std::string_view line = Trim(raw);
    if (line.empty() || line.front() == '#') continue;
    const int at = static_cast<int>(line_no);
    if (!header_seen) {
      if (line != "x_m,y_m,gain_db") {
        throw InputError(source, at, "header", "expected 'x_m,y_m,gain_db'");
      }
      header_seen = true;
      continue;
    }
    static const char* const kColumns[3] = {"x_m", "y_m", "gain_db"};
    double v[3];
    std::string_view rest = line;
    for (int i = 0; i < 3; ++i) {
      const size_t comma = rest.find(',');
      if ((i < 2) != (comma != std::string_view::npos)) {
        throw InputError(source, at, "", "expected 3 comma-separated numbers x_m,y_m,gain_db");
      }
      const std::string_view field = rest.substr(0, comma);
      if (!ParseNumber(field, &v[i])) {
        throw InputError(source,
                         at,
                         kColumns[i],
                         "'" + OneLine(Trim(field).substr(0, 64)) + "' is not a finite number");
      }
      rest.remove_prefix(comma == std::string_view::npos ? rest.size() : comma + 1);
    }
    if (set.positions.size() >= kMaxRows) {
      throw InputError(source, at, "", "more than 1000000 measurements");
    }
    set.positions.emplace_back(v[0], v[1]);
    set.values_db.push_back(v[2]);
  }
  if (!header_seen) throw InputError(source, 0, "", "empty measurement file (no header)");
  if (set.positions.size() < 3) {
    throw InputError(
        source, 0, "", "need at least 3 measurements, got " + std::to_string(set.positions.size()));
  }
  return set;
}

void CheckMeasurementsInside(const MeasurementSet& set,
                             const Eigen::Vector2d& lo,
                             const Eigen::Vector2d& hi,
                             const std::string& source) {
  for (size_t k = 0; k < set.positions.size(); ++k) {
    const Eigen::Vector2d& q = set.positions[k];
    if (q.x() >= lo.x() && q.x() <= hi.x() && q.y() >= lo.y() && q.y() <= hi.y()) continue;
    std::ostringstream os;
    os << source << ": measurement " << k + 1 << " at (" << q.x() << ", " << q.y()
       << ") lies outside the workspace [" << lo.x() << ", " << hi.x() << "] x [" << lo.y() << ", "
       << hi.y() << "]";
    throw std::invalid_argument(os.str());
  }
}

MeasurementSet LoadMeasurementsCsv(const std::string& path) {
  return ParseMeasurementsCsv(ReadInputFile(path, kMaxMeasurementFileBytes, "measurement file"),
                              OneLine(path));
}

}  // namespace ocpb
