// --coverage's report: the runs' coverage files merged into OUT/coverage/, the figures printed and
// written (regress --json, and summary.json in the output folder's coverage/), and the
// --coverage-min check.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "sim/regress/regress.h"
#include "sim/regress/regress_results.h"

namespace shadesim {

// --coverage: merges the runs' coverage files into OUT/coverage/ (merged.dat, coverage.info for
// lcov, annotated sources), prints line and toggle coverage per file, the uncovered lines of
// rtl/, the user cover points and the exclusions. Returns whether rtl/ line coverage meets
// --coverage-min (true without one).
bool report_coverage(const std::vector<RunRecord>& records, const std::filesystem::path& out,
                     const RegressOptions& o, nlohmann::json* summary);

}  // namespace shadesim
