// --coverage's report (sim/regress/regress_coverage.h).
#include "sim/regress/regress_coverage.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "sim/eda/common/build_paths.h"
#include "sim/eda/verilator/coverage.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/engines/fixed_text.h"
#include "sim/regress/regress_plan.h"

namespace shadesim {
// A named namespace, not an anonymous one: sim/ is compiled as unity files (CMakeLists.txt).
namespace regress_coverage_impl {

namespace fs = std::filesystem;

std::string percent(int hit, int total) {
  return total ? fixed_text(100.0 * hit / total, 1) + " %" : std::string("-");
}

// The coverage figures regress --json and the summary.json of OUT/coverage carry: totals over rtl/,
// per file, the files no run elaborated, and every user cover point with its count.
nlohmann::json coverage_json(const CoverageSummary& sum, size_t runs) {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& f : sum.files) {
    files.push_back({{"file", fs::relative(f.path, source_dir()).string()},
                     {"lines", f.lines},
                     {"lines_hit", f.lines_hit},
                     {"toggles", f.toggles},
                     {"toggles_hit", f.toggles_hit},
                     {"elaborated", f.elaborated}});
  }
  nlohmann::json not_elaborated = nlohmann::json::array();
  for (const auto& f : sum.files_without_points)
    not_elaborated.push_back(fs::relative(f, source_dir()).string());
  nlohmann::json packages = nlohmann::json::array();
  for (const auto& f : sum.packages) packages.push_back(fs::relative(f, source_dir()).string());
  nlohmann::json points = nlohmann::json::array();
  int hit = 0;
  for (const auto& u : sum.user) {
    hit += u.count > 0;
    points.push_back({{"name", u.name}, {"count", u.count}});
  }
  return {{"runs", runs},
          {"rtl_lines", sum.lines},
          {"rtl_lines_hit", sum.lines_hit},
          {"rtl_line_pct", sum.line_pct()},
          {"rtl_toggles", sum.toggles},
          {"rtl_toggles_hit", sum.toggles_hit},
          {"rtl_toggle_pct", sum.toggle_pct()},
          {"user_points", sum.user.size()},
          {"user_points_hit", hit},
          {"files", files},
          {"files_without_points", not_elaborated},
          {"packages", packages},
          {"user_cover_points", points}};
}

}  // namespace regress_coverage_impl

namespace fs = std::filesystem;

