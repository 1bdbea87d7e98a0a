#include "bench/cli/json_values.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ocpb {

using nlohmann::json;

json JsonNumber(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json JsonVector(const Vec& v) {
  json a = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(JsonNumber(v[i]));
  return a;
}

json JsonRows(const Mat& m, int rows) {
  const Eigen::Index n = rows < 0 ? m.rows() : std::min<Eigen::Index>(rows, m.rows());
  json out = json::array();
  for (Eigen::Index i = 0; i < n; ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j) row.push_back(JsonNumber(m(i, j)));
    out.push_back(std::move(row));
  }
  return out;
}

json JsonOptionValue(const OptionValue& v) {
  switch (v.kind()) {
    case OptionValue::Kind::kEmpty:
      return nullptr;
    case OptionValue::Kind::kNumber:
      // "inf" (no limit) is a legal value of some options; JSON has no infinity.
      return std::isfinite(v.number()) ? json(v.number()) : json(v.ToText());
    case OptionValue::Kind::kInteger:
      return v.integer();
    case OptionValue::Kind::kBool:
      return v.boolean();
    case OptionValue::Kind::kText:
      return v.text();
    case OptionValue::Kind::kVector: {
      json a = json::array();
      for (double x : v.vector()) a.push_back(JsonNumber(x));
      return a;
    }
  }
  return nullptr;
}

OptionValue OptionValueFromJson(const json& j, const std::string& where) {
  if (j.is_boolean()) return j.get<bool>();
  if (j.is_number_integer()) {
    if (j.is_number_unsigned() && j.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX)) {
      return static_cast<double>(j.get<std::uint64_t>());
    }
    return static_cast<long long>(j.get<std::int64_t>());
  }
  if (j.is_number_float()) return j.get<double>();
  if (j.is_string()) return j.get<std::string>();
  if (j.is_array()) {
    std::vector<double> values;
    for (const json& x : j) {
      if (!x.is_number()) {
        throw std::invalid_argument(where + ": a list must hold numbers only");
      }
      values.push_back(x.get<double>());
    }
    return values;
  }
  throw std::invalid_argument(where + ": must be a number, boolean, text or list of numbers");
}

json FieldSampleJson(const FieldSample& f) {
  return json{{"x", f.x},
              {"y", f.y},
              {f.quantity, JsonRows(f.values)},
              {"spacing", f.spacing},
              {"note", f.note}};
}

double Median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace ocpb
