// shadesim area's liberty flow: the unit mapped onto a standard-cell library (default: OSU's
// 0.18 um osu018, Debian's qflow-tech-osu018) and timed with OpenSTA (Debian's opensta, `sta`).
//
//   Yosys     the flat flow's read and chparam; synth -flatten -top shade_unit; dfflibmap
//             -liberty L; abc -D D -liberty L with an ABC script of structural choices and
//             delay mapping (fraig, scorr, &synch2, &dch, &nf -D D, buffer -p, upsize -D D,
//             dnsize -D D, stime -p; sim/eda/sta/liberty_flow.cpp); opt_clean; setundef -zero
//             (osu018 has no tie cells; OpenSTA takes the constants); splitnets -ports (OpenSTA
//             2019 rejects a concatenation on an assign's left side); rename -top; write_json.
//   buffering every net over LibertyOptions::max_fanout (8) cell input pins gets a tree of the
//   library's strongest
//             buffer (sim/eda/sta/fanout_buffer.h: ABC does not buffer the flip-flops' outputs),
//             then Yosys writes the Verilog (write_verilog -noattr -noexpr).
//   OpenSTA   read_liberty; read_verilog; link_design shade_unit; a clock of
//             LibertyOptions::period_ns (4 ns) on clk_i under the constraints of
//             sim/eda/sta/sta_constraints.h (clock uncertainty, the ports' driving cell, load
//             and delays);
//             report_checks -path_delay max (the worst path of each group), report_worst_slack.
//
// Fmax = 1000 / (period - worst slack) MHz: the critical path's arrival (from the launching
// clock edge, so clock-to-Q included) plus the endpoint's setup (or recovery) time and the
// clock uncertainty, at a fixed
// analysis period so the figure does not depend on a guessed target. ABC's delay target D is
// that period less the library's flip-flop overhead, measured by OpenSTA on two of the library's
// plain flip-flops in a row (clock-to-Q into setup; osu018 DFFPOSX1: 0.3 ns), so ABC aims at the
// logic between registers.
//
// Area: the sum of the liberty `area` of every cell of the buffered netlist (um^2 for osu018),
// also in NAND2 equivalents (area / the library's smallest NAND2's area, read from the liberty).
// No wire load (osu018 has no wire-load model), no placement, the library's one (typical)
// corner.
//
// Table memories (the exponent LUT's mem_q) are register files of the library's cells: synth's
// memory_map turns each into flip-flops, write decoding and read multiplexers, mapped, counted
// and timed like the rest of the unit, so the paths into the table's address and out of its
// data are in Fmax (an untimed blackbox "SRAM macro" would leave them out).
//
// The power flow's seam: LibertyReport::netlist_path is the buffered netlist (kept in the cache
// as liberty-netlist-<key>.v), flip_flop_q_nets() maps its flip-flop instances to their output
// nets, and sta_setup_tcl() is the read / link / clock / delay preamble this flow times with.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "sim/eda/common/flow_tools.h"
#include "sim/eda/sta/fanout_buffer.h"
#include "sim/eda/sta/liberty.h"
#include "sim/eda/sta/sta_constraints.h"

