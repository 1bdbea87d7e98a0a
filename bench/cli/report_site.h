// The files of `ocpbench report`'s site: HTML pages that each load their data (data/*.js) and
// the one script that draws them (assets/report.js, with assets/report.css), all relative links,
// so that the folder works opened from disk, served by any static server or zipped.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "bench/cli/report_model.h"

namespace ocpb {

/// The file that marks a folder as a site `ocpbench report` wrote: only such a folder (or an
/// empty one) is replaced by a new report, so that --out never deletes someone's other files.
inline constexpr const char* kReportMarker = ".ocpbench-report";

/// Writes the site of `input` into `dir` (an empty folder that exists): index.html, one page per
/// problem, and, when `comparison` is given (CompareJson's document), compare.html; the data of
/// each page under data/, the script and style sheet under assets/, the input folder's figures
/// copied under figures/, and the marker. Throws std::runtime_error naming the file on a failed
/// write.
void WriteReportSite(const std::string& dir,
                     const ReportInput& input,
                     const std::optional<nlohmann::json>& comparison);

}  // namespace ocpb