bool report_coverage(const std::vector<RunRecord>& records, const fs::path& out,
                     const RegressOptions& o, nlohmann::json* summary) {
  std::vector<std::string> dats;
  std::vector<std::string>
      without;  // runs that ran and left no coverage (killed, crashed, plain build)
  for (const auto& r : records) {
    const fs::path dat = fs::path(r.dir) / "coverage.dat";
    if (!r.dir.empty() && fs::exists(dat)) {
      dats.push_back(dat.string());
    } else if (r.status != "skipped") {
      without.push_back(r.spec.id() + " (" + r.status + ")");
    }
  }
  for (const auto& w : without)
    std::cout << "regress: coverage: no coverage file from run " << w << '\n';
  const fs::path dir = out / "coverage";
  fs::create_directories(dir);
  const fs::path rtl_dir = fs::path(source_dir()) / "rtl";
  const std::vector<std::string> rtl_files = rtl_source_files();
  const std::vector<CoverageExclusion> exclusions = list_exclusions(rtl_files);
  {
    std::ofstream ex(dir / "exclusions.txt");
    for (const auto& e : exclusions) {
      ex << fs::relative(e.file, source_dir()).string() << ':' << e.first_line << '-' << e.last_line
         << ": " << e.reason << '\n';
    }
  }
  if (dats.empty()) {
    std::cout << "regress: coverage: FAIL: no run wrote a coverage file\n";
    return false;
  }
  const fs::path merged = dir / "merged.dat", info = dir / "coverage.info",
                 annotated = dir / "annotated";
  merge_coverage(dats, merged.string(), info.string(), annotated.string());
  const CoverageSummary sum = summarize_coverage(merged.string(), rtl_dir.string(), rtl_files);

  std::cout << "\nregress: coverage of " << dats.size() << " run(s), merged into "
            << merged.string() << '\n'
            << "  " << std::left << std::setw(28) << "file" << std::right << std::setw(8) << "lines"
            << std::setw(10) << "line %" << std::setw(10) << "toggles" << std::setw(10)
            << "toggle %" << '\n';
  for (const auto& f : sum.files) {
    std::cout << "  " << std::left << std::setw(28) << fs::relative(f.path, source_dir()).string()
              << std::right << std::setw(8)
              << (std::to_string(f.lines_hit) + "/" + std::to_string(f.lines)) << std::setw(10)
              << regress_coverage_impl::percent(f.lines_hit, f.lines) << std::setw(10)
              << (std::to_string(f.toggles_hit) + "/" + std::to_string(f.toggles)) << std::setw(10)
              << regress_coverage_impl::percent(f.toggles_hit, f.toggles)
              << (f.elaborated ? "" : "  (no run elaborated it: its code lines count, none hit)")
              << '\n';
  }
  std::cout << "  " << std::left << std::setw(28) << "rtl/ (total)" << std::right << std::setw(8)
            << (std::to_string(sum.lines_hit) + "/" + std::to_string(sum.lines)) << std::setw(10)
            << regress_coverage_impl::percent(sum.lines_hit, sum.lines) << std::setw(10)
            << (std::to_string(sum.toggles_hit) + "/" + std::to_string(sum.toggles))
            << std::setw(10) << regress_coverage_impl::percent(sum.toggles_hit, sum.toggles)
            << '\n';
  for (const auto& f : sum.packages) {
    std::cout << "  no points (a package: constants and constant functions, nothing to run): "
              << fs::relative(f, source_dir()).string() << '\n';
  }
  for (const auto& f : sum.files) {
    if (!f.elaborated || f.uncovered_lines.empty() || fs::path(f.path).parent_path() != rtl_dir)
      continue;
    std::ifstream src(f.path);
    std::vector<std::string> text;
    for (std::string l; std::getline(src, l);) text.push_back(l);
    for (int l : f.uncovered_lines) {
      const std::string code = l >= 1 && static_cast<size_t>(l) <= text.size() ? text[l - 1] : "";
      std::cout << "  uncovered " << fs::relative(f.path, source_dir()).string() << ':' << l << ": "
                << code.substr(code.find_first_not_of(" \t") == std::string::npos
                                   ? 0
                                   : code.find_first_not_of(" \t"))
                << '\n';
    }
  }
  int user_hit = 0;
  for (const auto& u : sum.user) user_hit += u.count > 0;
  std::cout << "  user cover points: " << user_hit << " of " << sum.user.size() << " hit\n";
  for (const auto& u : sum.user) {
    std::cout << "    " << (u.count > 0 ? "hit    " : "MISSED ") << std::left << std::setw(30)
              << u.name << std::right << std::setw(10) << u.count << "  "
              << fs::relative(u.file, source_dir()).string() << ':' << u.line << '\n';
  }
  std::cout << "  exclusions (" << exclusions.size()
            << ", the RTL's coverage_off pragmas): " << (dir / "exclusions.txt").string() << '\n'
            << "  lcov: " << info.string()
            << "; annotated sources (%000000: never run): " << annotated.string() << '\n';
  *summary = regress_coverage_impl::coverage_json(sum, dats.size());
  std::ofstream(dir / "summary.json") << summary->dump(2) << '\n';
  if (o.coverage_min < 0) return true;
  const bool met = sum.lines > 0 && sum.line_pct() >= o.coverage_min;
  std::cout << "regress: coverage: rtl/ line coverage " << fixed_text(sum.line_pct(), 2) << " % "
            << (met ? ">= " : "is below ") << "--coverage-min " << number_text(o.coverage_min)
            << " %" << (met ? "" : ": FAIL") << '\n';
  return met;
}

}  // namespace shadesim
