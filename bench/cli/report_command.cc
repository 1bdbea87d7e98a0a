// `ocpbench report DIR [NEW] [--out SITE] [--compare-json FILE]`: a suite's results as a static
// site (report_site.h). Every input and the output place are checked before any page is written;
// the site is written into a temporary folder beside SITE and renamed over it at the end, so a
// failed run never leaves half a site where a good one was.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "bench/cli/compare.h"
#include "bench/cli/compare_report.h"
#include "bench/cli/json_input.h"
#include "bench/cli/output_place.h"
#include "bench/cli/report_model.h"
#include "bench/cli/report_site.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;

// The site folder as an absolute, normal path without a trailing separator: "site/", "." and
// "a/.." name a folder whose own name the temporary and the aside folders are made from.
fs::path SiteFolder(const std::string& out) {
  fs::path p = fs::absolute(out).lexically_normal();
  if (p.filename().empty() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p;
}

using json = nlohmann::json;

struct ReportArgs {
  std::vector<std::string> dirs;
  std::string out, compare_json;
  std::vector<std::string> ignore_options;
  OptionMap thresholds;  ///< as given, resolved by CompareThresholdSchema()
};

std::string Absolute(const std::string& path) {
  return fs::weakly_canonical(fs::absolute(path)).lexically_normal().string();
}

// True when `inner` is `outer` or lies below it (both absolute, normalized).
bool Within(const std::string& inner, const std::string& outer) {
  const fs::path rel = fs::path(inner).lexically_relative(outer);
  return !rel.empty() && *rel.begin() != "..";
}

// The files a site is built from: the records, suite.json and shards.json of a folder, and its
// figures (copied into the site).
std::vector<std::string> InputFiles(const ReportInput& in) {
  std::vector<std::string> files{in.records_path};
  std::error_code ec;
  if (fs::is_directory(in.path, ec)) {
    for (const char* name : {"suite.json", "shards.json"}) {
      const fs::path p = fs::path(in.path) / name;
      if (fs::exists(p, ec)) files.push_back(p.string());
    }
    for (const std::string& f : in.figures) {
      files.push_back((fs::path(in.path) / "figures" / f).string());
    }
  }
  return files;
}

// The output folder: replaced as a whole, so it may hold no input, and it may only be a folder
// an earlier report wrote (or an empty one): --out never deletes anyone's other files.
void CheckOutPlace(const std::string& out,
                   const std::vector<ReportInput>& inputs,
                   const std::string& compare_json) {
  FilePlan plan;
  for (const ReportInput& in : inputs) {
    for (const std::string& f : InputFiles(in)) plan.Input(f, "DIR " + in.path);
  }
  if (!compare_json.empty()) plan.Input(compare_json, "--compare-json");
  plan.Output((fs::path(out) / "index.html").string(), "--out");
  plan.Check();
  const std::string site = Absolute(out);
  for (const ReportInput& in : inputs) {
    std::vector<std::string> files = InputFiles(in);
    files.push_back(in.path);
    if (!compare_json.empty()) files.push_back(compare_json);
    for (const std::string& f : files) {
      if (Within(Absolute(f), site)) {
        throw std::invalid_argument(
            fmt::format("report: --out {}: holds the input {} (the site replaces its whole folder; "
                        "choose a folder that holds no input, such as DIR/report)",
                        out,
                        f));
      }
    }
  }
  std::error_code ec;
  if (fs::exists(out, ec)) {
    if (!fs::is_directory(out, ec)) {
      throw std::invalid_argument("report: --out " + out + ": is a file (expected a folder)");
    }
    const bool empty = fs::is_empty(out, ec);
    if (!empty && !fs::exists(fs::path(out) / kReportMarker, ec)) {
      throw std::invalid_argument(fmt::format(
          "report: --out {}: a folder that is not a report of ocpbench (no {}): only an empty "
          "folder or an earlier report is replaced; choose another folder",
          out,
          kReportMarker));
    }
  }
  const fs::path parent = SiteFolder(out).parent_path();
  CheckOutputFolder(parent.string(), "--out");
}

// `ocpbench compare --json`'s document, checked enough to draw: its parts and its suite.
json LoadCompareJson(const std::string& path, const ReportInput& input) {
  const json j = LoadJsonFile(path, kMaxRecordBytes, "--compare-json");
  if (!j.is_object()) throw std::invalid_argument("--compare-json " + path + ": not a JSON object");
  for (const char* part : {"base", "new", "verdict", "thresholds"}) {
    if (!j.contains(part) || !j[part].is_object()) {
      throw std::invalid_argument(fmt::format(
          "--compare-json {}: {}: must be an object (the file `ocpbench compare --json` writes)",
          path,
          part));
    }
  }
  for (const char* part : {"cases", "only_in_base", "only_in_new", "methods", "profiles"}) {
    if (!j.contains(part) || !j[part].is_array()) {
      throw std::invalid_argument(fmt::format(
          "--compare-json {}: {}: must be an array (the file `ocpbench compare --json` writes)",
          path,
          part));
    }
  }
  const json& suite = j["new"]["suite"];
  if (input.suite_named && suite.is_string() && !suite.get<std::string>().empty() &&
      suite.get<std::string>() != input.suite) {
    throw std::invalid_argument(fmt::format(
        "--compare-json {}: new.suite: '{}' is not the report's suite '{}' (mixed suites)",
        path,
        suite.get<std::string>(),
        input.suite));
  }
  return j;
}

CompareSide SideOf(const ReportInput& in) {
  CompareSide side;
  side.path = in.path;
  side.records_path = in.records_path;
  side.suite = in.suite_named ? in.suite : "";
  side.records = in.records;
  side.dropped_partial = in.dropped_partial;
  return side;
}

// Writes the site into a fresh folder beside `out`, then puts it in place of `out`: the old
// site is renamed aside first and removed last, so that a failure leaves it where it was.
void WriteInPlace(const std::string& out,
                  const ReportInput& input,
                  const std::optional<json>& comparison) {
  const fs::path target = SiteFolder(out);
  const fs::path parent = target.parent_path();
  const std::string stem = "." + target.filename().string();
  const fs::path temp = parent / fmt::format("{}.tmp-{}", stem, getpid());
  const fs::path old = parent / fmt::format("{}.old-{}", stem, getpid());
  fs::remove_all(temp);
  fs::create_directories(temp);
  try {
    WriteReportSite(temp.string(), input, comparison);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(temp, ec);
    throw;
  }
  std::error_code ec;
  const bool replace = fs::exists(target, ec);
  try {
    if (replace) fs::rename(target, old);
  } catch (...) {
    fs::remove_all(temp, ec);
    throw;
  }
  try {
    fs::rename(temp, target);
  } catch (...) {
    if (replace) fs::rename(old, target, ec);
    fs::remove_all(temp, ec);
    throw;
  }
  if (replace) fs::remove_all(old, ec);
}

void RunReport(const ReportArgs& args) {
  if (args.dirs.empty() || args.dirs.size() > 2) {
    throw std::invalid_argument(fmt::format(
        "report: DIR: give one result folder, or two of one suite (BASE NEW: the compare view); "
        "got {}",
        args.dirs.size()));
  }
  if (args.dirs.size() == 2 && !args.compare_json.empty()) {
    throw std::invalid_argument(
        "report: --compare-json: give it with one DIR (NEW), or give BASE NEW without it");
  }
  if (args.dirs.size() == 1 && (!args.thresholds.empty() || !args.ignore_options.empty())) {
    throw std::invalid_argument(
        "report: the compare flags (--cost, --cpu-ratio, ..., --ignore-option) apply to BASE NEW "
        "only (a --compare-json file was computed with its own)");
  }
  for (const std::string& d : args.dirs) FilePlan().Input(d, "DIR");
  if (!args.compare_json.empty())
    FilePlan().Input(args.compare_json, "--compare-json");  // empty, link loops
  CompareOptions options;
  options.thresholds = ResolveCompareThresholds(args.thresholds);
  options.ignore_options = args.ignore_options;
  std::vector<ReportInput> inputs;
  for (const std::string& d : args.dirs) inputs.push_back(LoadReportInput(d));
  ReportInput& shown = inputs.back();  // the site shows NEW; BASE only in the comparison
  // A records file names no suite (its name stands in): only two named suites can differ, as
  // in `ocpbench compare`.
  if (inputs.size() == 2 && inputs[0].suite_named && inputs[1].suite_named &&
      inputs[0].suite != inputs[1].suite) {
    throw std::invalid_argument(fmt::format(
        "report: BASE {} is suite '{}', NEW {} is suite '{}': a compare view needs two runs of "
        "one suite (mixed suites)",
        inputs[0].path,
        inputs[0].suite,
        inputs[1].path,
        inputs[1].suite));
  }
  if (inputs.size() == 2 && !shown.suite_named && inputs[0].suite_named) {
    shown.suite = inputs[0].suite;  // NEW is a records file: the suite is BASE's
  }
  std::optional<json> comparison;
  if (!args.compare_json.empty()) comparison = LoadCompareJson(args.compare_json, shown);
  std::string out = args.out;
  if (out.empty()) {
    std::error_code ec;
    if (!fs::is_directory(shown.path, ec)) {
      throw std::invalid_argument("report: --out: required when DIR " + shown.path +
                                  " is a records file (the default is DIR/report)");
    }
    out = (fs::path(shown.path) / "report").string();
  }
  CheckOutPlace(out, inputs, args.compare_json);
  if (inputs.size() == 2) {
    comparison = CompareJson(Compare(SideOf(inputs[0]), SideOf(inputs[1]), options));
  }
  WriteInPlace(out, shown, comparison);
  std::cerr << fmt::format("ocpbench: report: {} cases, {} problem pages{} in {}\n",
                           shown.records.size(),
                           ReportProblems(shown).size(),
                           comparison ? ", a compare view" : "",
                           (fs::path(out) / "index.html").string());
}

}  // namespace

