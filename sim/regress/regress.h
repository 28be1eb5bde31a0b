// shadesim regress's engine: the RTL regression, every scene x configuration x backend, with
// shards, job lines and resumed runs (sim/regress/regress.cpp). The command line that fills
// RegressOptions (and checks it): sim/cli/regress.cpp.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/regress/regress_stimulus.h"

namespace shadesim {

struct RegressOptions {
  std::vector<std::string> scenes;
  std::vector<std::string> random;        // --random SCENARIO: random runs after the scene runs
  bool random_only = false;               // --random-only: no scene runs
  std::vector<std::string> configs;       // named builds (--configs)
  std::vector<std::string> config_files;  // UnitConfig files (--config)
  std::vector<std::string> backends{"cpp", "systemc"};
  uint64_t seed = 1;
  int jobs = 0;  // 0: hardware threads
  int gap_pct = kRegressStimulus.gap_pct, max_gap = kRegressStimulus.max_gap,
      stall_pct = kRegressStimulus.stall_pct;
  std::string out_dir = "out/regress";
  std::string junit_path;
  std::string json_path;
  std::string cache;
  std::string optimization;  // quick | fast; empty: by each build's expected cycles
  std::string shard;         // I/N
  std::string emit_jobs;     // FILE: write one command per run instead of running
  std::string resume;        // DIR: run what DIR's plans name and DIR has no result for
  double timeout = 1800;     // seconds per run; 0: none
  uint64_t watchdog =
      0;              // cycles without pix_valid_o that count as a hang; 0: the harness's default
  std::string fault;  // SITE@Y: every run injects this deliberate fault (fault-hook builds)
  bool waves = false;
  bool list = false;
  bool coverage = false;      // covered builds; merge and report RTL coverage
  bool netlist = false;       // simulate Yosys's gate-level netlist in place of the RTL
  std::string netlist_cache;  // its cache folder; empty: <build>/netlist-cache
  double coverage_min = -1;   // --coverage-min PCT: exit 1 below this rtl/ line coverage
};

// Lists the named builds, writes --emit-jobs lines, or plans (or resumes), builds, runs and
// reports the regression; returns the exit code (1 on any failed run or no run, 128 + the signal
// when interrupted).
int run_regress(const RegressOptions& o);

}  // namespace shadesim
