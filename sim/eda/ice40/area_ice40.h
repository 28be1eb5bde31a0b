// shadesim area's iCE40 flow: synth_ice40's resources (SB_LUT4, SB_DFF*, SB_CARRY,
// SB_RAM40_4K), whether they fit an HX8K, and where they do, nextpnr-ice40's Fmax of clk_i out of
// context: the unit inside a generated register shell (fmax_shell) so its port count does not
// limit placement.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "model/rtl_parameters.h"
#include "sim/eda/common/content_hash.h"
#include "sim/eda/common/flow_tools.h"

namespace shadesim {

struct Ice40Area {
  int64_t lut4 = 0, dff = 0, carry = 0, ram4k = 0;
  static constexpr int64_t kHx8kLogicCells = 7680;
  static constexpr int64_t kHx8kRam4k = 32;
  bool fits_hx8k = false;          // false: see fit_note
  std::string fit_note;            // plain words: fits, or by how much it does not
  std::optional<double> fmax_mhz;  // nextpnr-ice40's post-route Fmax of clk_i
  std::string pnr_note;            // why there is no Fmax (no fit, --no-pnr, nextpnr failed)
  // nextpnr's post-route critical path: "net FIRST -> net LAST (L ns logic, R ns routing)", the
  // nets leaving the launching register and entering the capturing one (the unit's own nets
  // inside the shell's instance); empty where there is no Fmax or the cache entry was written
  // before it was recorded.
  std::string critical_path;
};

namespace ice40_flow {

// The synth_ice40 Yosys flow (after read_verilog and chparam): the commands of synth_ice40.ys
// beside this header; it writes @WORK@/ice40_stat.json.
std::string synth_script();
// Adds to a cache key everything of place and route the figures depend on besides nextpnr's
// version (its arguments, the shell and its script; the fields of the keys before the split).
void add_place_and_route_recipe(ContentHash& key);

// The resources in @WORK@/ice40_stat.json and whether they rule out an HX8K.
void read_synthesis(const flow_tools::fs::path& work, Ice40Area& a);

// The last "Critical path report" of a nextpnr log (the post-route one): its first and last net
// and the logic / routing line, as Ice40Area::critical_path; "" when there is none.
std::string read_critical_path(const std::string& log);

// Places and routes the unit in its Fmax shell on an HX8K for a.fmax_mhz. Returns whether the
// work folder must be kept: a failed placement, whose log says why (a finding, not an error;
// the shell's synthesis failing is the flow's fault and throws).
bool place_and_route(const FlowInputs& in, const std::string& nextpnr,
                     const std::vector<VerilogParameter>& parameters,
                     const flow_tools::fs::path& work, std::ostream* progress, Ice40Area& a);

// The register shell's Verilog (exposed for tests).
std::string fmax_shell_verilog(const std::vector<VerilogParameter>& parameters);

}  // namespace ice40_flow
}  // namespace shadesim
