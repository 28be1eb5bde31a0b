#include "sim/eda/common/tool_versions.h"

#include <regex>
#include <sstream>
#include <stdexcept>

#include "sim/eda/common/process.h"

namespace shadesim {
namespace {

// The first line a command prints that holds a version number (d.d; else the first non-empty
// line: wrappers such as Debian's chromium script may print a warning first), or "not found".
std::string version_line(const std::vector<std::string>& argv) {
  ProcessResult r;
  try {
    r = run_process(argv, "");
  } catch (const std::runtime_error&) {
    return "not found";
  }
  if (r.exit_code == 127) return "not found";
  if (r.exit_code != 0)
    return "not found (" + argv[1] + " exited with " + std::to_string(r.exit_code) + ")";
  static const std::regex version(R"(\d\.\d)");
  std::istringstream lines(r.output);
  std::string line, first;
  while (std::getline(lines, line)) {
    const size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos) continue;
    line = line.substr(start, line.find_last_not_of(" \t\r") + 1 - start);
    if (std::regex_search(line, version)) return line;
    if (first.empty()) first = line;
  }
  return first.empty() ? "(printed nothing)" : first;
}

// argv[0] as found on PATH (posix_spawn does not search it).
std::vector<std::string> on_path(std::vector<std::string> argv) {
  argv.insert(argv.begin(), "/usr/bin/env");
  return argv;
}

}  // namespace

std::vector<ToolVersion> find_tool_versions() {
  return {
      {"verilator", version_line(on_path({"verilator", "--version"}))},
      {"g++", version_line(on_path({"g++", "--version"}))},
      {"yosys", version_line(on_path({"yosys", "-V"}))},
      {"iverilog", version_line(on_path({"iverilog", "-V"}))},
      {"systemc", version_line(on_path({"pkg-config", "--modversion", "systemc"}))},
      {"python3 + matplotlib (scripts/plot's /usr/bin/python3)",
       version_line(on_path({"/usr/bin/python3", "-c",
                             "import sys, matplotlib; print(sys.version.split()[0], 'matplotlib', "
                             "matplotlib.__version__)"}))},
      {"chromium", version_line(on_path({"chromium", "--version"}))},
      {"shadesim built with", std::string("C++ ") + __VERSION__},
  };
}

}  // namespace shadesim
