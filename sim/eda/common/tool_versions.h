// The versions of the tools a run depends on, as found on this machine (for reports).
#pragma once

#include <string>
#include <vector>

namespace shadesim {

struct ToolVersion {
  std::string tool;
  std::string version;  // the tool's first version line, or "not found"
};

// verilator, g++, yosys, iverilog, systemc (pkg-config), python3 with matplotlib, chromium, and
// the compiler this shadesim was built with. Runs each tool's version option; never throws.
std::vector<ToolVersion> find_tool_versions();

}  // namespace shadesim
