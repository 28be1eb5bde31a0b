// The shell and cache glue every flow of shadesim area shares (generic, iCE40, liberty): finding
// a program, running it with a progress line, the Yosys script around a flow, the RTL sources,
// atomic cache writes and work folders. No flow's figures are computed here.
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "sim/eda/common/missing_tool.h"

namespace shadesim {

// What every Yosys flow of a run reads: the program, the RTL sources in order, the chparam
// arguments of the unit's parameters and the Yosys version (all part of each flow's cache key).
struct FlowInputs {
  std::string yosys;
  std::vector<std::filesystem::path> files;
  std::string chparam;
  std::string yosys_version;
};

namespace flow_tools {

namespace fs = std::filesystem;

// Writes `text` to a unique temporary name in p's folder, then renames it into place: a reader
// (another shadesim on the same cache) sees the whole file or none.
void write_atomically(const fs::path& p, const std::string& text);

// The program `name` (a path, or looked up on PATH); MissingToolError naming `package` if absent.
std::string find_tool(const std::string& name, const std::string& package);

// The first line of `program --version`-like output (`args` after the program).
std::string tool_version(const std::string& program, const std::vector<std::string>& args);

// The RTL sources of `dir` in the fixed order Yosys reads them (rtl/files.f, else every *.sv,
// packages first, then by name: ABC's result depends on the netlist's order).
std::vector<fs::path> rtl_sources(const std::string& dir);

// Runs a tool (stdout and stderr to `log`); with `progress`, one line updated while it runs.
// Throws std::runtime_error naming the label, the exit status and the log's tail on failure.
void run_tool(const std::vector<std::string>& argv, const fs::path& log, const std::string& label,
              std::ostream* progress);

// read_verilog -sv of `files`, chparam (when given) on shade_unit, then `flow` with every
// @WORK@ replaced by the work folder.
std::string yosys_script(const std::vector<fs::path>& files, const std::string& chparam,
                         const std::string& flow, const fs::path& work);

// A fresh work folder under `cache_dir` (the temporary folder without a cache), named after the
// key; the caller removes it on success and keeps it (its logs) on failure.
fs::path make_work_folder(const std::string& cache_dir, const std::string& key);

// CPU seconds of the finished child processes so far (getrusage RUSAGE_CHILDREN).
double children_cpu_seconds();

}  // namespace flow_tools
}  // namespace shadesim
