// An RTL build as the harness sees it: a unit configuration, whether it can inject the
// deliberate faults (sim/harness/fault_site.h), and a name for reports. The named builds the tests
// share live in sim/harness/builds.json; any other UnitConfig is built on demand
// (sim/eda/verilator/rtl_build.h). Verilog parameters come from the one mapping in
// model/rtl_parameters.h.
#pragma once

#include <string>
#include <vector>

#include "model/rtl_parameters.h"
#include "model/unit_config.h"

namespace shadesim {

// A build that can inject the harness's deliberate faults: sim/harness/faults/ bound into its
// shade_unit; which fault, and on which row, each run chooses (sim/harness/fault_site.h). No
// unit has them, and they change no Verilog parameter.
struct InjectedFaults {
  bool hooks = false;
  bool any() const { return hooks; }
};

struct RtlConfig {
  std::string name;
  UnitConfig unit;
  InjectedFaults faults;
  std::vector<std::string> backends;  // named builds: the backends the tests use
  // Non-empty: the gate-level netlist of `unit` (sim/engines/area_report.h unit_netlist: Yosys's
  // flat netlist, parameters baked in) is Verilated in place of rtl/; the build is keyed by its
  // contents. No fault hooks and no coverage in such a build.
  std::string netlist;
};

// The build a run simulates: a named build's fault hooks only when the run injects a fault. A
// run without one simulates the same unit without them, at the speed of a build that never had
// them: the hooks' force muxes on every cycle and the optimisation they switch off (-fno-dfg,
// sim/eda/verilator/rtl_recipe.cpp) slowed every run of grey_s428w (docs/history/benchmarks.md has
// the figures).
inline RtlConfig build_for_run(RtlConfig build, bool injects_fault) {
  if (!injects_fault) build.faults = InjectedFaults{};
  return build;
}

// The named builds of `path` (sim/harness/builds.json). Throws std::invalid_argument naming the
// file, the build and the field on malformed input.
std::vector<RtlConfig> load_named_builds(const std::string& path);

// The build called `name` in `path`, or an error listing the names there are.
RtlConfig named_build(const std::string& path, const std::string& name);

std::string fault_text(const InjectedFaults& faults);  // " fault-hooks", or ""

}  // namespace shadesim