void AddReportCommand(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "A suite's results as a static web site (no network needed): an index with every case, "
      "a page per problem, and with BASE NEW a compare view");
  cmd->add_option("dirs",
                  args->dirs,
                  "DIR: a result folder of ocpbench run or merge (or a records file); BASE NEW: "
                  "two runs of one suite, the site of NEW with the comparison")
      ->required();
  cmd->add_option("--out", args->out, "the site's folder (default DIR/report; NEW/report)");
  cmd->add_option("--compare-json",
                  args->compare_json,
                  "the compare view from this file of `ocpbench compare --json` (with one DIR)");
  cmd->add_option("--ignore-option",
                  args->ignore_options,
                  "compare view: match cases without this option (as ocpbench compare)");
  // The compare view's thresholds are `ocpbench compare`'s, with the same flags.
  for (const OptionSpec& spec : CompareThresholdSchema().specs()) {
    std::string flag = "--" + spec.name;
    for (char& ch : flag) ch = ch == '_' ? '-' : ch;
    const std::string key = spec.name;
    cmd->add_option_function<std::string>(
        flag,
        [args, key](const std::string& v) { args->thresholds.Set(key, v); },
        fmt::format("compare view: {} (default {})", spec.doc, spec.DefaultText()));
  }
  cmd->callback([args]() { RunReport(*args); });
}

}  // namespace ocpb
