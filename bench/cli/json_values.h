// Numbers, vectors and matrices to and from JSON, the way every OCPBench record writes them.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/field_sample.h"
#include "core/option_value.h"
#include "core/types.h"

namespace ocpb {

/// A finite number, or null for NaN and infinities (no JSON form: "not computed" / "never").
nlohmann::json JsonNumber(double v);
/// [v0, v1, ...] with JsonNumber entries.
nlohmann::json JsonVector(const Vec& v);
/// Rows of `m` (its first `rows` rows; all when rows < 0) as arrays of JsonNumber.
nlohmann::json JsonRows(const Mat& m, int rows = -1);
/// An option value as JSON: number (a number that is not finite as its text, "inf"), integer,
/// boolean, text or array; null when empty.
nlohmann::json JsonOptionValue(const OptionValue& v);
/// A JSON scalar or array of numbers as an OptionValue (as a suite file gives it). Throws
/// std::invalid_argument "WHERE: must be a number, boolean, text or list of numbers" for
/// objects, nested arrays or null.
OptionValue OptionValueFromJson(const nlohmann::json& j, const std::string& where);

/// {"x": [...], "y": [...], QUANTITY: rows of values, "spacing": h, "note": ...}: a record's
/// s_map.
nlohmann::json FieldSampleJson(const FieldSample& field);

/// The median of the values that are not NaN (NaN when there is none).
double Median(std::vector<double> values);

}  // namespace ocpb