namespace shadesim {

constexpr const char* kDefaultLiberty = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib";
constexpr const char* kDefaultLibertyPackage = "qflow-tech-osu018";

struct LibertyOptions {
  std::string liberty_path;    // empty: the flow is not run
  std::string sta = "sta";     // program name (on PATH) or path
  double period_ns = 4.0;      // the analysis clock (see Fmax above)
  int max_fanout = 8;          // the buffering rule's limit of cell input pins per net
  StaConstraints constraints;  // the clock's uncertainty, the ports' drive and load (sta/)
};

// One cell (or port) on the critical path, and the net it drives.
struct LibertyPathCell {
  std::string instance, cell, net;  // cell "in" / "out" for a port
  int fanout = -1;
  double delay_ns = 0, time_ns = 0;
};

struct LibertyReport {
  std::string library;       // the liberty's library (NAME)
  std::string liberty_path;  // the file read
  std::string key;           // this flow's cache key
  bool from_cache = false;
  std::string sta_version;
  // Area of the buffered netlist, table RAM macros apart.
  double area_um2 = 0;
  std::string nand2_cell;  // the NAND2 the equivalents count in (osu018: NAND2X1)
  double nand2_area_um2 = 0;
  int64_t cells = 0, flip_flops = 0;
  FanoutBufferResult buffering;
  // Timing.
  double period_ns = 0, worst_slack_ns = 0, fmax_mhz = 0;
  std::string overhead_cell;  // the flip-flop the overhead was measured on
  double flip_flop_overhead_ns = 0, abc_delay_ps = 0;
  ResolvedConstraints constraints;  // what the timing ran under (sim/eda/sta/sta_constraints.h)
  std::string path_from, path_to, path_group;  // register (Q net) or port names
  double path_arrival_ns = 0, path_setup_ns = 0;
  std::vector<LibertyPathCell> path;
  // The power flow's input: the buffered Verilog netlist (module shade_unit) in the cache.
  std::string netlist_path;
  double seconds = 0;  // wall time of the flow when it ran (it runs beside the other syntheses)
  std::vector<std::string> warnings;

  double nand2_equivalents() const { return nand2_area_um2 > 0 ? area_um2 / nand2_area_um2 : 0; }
};

// The liberty to use: `requested`, or `default_path` when empty. Throws MissingToolError naming
// kDefaultLiberty's Debian package when the default is missing, std::runtime_error naming the
// file when a requested one is.
std::string resolve_liberty(const std::string& requested,
                            const std::string& default_path = kDefaultLiberty);

// A run of the flow: everything its figures depend on, and its cache key.
struct LibertyRun {
  FlowInputs flow;
  LibertyOptions options;
  std::string sta, sta_version;
  std::string key;
};
// Finds sta (MissingToolError naming opensta), hashes the liberty's content and the scripts.
LibertyRun prepare_liberty_run(const FlowInputs& flow, const LibertyOptions& o);

// Where the flow keeps Yosys's log of the mapping in cache_dir (liberty-log-<key>.txt), for
// the power flow's fsm_recoded_registers().
std::string liberty_log_path(const std::string& cache_dir, const std::string& key);

// The cached report of `run` in cache_dir (liberty-<key>.json, with its netlist), if complete.
std::optional<LibertyReport> cached_liberty(const LibertyRun& run, const std::string& cache_dir);

// Runs the flow in `work` (a folder of its own) and, with a cache_dir, stores the entry and the
// netlist there. Throws std::runtime_error naming the tool's log when a tool fails.
LibertyReport run_liberty_flow(const LibertyRun& run, const flow_tools::fs::path& work,
                               const std::string& cache_dir);

std::string liberty_report_to_json(const LibertyReport& r);  // one JSON object, no newline
LibertyReport liberty_report_from_json(const std::string& text, const std::string& source);

// Flip-flop (and latch) instance -> the net on its state output (Q; QN when it has only that),
// in a Verilog netlist Yosys wrote (escaped names without their backslash: "u_decoder.pos_q[1]").
std::map<std::string, std::string> flip_flop_q_nets(const std::string& netlist_v,
                                                    const LibertyLibrary& lib);

// The Tcl that reads `liberty` and `netlist_v` and links shade_unit.
std::string sta_read_tcl(const std::string& liberty, const std::string& netlist_v);
// sta_read_tcl, then the clock (period_ns on clk_i) and the ports under `constraints`
// (sim/eda/sta/constraints.tcl): the preamble every timing of the netlist shares. With `spef`
// (shadesim layout's routed parasitics), read_spef after them: the same constraints, post-route.
std::string sta_setup_tcl(const std::string& liberty, const std::string& netlist_v,
                          double period_ns, const ResolvedConstraints& constraints,
                          const std::string& spef = "");

}  // namespace shadesim
