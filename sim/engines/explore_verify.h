// explore --verify and --emit-jobs (sim/engines/explore.cpp runs them on the chosen point): a point
// co-simulated on every scene in RTL by this shadesim's own `regress`, or the runs that would do
// it written as job lines.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/unit_config.h"

namespace shadesim {

// One point to co-simulate in RTL: its configuration as a value and as the config file written
// into --out (config_to_json), so an on-demand build can take either.
struct PointToVerify {
  std::string name;  // "chosen", "start", "pareto_3"
  UnitConfig config;
  std::string config_file;
};

// The RTL verdict of one point: `shadesim regress` of every scene on the point's configuration,
// both backends, under regress's default gaps and back-pressure.
struct Verification {
  std::string name;
  bool verified = false;  // every run passed: 0 pixel and 0 cycle mismatches
  long passed = 0, mismatched = 0, errors = 0, skipped = 0;
  std::string report;  // regress's --json
  std::string log;
};

// --emit-jobs: the regress runs --verify would do, one command per line (regress --emit-jobs
// writes them, so a line is the same as any regress job line), each point's results into
// <out>/verify/<point>/ for `shadesim merge`.
void emit_verify_jobs(const std::vector<PointToVerify>& points,
                      const std::vector<std::string>& scenes, const std::string& out_dir,
                      const std::string& jobs_file);

// Co-simulates each point on every scene through the on-demand Verilated builds (the RTL of a
// configuration not yet built is Verilated into the build cache first) by running this very
// shadesim's `regress` as a child, and marks the point verified or not.
std::vector<Verification> verify_in_rtl(const std::vector<PointToVerify>& points,
                                        const std::vector<std::string>& scenes,
                                        const std::string& out_dir);

nlohmann::json verification_json(const std::vector<Verification>& verified);

}  // namespace shadesim
