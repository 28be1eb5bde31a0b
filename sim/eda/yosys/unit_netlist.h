// The unit's gate-level netlist from the generic Yosys flow, for simulation in place of the RTL.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "model/unit_config.h"

namespace shadesim {

// The gate-level netlist of `unit` that the flat flow measures, for simulation in place of the
// RTL (regress --netlist): the flat script above, then `write_verilog -noattr`. Parameters are
// baked in (chparam); no fault hooks (sim/harness/faults/ is never synthesised). Cached in
// `cache_dir` as netlist-<key>.v, the key hashing the parameters, the RTL sources' contents, the
// Yosys version and the script (like the area cache), with its stat beside it (netlist-<key>.json).
// The top's ports are checked against the ports the co-simulation glue drives (names and widths
// from the parameters).
struct NetlistOptions {
  std::string rtl_dir;    // empty: SHADESIM_RTL_DIR, else this source tree's rtl/
  std::string cache_dir;  // required
  std::string yosys = "yosys";
  std::ostream* progress = nullptr;
};
struct UnitNetlist {
  std::string path;  // the Verilog netlist
  std::string key;
  bool from_cache = false;
  int64_t cells = 0, flip_flops = 0, gate_equivalents = 0, ram_bits = 0;
  double seconds = 0;  // Yosys's wall time when it was made
};
UnitNetlist unit_netlist(const UnitConfig& unit, const NetlistOptions& options);
// The default netlist cache: <build>/netlist-cache.
std::string default_netlist_cache_dir();

}  // namespace shadesim
