// The files of `ocpbench report`'s site (report_site.h).
#include "bench/cli/report_site.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "bench/cli/report_model.h"

namespace ocpb {

// The script and style sheet (bench/cli/report_assets/), embedded at build time
// (cmake/EmbedFiles.cmake).
extern const char kReportScript[];
extern const char kReportStyle[];

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

void WriteText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("report: " + path.string() + ": could not be written");
}

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// A page's data as a script that sets window.OCPB_DATA. Text the records hold that is not valid
// UTF-8 is replaced rather than refused: a report is for reading.
std::string DataScript(const json& data) {
  return "window.OCPB_DATA = " + data.dump(-1, ' ', false, json::error_handler_t::replace) + ";\n";
}

// Every page is the same shell: the navigation, a <main> the script fills, the page's data and
// the script. The title is the page's until the script sets it.
std::string Page(const std::string& kind,
                 const std::string& title,
                 const std::string& data_file,
                 bool has_compare) {
  std::string nav = "<a href=\"index.html\">suite</a>";
  if (has_compare) nav += "<a href=\"compare.html\">compare</a>";
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         "<title>" +
         HtmlEscape(title) +
         "</title>\n"
         "<link rel=\"icon\" href=\"data:,\">\n"
         "<link rel=\"stylesheet\" href=\"assets/report.css\">\n</head>\n"
         "<body data-page=\"" +
         kind +
         "\">\n"
         "<header><nav>OCPBench report &nbsp; " +
         nav +
         "</nav></header>\n"
         "<main id=\"main\"><noscript>This report draws its tables and figures with JavaScript "
         "(in the page itself: nothing is fetched from the network).</noscript></main>\n"
         "<script src=\"data/" +
         data_file +
         "\"></script>\n"
         "<script src=\"assets/report.js\"></script>\n</body>\n</html>\n";
}

}  // namespace

void WriteReportSite(const std::string& dir,
                     const ReportInput& input,
                     const std::optional<json>& comparison) {
  const fs::path root(dir);
  const bool has_compare = comparison.has_value();
  WriteText(root / "assets" / "report.js", kReportScript);
  WriteText(root / "assets" / "report.css", kReportStyle);
  WriteText(root / "data" / "index.js", DataScript(SuiteIndexData(input)));
  WriteText(root / "index.html",
            Page("index", input.suite + ": OCPBench report", "index.js", has_compare));
  for (const std::string& problem : ReportProblems(input)) {
    const std::string page = ProblemPageName(problem);
    const std::string data = page.substr(0, page.size() - 5) + ".js";
    WriteText(root / "data" / data, DataScript(ProblemPageData(input, problem)));
    WriteText(root / page, Page("problem", problem + ": OCPBench report", data, has_compare));
  }
  if (has_compare) {
    WriteText(root / "data" / "compare.js", DataScript(*comparison));
    WriteText(root / "compare.html",
              Page("compare", "compare " + input.suite + ": OCPBench report", "compare.js", true));
  }
  // The input's figures travel with the site, so that it stays whole when moved or zipped.
  if (!input.figures.empty()) {
    fs::create_directories(root / "figures");
    for (const std::string& name : input.figures) {
      fs::copy_file(fs::path(input.path) / "figures" / name, root / "figures" / name);
    }
  }
  WriteText(root / kReportMarker,
            "A site written by `ocpbench report`; a new report may replace this folder.\n");
}

}  // namespace ocpb
