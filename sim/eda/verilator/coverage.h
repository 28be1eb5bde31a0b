// RTL coverage of a regression: the runs' Verilator coverage files (covered builds,
// sim/eda/verilator/rtl_build.h) merged with verilator_coverage, summarized per source file and
// listed where uncovered.
//
// What counts (Verilator 5.006's point types, each point a counter):
//   line    the "line" and "branch" points of --coverage-line. A source line is code when some
//           such point names it (a point names every line of its block); it is covered when one
//           of the points that name it counted at least once.
//   toggle  --coverage-toggle's points, one per signal bit: covered when it toggled at least once.
//   user    the named cover properties of sim/harness/shade_cover.sv (--coverage-user).
// Only elaborated code has points. A generate branch no configuration of the run instantiates
// has none and is not counted; a whole rtl/ module no run elaborates counts as 0 %: its code
// lines (every non-blank line from `module` to `endmodule` that is not only a comment, more than
// Verilator would instrument) join the line total, none hit. A package (shade_pkg: constants
// and constant functions, which Verilator does not instrument) has no points and is named.
//
// Exclusions are `/* verilator coverage_off */ // reason` ... `/* verilator coverage_on */`
// pragmas in the RTL (Verilator then makes no points there); list_exclusions() reads them back
// with their reasons, and a pragma without a reason is an error.
#pragma once

#include <string>
#include <vector>

namespace shadesim {

struct CoverageFile {
  std::string path;  // as the .dat names it (absolute)
  int lines = 0, lines_hit = 0;
  int toggles = 0, toggles_hit = 0;
  std::vector<int> uncovered_lines;
  bool elaborated = true;  // false: no run elaborated it; its code lines count, none hit
};

struct CoverPoint {
  std::string name, file;
  int line = 0;
  long long count = 0;
};

struct CoverageSummary {
  std::vector<CoverageFile> files;                // sorted by path
  std::vector<CoverPoint> user;                   // merged over instances, sorted by name
  std::vector<std::string> files_without_points;  // rtl/ modules no run elaborated (0 %)
  std::vector<std::string> packages;              // rtl/ packages: no points, not counted
  int lines = 0, lines_hit = 0, toggles = 0, toggles_hit = 0;  // over `rtl_dir` only
  double line_pct() const { return lines ? 100.0 * lines_hit / lines : 0.0; }
  double toggle_pct() const { return toggles ? 100.0 * toggles_hit / toggles : 0.0; }
};

struct CoverageExclusion {
  std::string file;
  int first_line = 0, last_line = 0;
  std::string reason;
};

// Parses a Verilator coverage .dat (merged or not); throws std::runtime_error naming the file and
// line of anything it cannot read. Totals count the files under `rtl_dir` only.
CoverageSummary summarize_coverage(const std::string& dat_path, const std::string& rtl_dir,
                                   const std::vector<std::string>& rtl_files);

// The coverage_off ... coverage_on regions of the files, with the reason beside each pragma;
// throws std::runtime_error naming the file and line of a pragma without a reason or an
// unmatched one.
std::vector<CoverageExclusion> list_exclusions(const std::vector<std::string>& files);

// verilator_coverage: merges `inputs` into `merged`, writes lcov `info`, annotates into
// `annotate_dir`. Throws std::runtime_error with the tool's output when a step fails.
void merge_coverage(const std::vector<std::string>& inputs, const std::string& merged,
                    const std::string& info, const std::string& annotate_dir);

}  // namespace shadesim
