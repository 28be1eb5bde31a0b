// The HTML page of `shadesim report`: one self-contained file (images as data: URIs, styles
// inline, no script, nothing fetched) with a section per report kind, each saying so when it has
// no input.
#pragma once

#include <string>
#include <vector>

#include "sim/eda/common/tool_versions.h"
#include "sim/report/report_inputs.h"

namespace shadesim {

// A plot drawn by scripts/plot from one input: the PNG written, or why there is none.
struct ReportPlot {
  std::string input_path;
  std::string png_path;
  std::string error;
};

struct ReportPage {
  ReportInputs inputs;
  std::vector<ReportPlot> plots;
  std::vector<ToolVersion> tools;
  std::vector<std::string> run_notes;  // what --run ran, and what failed
  std::string generated;               // when, in UTC
};

// The section headings, in page order (the test looks for each).
const std::vector<std::string>& report_sections();

std::string report_html(const ReportPage& page);

}  // namespace shadesim
