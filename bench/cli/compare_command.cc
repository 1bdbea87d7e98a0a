// `ocpbench compare BASE NEW`: the comparison of bench/cli/compare.h from the command line.
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/cli/app.h"
#include "bench/cli/compare.h"
#include "bench/cli/compare_report.h"
#include "bench/cli/io.h"
#include "bench/cli/output_place.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;

struct CompareArgs {
  std::string base, next, json_path, markdown_path;
  std::vector<std::string> ignore_options;
  OptionMap thresholds;  ///< as given, resolved by CompareThresholdSchema()
};

// The files a side is read from: its records and, for a result folder, its suite.json.
void AddInputs(const CompareSide& side, const std::string& what, FilePlan* plan) {
  plan->Input(side.records_path, what);
  std::error_code ec;
  if (fs::is_directory(side.path, ec)) {
    plan->Input((fs::path(side.path) / "suite.json").string(), what);
  }
}

// An output file must be writable where it is (checked before the comparison is computed).
void CheckOutput(const std::string& flag, const std::string& path) {
  if (path.empty()) return;
  if (fs::is_directory(path)) {
    throw std::invalid_argument(flag + " '" + path + "': is a folder (expected a file name)");
  }
  CheckOutputFile(path, flag);
}

void RunCompare(const CompareArgs& args) {
  CompareOptions options;
  options.thresholds = ResolveCompareThresholds(args.thresholds);
  options.ignore_options = args.ignore_options;
  // The paths themselves first: an empty one, a loop of links (FilePlan refuses them).
  FilePlan().Input(args.base, "BASE");
  FilePlan().Input(args.next, "NEW");
  const CompareSide base = LoadCompareSide(args.base);
  const CompareSide next = LoadCompareSide(args.next);
  // No output may be an input of the comparison, nor the other output.
  FilePlan plan;
  AddInputs(base, "BASE", &plan);
  AddInputs(next, "NEW", &plan);
  if (!args.json_path.empty()) plan.Output(args.json_path, "--json");
  if (!args.markdown_path.empty()) plan.Output(args.markdown_path, "--markdown");
  plan.Check();
  CheckOutput("--json", args.json_path);
  CheckOutput("--markdown", args.markdown_path);
  const Comparison comparison = Compare(base, next, options);
  const std::string markdown = CompareMarkdown(comparison);
  if (!args.json_path.empty()) {
    WriteFileAtomically(args.json_path, CompareJson(comparison).dump(1) + "\n");
  }
  if (!args.markdown_path.empty()) WriteFileAtomically(args.markdown_path, markdown);
  std::cout << markdown;
  std::cerr << fmt::format(
      "ocpbench: compare: {} matched cases: {} regressed, {} improved; {} methods' CPU "
      "regressed; {} only in BASE, {} only in NEW\n",
      comparison.cases.size(),
      comparison.RegressedCases(),
      comparison.ImprovedCases(),
      comparison.RegressedMethods(),
      comparison.only_in_base.size(),
      comparison.only_in_new.size());
  if (comparison.HasRegression()) ReportSomeFailed();
}

}  // namespace

void AddCompareCommand(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Two runs of one suite side by side, case by case, regressions first (exit 1 when a "
      "regression beyond the thresholds is found)");
  cmd->add_option("base", args->base, "BASE: a result folder of ocpbench run, or a records file")
      ->required();
  cmd->add_option("new", args->next, "NEW: the same, after the change")->required();
  cmd->add_option("--json", args->json_path, "also write the comparison as JSON to this file");
  cmd->add_option(
      "--markdown", args->markdown_path, "also write the Markdown report (stdout) to this file");
  cmd->add_option("--ignore-option",
                  args->ignore_options,
                  "match cases without this solver or transcription option (repeatable): an "
                  "A/B test of the option");
  // One flag per threshold, named after its key (ocpbench describe compare lists them).
  for (const OptionSpec& spec : CompareThresholdSchema().specs()) {
    std::string flag = "--" + spec.name;
    for (char& ch : flag) ch = ch == '_' ? '-' : ch;
    const std::string key = spec.name;
    cmd->add_option_function<std::string>(
        flag,
        [args, key](const std::string& v) { args->thresholds.Set(key, v); },
        fmt::format("{} (default {})", spec.doc, spec.DefaultText()));
  }
  cmd->callback([args]() { RunCompare(*args); });
}

}  // namespace ocpb
