// bender-cli compare CASE_A CASE_B -o report.pdf [--json] [--png DIR] [--plan PLAN]: the flow
// of two CFD cases compared (the original vessel and a bent candidate), as a table on stdout
// and the report a surgeon brings to the planning meeting (issue 23).

#include "CliCommand.h"
#include "CliParsing.h"
#include "HeadlessDisplay.h"

#include "CfdCaseComparison.h"
#include "CfdCaseFile.h"
#include "CfdFlowResults.h"
#include "FileIdentity.h"
#include "FlowReport.h"
#include "StringUtil.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

namespace
{
const char* const Details =
  "Compares two CFD cases that have run (bender-cli cfd-case --run: CASE/results/flow.json and "
  "surface.vtp): CASE_A is the reference (the vessel as it is), CASE_B the candidate (the bent "
  "vessel). Prints the table: pressure drop, flow split and flow rate per outlet (matched by "
  "name; an outlet of one case only is listed), wall shear stress mean, maximum and 99th "
  "percentile, the wall areas with WSS below 0.4 Pa and above 15 Pa, mesh cells and the "
  "solver's state; each with A, B, B - A and (B - A) / |A|. A row is highlighted (*) when the "
  "difference is above 5 % of A and above the quantity's floor (pressure 1 Pa, split 1 point, "
  "flow 1 ml/min, WSS 0.05 Pa, area 1 mm^2), for an outlet of one case only, and for a run "
  "that did not converge. Then each branch's bend angle, length and minimal inscribed radius "
  "in A and B (centerlines of both surfaces, branches matched by end names) and, with --plan, "
  "the plan's name and warps.\n"
  "\n"
  "Writes the report (a PDF: provenance, table, plan, bend measures, mesh and convergence, both "
  "shapes coloured by pressure and by wall shear stress from the same viewpoints on one shared "
  "colour scale) atomically; with --png, each picture as a PNG too. Without a display a "
  "private Xvfb is started when installed.\n"
  "\n"
  "exit status: 0 written, 1 a case not run, results missing or not matching, or a file that "
  "cannot be written, 2 usage error";

struct CompareArguments
{
  bender::CompareCfdCasesOptions options;
  std::string output, pngFolder;
  bool json = false;
};

// Every file compare reads: the output must be none of them.
std::vector<std::string> Inputs(const CompareArguments& a)
{
  std::vector<std::string> inputs{ a.options.plan };
  for (const std::string& folder : { a.options.caseA, a.options.caseB })
  {
    const std::filesystem::path dir(folder);
    const std::filesystem::path results = dir / bender::kCfdResultsFolder;
    inputs.push_back(folder);
    inputs.push_back((dir / bender::kCfdCaseJson).string());
    inputs.push_back((results / bender::kCfdFlowJson).string());
    inputs.push_back((results / bender::kCfdSurfaceResults).string());
  }
  return inputs;
}

int RunCompare(CompareArguments a)
{
  for (const std::string& input : Inputs(a))
  {
    if (!input.empty() && bender::SameFile(input, a.output))
    {
      return bender::CommandError(
        "compare", a.output + ": refusing to overwrite an input (" + input + ")");
    }
  }
  if (bender::LowerExtension(a.output) != ".pdf")
  {
    return bender::CommandError("compare", a.output + ": the report is a PDF (name it .pdf)");
  }
  const bender::CfdCaseComparison comparison = bender::CompareCfdCases(a.options);
  if (const std::string problem = bender::EnsureHeadlessDisplay(); !problem.empty())
  {
    return bender::CommandError("compare", a.output + ": " + problem);
  }
  bender::FlowReportOptions report;
  report.output = a.output;
  report.pngFolder = a.pngFolder;
  const bender::FlowReportResult written = bender::WriteFlowReport(comparison, report);
  if (a.json)
  {
    nlohmann::ordered_json j =
      nlohmann::ordered_json::parse(bender::CfdCaseComparisonToJson(comparison));
    j["report"] = { { "pdf", written.pdf }, { "pages", written.pages }, { "pngs", written.pngs } };
    std::fputs((j.dump(2) + "\n").c_str(), stdout);
    return 0;
  }
  std::string text = bender::CfdComparisonToText(comparison.table) + "\n" +
    bender::BendMeasuresToText(comparison) + "report: " + written.pdf + " (" +
    std::to_string(written.pages) + " pages)\n";
  for (const std::string& png : written.pngs)
  {
    text += "picture: " + png + "\n";
  }
  std::fputs(text.c_str(), stdout);
  return 0;
}
} // namespace

void bender::AddCompareCommand(CLI::App& cli)
{
  auto a = std::make_shared<CompareArguments>();
  CLI::App* compare = AddCommand(cli,
    "compare",
    "compare the flow of two CFD cases (original and candidate) and write the report (PDF)",
    Details,
    [a] { return RunCompare(*a); });
  compare->add_option("CASE_A", a->options.caseA, "the reference case (the vessel as it is)")
    ->required();
  compare->add_option("CASE_B", a->options.caseB, "the candidate case (the bent vessel)")
    ->required();
  compare->add_option("-o,--output", a->output, "the report")->required()->type_name("REPORT.pdf");
  compare->add_flag("--json", a->json, "print one JSON object instead of the table");
  compare->add_option("--png", a->pngFolder, "also write each picture as a PNG into DIR")
    ->type_name("DIR");
  compare->add_option("--plan", a->options.plan, "the plan that made B from A (.bender.json)")
    ->type_name("PLAN");
  compare->add_option("--label-a", a->options.labelA, "what A is called")->capture_default_str();
  compare->add_option("--label-b", a->options.labelB, "what B is called")->capture_default_str();
  compare->add_flag_callback(
    "--no-bend-measures",
    [a] { a->options.measureBends = false; },
    "do not compute the centerlines of both shapes (their branch measures)");
}
