#include "sim/eda/area.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "model/exponent_lut.h"
#include "model/json_error.h"
#include "model/specular_units.h"
#include "model/text_file.h"
#include "sim/eda/content_hash.h"
#include "sim/eda/process.h"
#include "sim/eda/rtl_files.h"

#ifndef SHADESIM_SOURCE_DIR
#define SHADESIM_SOURCE_DIR "."
#endif

namespace shadesim {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::json;

// The Yosys scripts, minus the file list and the chparam arguments (both part of the key);
// @WORK@ stands for the run's work folder.
// Flat: the unit as it would be built; flattening lets Yosys drop what a module's neighbour
// never reads (e.g. the product bits above a wrapping series), so this is the headline figure.
constexpr const char* kFlatScript =
    "synth -flatten -top shade_unit\n"
    "abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX\n"
    "opt_clean\n"
    "tee -q -o @WORK@/flat_stat.json stat -json -tech cmos\n"
    "tee -q -o @WORK@/flat_ltp.txt ltp -noff\n";
// Table memories: synth's first half (to `fine`, where memory_map would turn them into
// flip-flops), then a dump of the $mem cells: their SIZE x WIDTH are the RAM bits kept out of GE
// (area.h). A run of its own: splitting the flat flow's synth at `fine` changes ABC's result by
// a few cells, and the flat figures must equal one plain synth.
constexpr const char* kMemoryScript =
    "synth -flatten -top shade_unit -run :fine\n"
    "tee -q -o @WORK@/flat_mem.txt dump t:$mem_v2 t:$mem\n";
// The netlist regress --netlist simulates: the flat flow's own result, written out.
constexpr const char* kNetlistWrite =
    "rename -top shade_unit\n"
    "write_verilog -noattr @WORK@/netlist.v\n";
// Breakdown: the same flow with the datapath modules kept as modules (their fixed_round /
// fixed_sat helpers are flattened into them), so stat says where the area goes. Across a kept
// boundary Yosys cannot drop unread logic, so this total is at least the flat one.
// `rename -top`: when hierarchy re-derives the chparam'd top (a submodule's ports became known
// only after its own derivation, as pixel_combine's gate_only_i), the top is left as
// $paramod...\shade_unit and `-top shade_unit` below would not find it.
constexpr const char* kBreakdownScript =
    "hierarchy -top shade_unit\n"
    "rename -top shade_unit\n"
    "setattr -mod -set keep_hierarchy 1 *span_setup *series_engine *specular_unit *pixel_combine\n"
    // shade_unit's control modules (rtl/files.f), each its own row.
    "setattr -mod -set keep_hierarchy 1 *cmd_decoder *coef_bank *span_queue *material_bank\n"
    "setattr -mod -set keep_hierarchy 1 *start_bank\n"
    // (setup_ctrl's one parameter stays in its name: $paramod\setup_ctrl\XY_BITS=...)
    "setattr -mod -set keep_hierarchy 1 *setup_ctrl* *engine_ctrl *slot_meta *out_reg\n"
    "synth -flatten -top shade_unit\n"
    "abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX\n"
    "opt_clean\n"
    "tee -q -o @WORK@/breakdown_stat.json stat -json -tech cmos -top shade_unit\n";
// synth_ice40's own steps up to its `check`, then that step without `autoname`, which only names
// wires (nextpnr does not need the names) and took most of Yosys's 14.6 minutes and 15 GB on
// multi's unit with 17-bit offsets.
constexpr const char* kIce40Script =
    "synth_ice40 -top shade_unit -run :check\n"
    "hierarchy -check\n"
    "tee -q -o @WORK@/ice40_stat.json stat -json\n"
    "check -noinit\n"
    "blackbox =A:whitebox\n"
    "write_json @WORK@/ice40.json\n";
// HX8K in its largest package (206 I/O); 12 MHz is only the target the report compares with.
constexpr const char* kPnrArgs = "--hx8k --package ct256 --freq 12 --timing-allow-fail";
// Fmax is measured out of context: the unit inside fmax_shell (fmax_shell_verilog below), which
// shifts one input pin into every input port and folds every output port into one output pin
// through a chain of registers, so no I/O count limits placement (a four-word command port
// alone is 256 pins, more than an HX8K has) and every output still matters. Only the unit's
// own logic lies between two registers of the shell on a path longer than one LUT.
constexpr const char* kShellScript =
    "synth_ice40 -top fmax_shell -run :check\n"
    "hierarchy -check\n"
    "check -noinit\n"
    "blackbox =A:whitebox\n"
    "write_json @WORK@/shell.json\n";
constexpr const char* kShellVersion = "fmax_shell v2";

void write_atomically(const fs::path& p, const std::string& text) {
  // A unique temporary name in the same folder, then rename(2): readers see all or nothing.
  const fs::path tmp = p.string() + ".tmp." + std::to_string(::getpid()) + "." +
                       std::to_string(std::chrono::steady_clock::now().time_since_epoch().count());
  write_text_file(tmp.string(), text);
  std::error_code ec;
  fs::rename(tmp, p, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error(p.string() + ": cannot rename into place: " + ec.message());
  }
}

std::string find_program(const std::string& name, const std::string& package) {
  auto executable = [](const fs::path& p) {
    return ::access(p.c_str(), X_OK) == 0 && fs::is_regular_file(p);
  };
  if (name.find('/') != std::string::npos) {
    if (executable(name)) return name;
  } else if (const char* path = std::getenv("PATH")) {
    std::stringstream ss(path);
    std::string dir;
    while (std::getline(ss, dir, ':')) {
      if (dir.empty()) continue;
      const fs::path p = fs::path(dir) / name;
      if (executable(p)) return p.string();
    }
  }
  throw MissingToolError(
      "'" + name + "' not found" + (name.find('/') != std::string::npos ? "" : " on PATH") +
      ": shadesim area needs it (Debian package " + package + "; scripts/setup installs it)");
}

std::vector<fs::path> rtl_sources(const std::string& dir) {
  // The one list (rtl/files.f); a tree from before it (--rtl-dir) is read whole, below.
  if (fs::exists(fs::path(dir) / "files.f")) return rtl_file_list(dir);
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_regular_file() && e.path().extension() == ".sv") files.push_back(e.path());
  }
  if (ec) throw std::runtime_error(dir + ": cannot list the RTL sources: " + ec.message());
  if (files.empty()) throw std::runtime_error(dir + ": no *.sv RTL sources");
  // Yosys resolves the hierarchy after reading every file, so the order only has to be fixed
  // (for the cache key), not dependency order; except that a package must be read before a file
  // that names it in a parameter declaration (the units' SPEC_PARAMS width is shade_pkg's).
  const auto is_package = [](const fs::path& f) {
    const std::string n = f.filename().string();
    return n.size() > 7 && n.compare(n.size() - 7, 7, "_pkg.sv") == 0;
  };
  std::sort(files.begin(), files.end(), [&](const fs::path& a, const fs::path& b) {
    if (is_package(a) != is_package(b)) return is_package(a);
    return a < b;
  });
  return files;
}

// Runs a tool, updating one progress line once a second while it works.
void run_tool(const std::vector<std::string>& argv, const fs::path& log, const std::string& label,
              std::ostream* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  auto job = std::async(std::launch::async, [&] { return run_process(argv, log.string()); });
  // On a terminal one line updated in place every second; in a log a line every 30 s.
  const bool terminal = progress == &std::cerr && ::isatty(STDERR_FILENO);
  int ticks = 0;
  while (job.wait_for(std::chrono::seconds(1)) != std::future_status::ready) {
    ++ticks;
    if (progress && (terminal || ticks % 30 == 0)) {
      const auto s =
          std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - t0);
      *progress << (terminal ? "\r" : "") << "[area] " << label << " ... " << s.count() << " s"
                << (terminal ? " " : "\n") << std::flush;
    }
  }
  const ProcessResult r = job.get();
  if (progress) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    *progress << (terminal ? "\r" : "") << "[area] " << label << " done in " << std::fixed
              << std::setprecision(1) << s << " s\n"
              << std::flush;
  }
  if (r.exit_code != 0) {
    std::string tail;
    try {
      const std::string text = read_text_file(log.string());
      const auto from = text.size() > 800 ? text.size() - 800 : 0;
      tail = text.substr(from);
    } catch (const std::exception&) {
    }
    throw std::runtime_error(label + " failed (exit " + std::to_string(r.exit_code) + "); log " +
                             log.string() + (tail.empty() ? "" : ":\n..." + tail));
  }
}

std::string yosys_script(const std::vector<fs::path>& files, const std::string& chparam,
                         const char* flow, const fs::path& work) {
  std::string body = flow;
  for (size_t at; (at = body.find("@WORK@")) != std::string::npos;)
    body.replace(at, 6, work.string());
  std::string s = "read_verilog -sv";
  for (const auto& f : files) s += " " + f.string();
  s += "\n";
  if (!chparam.empty()) s += "chparam " + chparam + " shade_unit\n";
  return s + body;
}

// "$paramod$0f50...\span_setup" -> "span_setup"; "\shade_unit" -> "shade_unit"; a module with
// one short parameter keeps it in its name: "$paramod\setup_ctrl\XY_BITS=s32'..." -> "setup_ctrl".
std::string base_module_name(const std::string& yosys_name) {
  const std::string short_paramod = "$paramod\\";
  if (yosys_name.rfind(short_paramod, 0) == 0) {
    const auto end = yosys_name.find('\\', short_paramod.size());
    return yosys_name.substr(short_paramod.size(), end == std::string::npos
                                                       ? std::string::npos
                                                       : end - short_paramod.size());
  }
  const auto bs = yosys_name.rfind('\\');
  return bs == std::string::npos ? yosys_name : yosys_name.substr(bs + 1);
}

bool is_flip_flop(const std::string& cell_type) {
  return (cell_type.rfind("$_", 0) == 0 && cell_type.find("DFF") != std::string::npos) ||
         cell_type.rfind("SB_DFF", 0) == 0;
}

// One module's figures, or the design's, in Yosys's `stat -json`.
struct StatSection {
  int64_t cells = 0;
  int64_t transistors = 0;
  bool transistors_partial = false;  // "N+": some cells (flip-flops) have no CMOS cost
  std::map<std::string, int64_t> by_type;
};

// A `stat -json` report: "modules" {name: {"num_cells", "num_cells_by_type" {type: n},
// "estimated_num_transistors" "N" or "N+" (only with -tech cmos)}} and "design", the top module
// with everything below it (as the text's "design hierarchy"). Names are spelled as the text
// spells them: "\shade_unit" is "shade_unit", "$paramod..." stays.
// Yosys 0.23 writes invalid JSON in two cases, neither of which the scripts above meet: when no
// top module is known (no -top, and no module with the `top` attribute that synth -top and
// synth_ice40 -top set), "modules" ends in a comma and "design" is missing; and when a module
// below the top instantiates a module of its own (the breakdown's kept modules instantiate none
// of each other), the text's nested hierarchy lines land between "modules" and "design".
struct StatReport {
  std::map<std::string, StatSection> modules;
  std::optional<StatSection> design;
};

std::string text_spelling(const std::string& yosys_id) {
  return yosys_id.rfind('\\', 0) == 0 ? yosys_id.substr(1) : yosys_id;
}

// "13330" or "13330+" (the "+": cells without a CMOS cost).
void read_transistors(const std::string& field, StatSection& s) {
  const bool partial = !field.empty() && field.back() == '+';
  const std::string digits = field.substr(0, field.size() - (partial ? 1 : 0));
  if (digits.empty() || digits.size() > 18 ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw std::runtime_error("estimated_num_transistors \"" + field + "\" is not a count");
  s.transistors = std::stoll(digits);
  s.transistors_partial = partial;
}

// `cmos`: the report is of `stat -tech cmos`, which must carry each transistor estimate.
StatSection read_stat_section(const Json& j, bool cmos) {
  StatSection s;
  s.cells = j.at("num_cells").get<int64_t>();
  for (const auto& [type, n] : j.at("num_cells_by_type").items())
    s.by_type[text_spelling(type)] += n.get<int64_t>();
  if (cmos) read_transistors(j.at("estimated_num_transistors").get<std::string>(), s);
  return s;
}

// Throws naming the file (and, for a section's missing or mistyped field, the section).
StatReport read_stat_json(const fs::path& p, bool cmos) {
  const std::string text = read_text_file(p.string());
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::exception& e) {
    const JsonTextError error = describe_json_error(text, e);
    throw std::runtime_error(p.string() + error.place + ": Yosys's stat -json is not valid JSON (" +
                             error.reason +
                             "); Yosys 0.23's is invalid when no top module is known or a module "
                             "below the top instantiates another");
  }
  StatReport r;
  std::string section = "the report";
  try {
    for (const auto& [name, m] : j.at("modules").items()) {
      section = "module " + text_spelling(name);
      r.modules[text_spelling(name)] = read_stat_section(m, cmos);
    }
    section = "design";
    if (j.contains("design")) r.design = read_stat_section(j.at("design"), cmos);
  } catch (const Json::exception& e) {
    throw std::runtime_error(p.string() + ": Yosys's stat -json, " + section + ": " +
                             describe_json_error(text, e).reason);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(p.string() + ": Yosys's stat -json, " + section + ": " + e.what());
  }
  if (r.modules.empty()) throw std::runtime_error(p.string() + ": no statistics from Yosys");
  return r;
}

const std::string& top_name(const StatReport& stat, const fs::path& p) {
  for (const auto& [name, sec] : stat.modules) {
    if (base_module_name(name) == "shade_unit") return name;
  }
  throw std::runtime_error(p.string() + ": Yosys statistics have no shade_unit module");
}

int64_t flip_flops_of(const StatSection& s) {
  int64_t n = 0;
  for (const auto& [type, count] : s.by_type) {
    if (is_flip_flop(type)) n += count;
  }
  return n;
}

// The transistors `stat -tech cmos` charged for the flip-flops of `s` (area.h: only the plain
// $_DFF_P_ / $_DFF_N_ have a cost in its table).
int64_t flip_flop_transistors_of(const StatSection& s) {
  int64_t n = 0;
  for (const auto& [type, count] : s.by_type) {
    if (type == "$_DFF_P_" || type == "$_DFF_N_") n += count * kYosysCmosPlainDffTransistors;
  }
  return n;
}

// Per-module rows from the kept-hierarchy stat: each module with its submodules folded in,
// instance counts from the top down, then the top's own glue.
void read_breakdown(const StatReport& stat, const fs::path& p, AreaReport& r) {
  struct Totals {
    int64_t cells = 0, transistors = 0, ffs = 0, logic = 0;
  };
  std::map<std::string, Totals> memo;
  auto is_module = [&](const std::string& type) { return stat.modules.count(type) > 0; };
  std::function<Totals(const std::string&)> total = [&](const std::string& name) -> Totals {
    if (auto f = memo.find(name); f != memo.end()) return f->second;
    const StatSection& sec = stat.modules.at(name);
    Totals t{sec.cells, sec.transistors, flip_flops_of(sec),
             sec.transistors - flip_flop_transistors_of(sec)};
    for (const auto& [type, n] : sec.by_type) {
      if (!is_module(type)) continue;
      const Totals sub = total(type);
      t.cells += n * (sub.cells - 1);  // each instance counts as one cell in sec.cells
      t.transistors += n * sub.transistors;
      t.ffs += n * sub.ffs;
      t.logic += n * sub.logic;
    }
    return memo[name] = t;
  };
  const StatSection& top = stat.modules.at(top_name(stat, p));
  r.modules.clear();
  int64_t glue_cells = top.cells;
  for (const auto& [type, n] : top.by_type) {
    if (!is_module(type)) continue;
    const Totals sub = total(type);
    glue_cells -= n;
    r.modules.push_back({base_module_name(type), static_cast<int>(n), sub.cells, sub.transistors,
                         sub.ffs, sub.logic});
  }
  r.modules.push_back({"shade_unit", 1, glue_cells, top.transistors, flip_flops_of(top),
                       top.transistors - flip_flop_transistors_of(top)});
  // The table memories sit in specular_unit (exponent_lut): their bits from the parameters,
  // checked against Yosys's count of the flat flow in check_ram().
  const int64_t ram_each = ram_bits_per_specular_unit(r.parameters);
  for (auto& m : r.modules) {
    if (m.module == "specular_unit") m.ram_bits_each = ram_each;
  }
  r.breakdown_cells = 0;
  for (const auto& m : r.modules) r.breakdown_cells += m.cells();
  if (stat.design && stat.design->cells != r.breakdown_cells) {
    throw std::runtime_error(p.string() + ": per-module cells sum to " +
                             std::to_string(r.breakdown_cells) + ", Yosys's design total is " +
                             std::to_string(stat.design->cells));
  }
}

void read_ice40_stat(const StatSection& s, Ice40Area& a) {
  for (const auto& [type, n] : s.by_type) {
    if (type == "SB_LUT4")
      a.lut4 += n;
    else if (type.rfind("SB_DFF", 0) == 0)
      a.dff += n;
    else if (type == "SB_CARRY")
      a.carry += n;
    else if (type.rfind("SB_RAM40_4K", 0) == 0)
      a.ram4k += n;
  }
}

// Diffuse series of a unit's parameters: one per light and channel, or one per light with
// DIFFUSE_MULTIPLY.
int64_t diffuse_series_of(const std::map<std::string, int64_t>& p) {
  const auto it = p.find("DIFFUSE_MULTIPLY");
  const bool multiply = it != p.end() && it->second == 1;
  return (multiply ? 1 : p.at("CHANNELS")) * p.at("LIGHTS");
}

// Every series the unit uses must survive synthesis (the ideal slot outputs 0, so its specular
// series legitimately go). Fewer means Yosys's netlist is not the unit the co-simulation checks
// and its area is understated: say so.
void check_series(AreaReport& r) {
  if (r.modules.empty()) {
    r.warnings.clear();
    if (r.has_gate_equivalents() && r.ram_bits != r.ram_bits_expected) {
      r.warnings.push_back("Yosys found " + std::to_string(r.ram_bits) +
                           " table memory bits, the parameters give " +
                           std::to_string(r.ram_bits_expected));
    }
    return;
  }
  const std::map<std::string, int64_t> p = parameter_map(r.parameters);
  const int64_t kind = p.at("SPECULAR_KIND");
  const int64_t expected =
      diffuse_series_of(p) +
      (kind == 0 ? 0 : p.at("LIGHTS") * specular_config_of_parameters(p).series_per_light());
  // Each series has a span_setup, or with host span setup (SPAN_SETUP 1) engines of its own.
  const auto host = p.find("SPAN_SETUP");
  const bool host_setup = host != p.end() && host->second == 1;
  const auto lanes_it = p.find("LANES");
  const int64_t per_series = host_setup && lanes_it != p.end() ? lanes_it->second : 1;
  int64_t kept = 0;
  for (const auto& m : r.modules) {
    if (m.module == (host_setup ? "series_engine" : "span_setup")) kept += m.instances;
  }
  kept /= per_series;
  r.warnings.clear();
  if (r.has_gate_equivalents() && r.ram_bits != r.ram_bits_expected) {
    r.warnings.push_back("Yosys found " + std::to_string(r.ram_bits) +
                         " table memory bits, the parameters give " +
                         std::to_string(r.ram_bits_expected) +
                         ": GE leaves out Yosys's count, the per-module rows the parameters'");
  }
  if (kept < expected) {
    r.warnings.push_back(
        "Yosys kept " + std::to_string(kept) + " of the " + std::to_string(expected) +
        " series (span_setup or, with host setup, series_engine instances) this unit uses: the "
        "others did not reach an output "
        "in Yosys's elaboration, so these figures are understated");
  }
}

std::string thousands(int64_t v) {
  std::string s = std::to_string(v < 0 ? -v : v);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<size_t>(i), ",");
  return (v < 0 ? "-" : "") + s;
}

// Whether the synth_ice40 counts alone rule out an HX8K (each logic cell holds one LUT4 and one
// DFF). Passing this check is necessary, not sufficient: nextpnr has the last word.
void check_fit(Ice40Area& a) {
  const int64_t need = std::max(a.lut4, a.dff);
  std::ostringstream os;
  if (need > Ice40Area::kHx8kLogicCells) {
    a.fits_hx8k = false;
    os << "does not fit an iCE40 HX8K: needs at least " << thousands(need) << " logic cells ("
       << (a.lut4 >= a.dff ? "LUT4s" : "DFFs") << "), the HX8K has "
       << thousands(Ice40Area::kHx8kLogicCells) << " ("
       << thousands(need - Ice40Area::kHx8kLogicCells) << " over, " << std::fixed
       << std::setprecision(2) << static_cast<double>(need) / Ice40Area::kHx8kLogicCells << "x)";
  } else if (a.ram4k > Ice40Area::kHx8kRam4k) {
    a.fits_hx8k = false;
    os << "does not fit an iCE40 HX8K: needs " << a.ram4k << " RAM40_4K blocks, the HX8K has "
       << Ice40Area::kHx8kRam4k;
  } else {
    a.fits_hx8k = true;
    os << "fits an iCE40 HX8K by LUT4/DFF count (" << thousands(need) << " of "
       << thousands(Ice40Area::kHx8kLogicCells) << " logic cells)";
  }
  a.fit_note = os.str();
}

}  // namespace

LogicDepth read_logic_depth(const std::string& ltp_file) {
  // "Longest topological path in shade_unit (length=87):", then "    0: \\cmd_data_i [16]",
  // one "  n: wire (via cell)" line per cell, and "ff: \\q (via $dff)" where it ends at one.
  std::istringstream is(read_text_file(ltp_file));
  static const std::regex head(R"(Longest topological path in \S+ \(length=([0-9]+)\))");
  static const std::regex step(R"(^\s*([0-9]+|ff):\s*\\?(.*?)(\s+\(via .*\))?\s*$)");
  LogicDepth d;
  std::smatch m;
  bool in_path = false;
  for (std::string line; std::getline(is, line);) {
    if (std::regex_search(line, m, head)) {
      d.gates = std::stoll(m[1].str());
      in_path = true;
    } else if (in_path && std::regex_match(line, m, step)) {
      if (m[1] == "0") d.from = m[2];
      d.to = m[2];
    }
  }
  if (d.gates < 0) throw std::runtime_error(ltp_file + ": no 'Longest topological path' line");
  return d;
}

namespace {

int64_t parameter_value(const std::vector<VerilogParameter>& ps, const char* name) {
  for (const auto& p : ps)
    if (p.name == name) return p.value;
  throw std::logic_error(std::string("area: no parameter ") + name);
}

// The register shell of the out-of-context Fmax flow (kShellScript), which instantiates
// shade_unit with the configuration's parameters (chparam would rename the derived module).
std::string fmax_shell_verilog(const std::vector<VerilogParameter>& ps) {
  const int64_t cmd_w = parameter_value(ps, "PORT_WORDS") * 64;
  const int64_t xy = parameter_value(ps, "XY_BITS");
  const int64_t lanes = parameter_value(ps, "LANES");
  const int64_t colour_w =
      lanes * parameter_value(ps, "CHANNELS") * parameter_value(ps, "OUT_BITS");
  const int64_t in_w = cmd_w + 2;                           // cmd_data, cmd_valid, pix_ready
  const int64_t out_w = 1 + 2 * xy + colour_w + lanes + 2;  // ready, x, y, colour, mask, eor, valid
  std::ostringstream v;
  v << "// Generated by shadesim area (sim/eda/area.cpp): the out-of-context Fmax shell.\n"
    << "module fmax_shell (input logic clk_i, input logic rst_ni, input logic in_i,\n"
    << "                   output logic out_o);\n"
    << "  logic [" << in_w - 1 << ":0] in_q;\n"
    << "  logic [" << out_w - 1 << ":0] o, chain_q;\n"
    << "  always_ff @(posedge clk_i) in_q <= {in_q[" << in_w - 2 << ":0], in_i};\n"
    << "  always_ff @(posedge clk_i) chain_q <= {chain_q[" << out_w - 2 << ":0], 1'b0} ^ o;\n"
    << "  assign out_o = chain_q[" << out_w - 1 << "];\n"
    << "  shade_unit #(\n";
  for (size_t i = 0; i < ps.size(); ++i)
    v << "    ." << ps[i].name << "(" << ps[i].literal() << ")" << (i + 1 < ps.size() ? "," : "")
      << "\n";
  v << "  ) u_unit (\n"
    << "    .clk_i(clk_i), .rst_ni(rst_ni),\n"
    << "    .cmd_data_i(in_q[" << cmd_w - 1 << ":0]), .cmd_valid_i(in_q[" << cmd_w << "]),\n"
    << "    .pix_ready_i(in_q[" << cmd_w + 1 << "]),\n"
    << "    .cmd_ready_o(o[0]), .pix_x_o(o[" << xy << ":1]), .pix_y_o(o[" << 2 * xy << ":" << xy + 1
    << "]),\n"
    << "    .pix_colour_o(o[" << 2 * xy + colour_w << ":" << 2 * xy + 1 << "]),\n"
    << "    .pix_mask_o(o[" << 2 * xy + colour_w + lanes << ":" << 2 * xy + colour_w + 1 << "]),\n"
    << "    .pix_eor_o(o[" << out_w - 2 << "]), .pix_valid_o(o[" << out_w - 1 << "]));\n"
    << "endmodule\n";
  return v.str();
}

// nextpnr's last "Max frequency for clock ..." line (the post-route one).
std::optional<double> read_fmax(const std::string& log) {
  static const std::regex re(R"(Max frequency for clock[^:]*:\s*([0-9.]+)\s*MHz)");
  std::optional<double> f;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator();
       ++it) {
    f = std::stod((*it)[1].str());
  }
  return f;
}

Json params_json(const std::vector<VerilogParameter>& ps) {
  Json j = Json::array();
  for (const auto& p : ps) {
    if (p.slots.empty())
      j.push_back({{"name", p.name}, {"value", p.value}});
    else
      j.push_back({{"name", p.name}, {"slots", p.slots}});
  }
  return j;
}

}  // namespace

int64_t gate_equivalents(int64_t logic_transistors, int64_t flip_flops, int64_t ram_bits) {
  return std::llround(static_cast<double>(logic_transistors) / kTransistorsPerGate) +
         kGatesPerFlipFlop * (flip_flops - ram_bits);
}

int64_t ModuleArea::gate_equivalents_each() const {
  return has_gate_equivalents()
             ? shadesim::gate_equivalents(logic_transistors_each, flip_flops_each, ram_bits_each)
             : -1;
}

int64_t AreaReport::gate_equivalents() const {
  return has_gate_equivalents()
             ? shadesim::gate_equivalents(logic_transistors, flip_flops, ram_bits)
             : -1;
}

CmosStat read_cmos_stat(const std::string& stat_file, const std::string& module) {
  const StatReport stat = read_stat_json(stat_file, true);
  const StatSection* sec = nullptr;
  if (!module.empty()) {
    for (const auto& [name, s] : stat.modules)
      if (base_module_name(name) == module) sec = &s;
  } else if (stat.modules.size() == 1) {
    sec = &stat.modules.begin()->second;
  } else if (stat.design) {
    sec = &*stat.design;
  }
  if (!sec) throw std::runtime_error(stat_file + ": no statistics for module '" + module + "'");
  CmosStat c;
  c.cells = sec->cells;
  c.transistors = sec->transistors;
  c.transistors_partial = sec->transistors_partial;
  c.flip_flops = flip_flops_of(*sec);
  c.logic_transistors = sec->transistors - flip_flop_transistors_of(*sec);
  return c;
}

int64_t read_memory_bits(const std::string& dump_file) {
  // "  cell $mem_v2 \name" then its "    parameter \SIZE n" and "    parameter \WIDTH n".
  // Only the tables count: register arrays (shade_unit's coef_q, ambient_q, ...) are $mem cells
  // too at this point, and are logic.
  std::istringstream is(read_text_file(dump_file));
  static const std::regex cell(R"(^\s*cell \$mem(_v2)? \\(\S*\.)?)" +
                               std::string(kTableMemoryName) + R"(\s*$)");
  static const std::regex any_cell(R"(^\s*cell )");
  static const std::regex param(R"(^\s*parameter \\(SIZE|WIDTH) ([0-9]+)\s*$)");
  int64_t total = 0, size = -1, width = -1;
  bool in_mem = false;
  auto close = [&] {
    if (!in_mem) return;
    if (size < 0 || width < 0)
      throw std::runtime_error(dump_file + ": a memory cell without SIZE or WIDTH");
    total += size * width;
    in_mem = false;
  };
  std::smatch m;
  for (std::string line; std::getline(is, line);) {
    if (std::regex_search(line, m, cell)) {
      close();
      in_mem = true;
      size = width = -1;
    } else if (std::regex_search(line, m, any_cell)) {
      close();
    } else if (in_mem && std::regex_match(line, m, param)) {
      (m[1].str() == "SIZE" ? size : width) = std::stoll(m[2].str());
    } else if (in_mem && std::regex_match(line, std::regex(R"(^\s*end\s*$)"))) {
      close();
    }
  }
  close();
  return total;
}

int64_t ram_bits_per_specular_unit(const std::vector<VerilogParameter>& parameters) {
  const std::map<std::string, int64_t> p = parameter_map(parameters);
  const SpecularConfig unit = specular_config_of_parameters(p);
  if (unit.kind != SpecularUnitKind::kLut) return 0;
  const auto banks = p.find("MATERIAL_BUFFERS");
  return ExponentLut::table_bits(unit.lut) * (banks == p.end() ? 1 : banks->second);
}

int64_t ram_bits_of_parameters(const std::vector<VerilogParameter>& parameters) {
  const std::map<std::string, int64_t> p = parameter_map(parameters);
  const auto lanes = p.find("LANES");
  return ram_bits_per_specular_unit(parameters) * p.at("LIGHTS") *
         (lanes == p.end() ? 1 : lanes->second);
}

std::string area_report_to_json(const AreaReport& r) {
  Json modules = Json::array();
  for (const auto& m : r.modules) {
    modules.push_back({{"module", m.module},
                       {"instances", m.instances},
                       {"cells_each", m.cells_each},
                       {"transistors_each", m.transistors_each},
                       {"flip_flops_each", m.flip_flops_each},
                       {"cells", m.cells()},
                       {"transistors", m.transistors()}});
    if (m.has_gate_equivalents()) {
      modules.back()["logic_transistors_each"] = m.logic_transistors_each;
      modules.back()["ram_bits_each"] = m.ram_bits_each;
      modules.back()["gate_equivalents_each"] = m.gate_equivalents_each();
      modules.back()["gate_equivalents"] = m.gate_equivalents();
    }
  }
  Json ice40 = {{"lut4", r.ice40.lut4},           {"dff", r.ice40.dff},
                {"carry", r.ice40.carry},         {"ram4k", r.ice40.ram4k},
                {"fits_hx8k", r.ice40.fits_hx8k}, {"fit_note", r.ice40.fit_note},
                {"pnr_note", r.ice40.pnr_note}};
  ice40["fmax_mhz"] = r.ice40.fmax_mhz ? Json(*r.ice40.fmax_mhz) : Json(nullptr);
  Json j = {{"parameters", params_json(r.parameters)},
            {"key", r.key},
            {"from_cache", r.from_cache},
            {"yosys_version", r.yosys_version},
            {"nextpnr_version", r.nextpnr_version},
            {"cells", r.cells},
            {"transistors", r.transistors},
            {"transistors_exclude_flip_flops", r.transistors_partial},
            {"flip_flops", r.flip_flops},
            {"breakdown_cells", r.breakdown_cells},
            {"modules", modules},
            {"ice40", ice40},
            {"logic_depth",
             {{"gates", r.logic_depth.gates},
              {"from", r.logic_depth.from},
              {"to", r.logic_depth.to},
              {"method", LogicDepth::kMethod}}},
            {"seconds", r.seconds},
            {"cpu_seconds", r.cpu_seconds},
            {"warnings", r.warnings}};
  if (r.has_gate_equivalents()) {
    // GE: NAND2 gate equivalents = logic_transistors / 4 + 6 per flip-flop outside the RAM
    // (sim/eda/area.h); ram_bits: the table memories, apart.
    j["logic_transistors"] = r.logic_transistors;
    j["ram_bits"] = r.ram_bits;
    j["ram_bits_expected"] = r.ram_bits_expected;
    j["gate_equivalents"] = r.gate_equivalents();
    j["gate_equivalents_convention"] =
        "NAND2 GE = (stat -tech cmos transistors less its flip-flop cost) / 4 + 6 per flip-flop; "
        "table memory bits apart (ram_bits), not flip-flops";
  }
  return j.dump(2) + "\n";
}

AreaReport area_report_from_json(const std::string& text, const std::string& source) {
  try {
    const Json j = Json::parse(text);
    AreaReport r;
    for (const auto& p : j.at("parameters")) {
      if (p.contains("slots"))
        r.parameters.emplace_back(p.at("name").get<std::string>(),
                                  p.at("slots").get<std::vector<int64_t>>());
      else
        r.parameters.emplace_back(p.at("name").get<std::string>(), p.at("value").get<int64_t>());
    }
    r.key = j.at("key");
    r.from_cache = j.at("from_cache");
    r.yosys_version = j.at("yosys_version");
    r.nextpnr_version = j.at("nextpnr_version");
    r.cells = j.at("cells");
    r.transistors = j.at("transistors");
    r.transistors_partial = j.at("transistors_exclude_flip_flops");
    r.flip_flops = j.at("flip_flops");
    r.breakdown_cells = j.at("breakdown_cells");
    for (const auto& m : j.at("modules")) {
      r.modules.push_back({m.at("module"), m.at("instances"), m.at("cells_each"),
                           m.at("transistors_each"), m.at("flip_flops_each")});
      // Entries written before GE were measured have no logic transistors: GE unknown.
      if (m.contains("logic_transistors_each")) {
        r.modules.back().logic_transistors_each = m.at("logic_transistors_each");
        r.modules.back().ram_bits_each = m.at("ram_bits_each");
      }
    }
    if (j.contains("logic_transistors")) {
      r.logic_transistors = j.at("logic_transistors");
      r.ram_bits = j.at("ram_bits");
      r.ram_bits_expected = j.at("ram_bits_expected");
    }
    if (j.contains("logic_depth")) {
      const Json& d = j.at("logic_depth");
      r.logic_depth = {d.at("gates").get<int64_t>(), d.at("from"), d.at("to")};
    }
    const Json& a = j.at("ice40");
    r.ice40.lut4 = a.at("lut4");
    r.ice40.dff = a.at("dff");
    r.ice40.carry = a.at("carry");
    r.ice40.ram4k = a.at("ram4k");
    r.ice40.fits_hx8k = a.at("fits_hx8k");
    r.ice40.fit_note = a.at("fit_note");
    r.ice40.pnr_note = a.at("pnr_note");
    if (!a.at("fmax_mhz").is_null()) r.ice40.fmax_mhz = a.at("fmax_mhz").get<double>();
    r.seconds = j.at("seconds");
    r.cpu_seconds = j.at("cpu_seconds");
    if (j.contains("warnings")) r.warnings = j.at("warnings").get<std::vector<std::string>>();
    return r;
  } catch (const Json::exception& e) {
    throw std::runtime_error(source + ": not an area report: " + e.what());
  }
}

namespace {

// A synthesis run's tools and inputs: the figures depend on these and on the scripts only.
struct AreaInputs {
  std::string yosys, nextpnr;  // the programs; nextpnr empty without place and route
  std::vector<fs::path> files;
  std::string chparam;
  std::string yosys_version;
};

AreaInputs area_inputs(const std::vector<VerilogParameter>& parameters, const AreaOptions& o) {
  AreaInputs in;
  in.chparam = yosys_chparam_args(parameters);
  in.yosys = find_program(o.yosys, "yosys");
  in.nextpnr = o.place_and_route ? find_program(o.nextpnr, "nextpnr-ice40") : "";
  in.files = rtl_sources(o.rtl_dir.empty() ? SHADESIM_SOURCE_DIR "/rtl" : o.rtl_dir);
  in.yosys_version = first_line(run_process({in.yosys, "-V"}, "").output);
  return in;
}

// Cache key: everything the figures depend on. The file names are in the script text.
std::string area_key(const AreaInputs& in, bool breakdown, bool pnr,
                     const std::string& nextpnr_version) {
  ContentHash h;
  h.add("shadesim-area-v2");  // 2: gate equivalents and RAM bits measured
  h.add(in.chparam);
  for (const auto& f : in.files) {
    h.add(f.filename().string());
    h.add(read_text_file(f.string()));
  }
  h.add(in.yosys_version);
  h.add(kFlatScript);
  h.add(kIce40Script);
  h.add(kMemoryScript);
  if (breakdown) h.add(kBreakdownScript);
  if (pnr) {
    h.add(nextpnr_version);
    h.add(kPnrArgs);
    h.add(kShellVersion).add(kShellScript);
  }
  return h.hex();
}

// The cache entries that answer the request `r` stands for: its own, then any that ran more
// (breakdown, place and route), which also answer a request for less.
std::vector<fs::path> cache_candidates(const AreaInputs& in, const AreaReport& r,
                                       const AreaOptions& o) {
  std::vector<fs::path> candidates = {fs::path(o.cache_dir) / (r.key + ".json")};
  std::string np_version = r.nextpnr_version;
  if (!o.place_and_route) {
    try {
      np_version = first_line(
          run_process({find_program(o.nextpnr, "nextpnr-ice40"), "--version"}, "").output);
    } catch (const MissingToolError&) {
      // no nextpnr: only entries without place and route can be wanted
    }
  }
  for (const bool b : {o.breakdown, true}) {
    for (const bool pnr : {o.place_and_route, true}) {
      if (pnr && np_version.empty()) continue;
      candidates.push_back(fs::path(o.cache_dir) / (area_key(in, b, pnr, np_version) + ".json"));
    }
  }
  return candidates;
}

std::optional<AreaReport> cached_area(const AreaInputs& in, const AreaReport& r,
                                      const AreaOptions& o) {
  for (const auto& c : cache_candidates(in, r, o)) {
    if (!fs::exists(c)) continue;
    AreaReport cached = area_report_from_json(read_text_file(c.string()), c.string());
    cached.from_cache = true;
    check_series(cached);
    if (o.progress) *o.progress << "[area] cache hit " << c.string() << "\n";
    return cached;
  }
  return std::nullopt;
}

// A fresh work folder; kept when a tool fails (its logs say why), removed on success.
fs::path make_work_folder(const AreaOptions& o, const std::string& key) {
  const fs::path work_root =
      o.cache_dir.empty() ? fs::temp_directory_path() : fs::path(o.cache_dir);
  std::string tmpl = (work_root / ("work-" + key + "-XXXXXX")).string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error(tmpl + ": cannot create a work folder");
  return tmpl;
}

struct SynthesisJob {
  std::string label;
  std::future<void> done;
  bool finished = false;
};

// Waits for every job, with one progress line for all of them: which are still running and for
// how long. Rethrows the first failure.
void wait_for_syntheses(std::vector<SynthesisJob>& jobs, const AreaOptions& o,
                        std::chrono::steady_clock::time_point t0) {
  const bool terminal = o.progress == &std::cerr && ::isatty(STDERR_FILENO);
  for (int ticks = 0;; ++ticks) {
    std::string running;
    for (auto& j : jobs) {
      if (!j.finished && j.done.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
        j.finished = true;
      if (!j.finished) running += (running.empty() ? "" : ", ") + j.label;
    }
    if (running.empty()) break;
    if (o.progress && ticks > 0 && (terminal || ticks % 30 == 0)) {
      const auto el =
          std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - t0);
      *o.progress << (terminal ? "\r" : "") << "[area] yosys: " << running << " ... " << el.count()
                  << " s" << (terminal ? "   " : "\n") << std::flush;
    }
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  std::exception_ptr error;
  for (auto& j : jobs) {
    try {
      j.done.get();
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (o.progress) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    *o.progress << (terminal ? "\r" : "") << "[area] yosys: " << (error ? "failed" : "done")
                << " after " << std::fixed << std::setprecision(1) << el << " s"
                << (terminal ? "                                        " : "") << "\n";
  }
  if (error) std::rethrow_exception(error);
}

// The flat, iCE40, table-memory and (with o.breakdown) per-module syntheses, into `work`. They
// are independent: they run side by side.
void run_syntheses(const AreaInputs& in, const fs::path& work, const AreaOptions& o,
                   std::chrono::steady_clock::time_point t0) {
  const auto run_yosys = [&](const std::string& name, const char* flow, const std::string& label) {
    const fs::path script = work / (name + ".ys");
    write_atomically(script, yosys_script(in.files, in.chparam, flow, work));
    run_tool({in.yosys, "-q", "-l", (work / (name + ".log")).string(), script.string()},
             work / (name + ".out"), label, nullptr);
  };
  std::vector<SynthesisJob> jobs;
  jobs.push_back({"flat synthesis", std::async(std::launch::async, [&] {
                    run_yosys("flat", kFlatScript, "yosys flat synthesis");
                  })});
  jobs.push_back({"synth_ice40", std::async(std::launch::async, [&] {
                    run_yosys("ice40", kIce40Script, "yosys synth_ice40");
                  })});
  jobs.push_back({"table memories", std::async(std::launch::async, [&] {
                    run_yosys("memory", kMemoryScript, "yosys table memories");
                  })});
  if (o.breakdown) {
    jobs.push_back({"per-module synthesis", std::async(std::launch::async, [&] {
                      run_yosys("breakdown", kBreakdownScript, "yosys per-module synthesis");
                    })});
  }
  wait_for_syntheses(jobs, o, t0);
}

// The syntheses' figures into r: cells, flip-flops, GE and RAM bits, logic depth, the
// per-module rows, the iCE40 resources and whether they fit.
void read_syntheses(const fs::path& work, bool breakdown, AreaReport& r) {
  {
    const fs::path p = work / "flat_stat.json";
    const StatReport stat = read_stat_json(p, true);
    const StatSection& top = stat.modules.at(top_name(stat, p));
    r.cells = top.cells;
    r.transistors = top.transistors;
    r.transistors_partial = top.transistors_partial;
    r.flip_flops = flip_flops_of(top);
    r.logic_transistors = top.transistors - flip_flop_transistors_of(top);
    r.ram_bits = read_memory_bits((work / "flat_mem.txt").string());
    r.ram_bits_expected = ram_bits_of_parameters(r.parameters);
    r.logic_depth = read_logic_depth((work / "flat_ltp.txt").string());
  }
  if (breakdown) {
    const fs::path p = work / "breakdown_stat.json";
    read_breakdown(read_stat_json(p, true), p, r);
  }
  check_series(r);
  {
    const fs::path p = work / "ice40_stat.json";  // no -tech: no transistor estimate
    const StatReport stat = read_stat_json(p, false);
    read_ice40_stat(stat.modules.at(top_name(stat, p)), r.ice40);
  }
  check_fit(r.ice40);
}

// Places and routes the unit in its Fmax shell on an HX8K for r.ice40's Fmax. Returns whether
// the work folder must be kept: a failed placement, whose log says why.
bool place_and_route(const AreaInputs& in, const fs::path& work, const AreaOptions& o,
                     AreaReport& r) {
  std::vector<std::string> argv = {in.nextpnr};
  std::istringstream args(kPnrArgs);
  for (std::string a; args >> a;) argv.push_back(a);
  argv.insert(argv.end(), {"--json", (work / "shell.json").string(), "--asc",
                           (work / "shell.asc").string(), "-l", (work / "pnr.log").string()});
  // The shell's synthesis failing is the flow's fault, not a finding: it throws.
  write_atomically(work / "fmax_shell.sv", fmax_shell_verilog(r.parameters));
  std::vector<fs::path> shell_files = in.files;
  shell_files.push_back(work / "fmax_shell.sv");
  const fs::path script = work / "shell.ys";
  write_atomically(script, yosys_script(shell_files, "", kShellScript, work));
  run_tool({in.yosys, "-q", "-l", (work / "shell.log").string(), script.string()},
           work / "shell.out", "yosys synth_ice40 of the unit in its Fmax shell", o.progress);
  try {
    run_tool(argv, work / "pnr.out", "nextpnr-ice40 place and route (HX8K)", o.progress);
    r.ice40.fmax_mhz = read_fmax(read_text_file((work / "pnr.log").string()));
    if (!r.ice40.fmax_mhz) r.ice40.pnr_note = "nextpnr-ice40 reported no Fmax";
    return false;
  } catch (const std::runtime_error& e) {
    // A failed placement (no room once packed, too many I/O) is a finding about the design.
    r.ice40.fits_hx8k = false;
    r.ice40.fit_note = "does not fit an iCE40 HX8K: nextpnr-ice40 failed (log " +
                       (work / "pnr.log").string() + ")";
    r.ice40.pnr_note = "no Fmax: " + first_line(e.what());
    return true;
  }
}

// CPU seconds of the finished child processes so far.
double children_cpu_seconds() {
  struct rusage u {};
  ::getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

AreaReport unit_area(const UnitConfig& unit, const AreaOptions& o) {
  AreaReport r;
  r.parameters = shade_unit_parameters(unit);  // validates `unit`
  const AreaInputs in = area_inputs(r.parameters, o);
  r.yosys_version = in.yosys_version;
  if (o.place_and_route)
    r.nextpnr_version = first_line(run_process({in.nextpnr, "--version"}, "").output);
  r.key = area_key(in, o.breakdown, o.place_and_route, r.nextpnr_version);

  fs::path entry;
  if (!o.cache_dir.empty()) {
    fs::create_directories(o.cache_dir);
    entry = fs::path(o.cache_dir) / (r.key + ".json");
    if (std::optional<AreaReport> cached = cached_area(in, r, o)) return *cached;
  }

  const fs::path work = make_work_folder(o, r.key);
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu_before = children_cpu_seconds();
  run_syntheses(in, work, o, t0);
  read_syntheses(work, o.breakdown, r);

  bool keep_work = false;
  if (!o.place_and_route) {
    r.ice40.pnr_note = "place and route not run (--no-pnr)";
  } else if (!r.ice40.fits_hx8k) {
    r.ice40.pnr_note = "no Fmax: the design does not fit an HX8K";
  } else {
    keep_work = place_and_route(in, work, o, r);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu_seconds = children_cpu_seconds() - cpu_before;

  if (!entry.empty()) write_atomically(entry, area_report_to_json(r));
  if (!keep_work) {
    std::error_code ec;
    fs::remove_all(work, ec);
  }
  return r;
}

// ---- netlist -------------------------------------------------------------------------------

namespace {

// The ports of shade_unit the co-simulation glue drives (sim/harness/cosim_glue.cpp), with their
// widths from the parameters (rtl/shade_unit.sv's port list).
std::map<std::string, std::pair<std::string, int64_t>> expected_ports(
    const std::vector<VerilogParameter>& parameters) {
  const std::map<std::string, int64_t> p = parameter_map(parameters);
  const auto get_or = [&](const char* n, int64_t d) {
    const auto it = p.find(n);
    return it == p.end() ? d : it->second;
  };
  const int64_t lanes = get_or("LANES", 1);
  return {{"clk_i", {"input", 1}},
          {"rst_ni", {"input", 1}},
          {"cmd_data_i", {"input", get_or("PORT_WORDS", 1) * 64}},
          {"cmd_valid_i", {"input", 1}},
          {"cmd_ready_o", {"output", 1}},
          {"pix_x_o", {"output", p.at("XY_BITS")}},
          {"pix_y_o", {"output", p.at("XY_BITS")}},
          {"pix_colour_o", {"output", lanes * p.at("CHANNELS") * p.at("OUT_BITS")}},
          {"pix_mask_o", {"output", lanes}},
          {"pix_eor_o", {"output", 1}},
          {"pix_valid_o", {"output", 1}},
          {"pix_ready_i", {"input", 1}}};
}

// Throws naming the netlist and the port when its top is not shade_unit with exactly the ports
// (direction, width) the glue drives.
void check_netlist_ports(const fs::path& netlist, const std::vector<VerilogParameter>& params) {
  std::istringstream is(read_text_file(netlist.string()));
  static const std::regex module_re(R"(^\s*module\s+(\S+?)\s*\()");
  static const std::regex port_re(
      R"(^\s*(input|output|inout)\s+(\[(-?[0-9]+):(-?[0-9]+)\]\s+)?(\S+)\s*;)");
  std::map<std::string, std::pair<std::string, int64_t>> found;
  int modules = 0;
  std::smatch m;
  for (std::string line; std::getline(is, line);) {
    if (std::regex_search(line, m, module_re)) {
      ++modules;
      if (m[1].str() != "shade_unit")
        throw std::runtime_error(netlist.string() + ": its module is '" + m[1].str() +
                                 "', not shade_unit");
    } else if (std::regex_search(line, m, port_re)) {
      const int64_t w =
          m[2].matched ? std::llabs(std::stoll(m[3].str()) - std::stoll(m[4].str())) + 1 : 1;
      found[m[5].str()] = {m[1].str(), w};
    }
  }
  if (modules != 1)
    throw std::runtime_error(netlist.string() + ": " + std::to_string(modules) +
                             " modules, expected the flat shade_unit alone");
  const auto want = expected_ports(params);
  for (const auto& [name, dw] : want) {
    const auto it = found.find(name);
    if (it == found.end())
      throw std::runtime_error(netlist.string() + ": shade_unit has no port " + name);
    if (it->second != dw)
      throw std::runtime_error(netlist.string() + ": port " + name + " is " + it->second.first +
                               " [" + std::to_string(it->second.second) + "], the RTL's is " +
                               dw.first + " [" + std::to_string(dw.second) + "]");
  }
  for (const auto& [name, dw] : found) {
    if (!want.count(name))
      throw std::runtime_error(netlist.string() + ": shade_unit has a port " + name +
                               " the RTL's port list (and the glue) does not");
  }
}

}  // namespace

std::string default_netlist_cache_dir() {
  return (fs::path(SHADESIM_BINARY_DIR) / "netlist-cache").string();
}

UnitNetlist unit_netlist(const UnitConfig& unit, const NetlistOptions& o) {
  if (o.cache_dir.empty()) throw std::invalid_argument("unit_netlist: no cache folder");
  const std::vector<VerilogParameter> params = shade_unit_parameters(unit);  // validates
  const std::string chparam = yosys_chparam_args(params);
  const std::string yosys = find_program(o.yosys, "yosys");
  std::string dir = o.rtl_dir;
  if (dir.empty()) {
    const char* other = std::getenv("SHADESIM_RTL_DIR");
    dir = other && *other ? other : SHADESIM_SOURCE_DIR "/rtl";
  }
  const std::vector<fs::path> files = rtl_sources(dir);
  const std::string version = first_line(run_process({yosys, "-V"}, "").output);
  ContentHash h;
  h.add("shadesim-netlist-v1").add(chparam);
  for (const auto& f : files) {
    h.add(f.filename().string());
    h.add(read_text_file(f.string()));
  }
  h.add(version).add(kFlatScript).add(kNetlistWrite);
  UnitNetlist n;
  n.key = h.hex();
  const fs::path cache = fs::absolute(o.cache_dir);
  fs::create_directories(cache);
  const fs::path path = cache / ("netlist-" + n.key + ".v");
  const fs::path info = cache / ("netlist-" + n.key + ".json");
  n.path = path.string();
  auto read_info = [&] {
    const Json j = Json::parse(read_text_file(info.string()));
    n.cells = j.at("cells");
    n.flip_flops = j.at("flip_flops");
    n.gate_equivalents = j.at("gate_equivalents");
    n.ram_bits = j.at("ram_bits");
    n.seconds = j.at("seconds");
  };
  if (fs::exists(path) && fs::exists(info)) {
    read_info();
    n.from_cache = true;
    return n;
  }
  std::string tmpl = (cache / ("work-" + n.key + "-XXXXXX")).string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error(tmpl + ": cannot create a work folder");
  const fs::path work = tmpl;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string flow = std::string(kFlatScript) + kNetlistWrite;
  write_atomically(work / "netlist.ys", yosys_script(files, chparam, flow.c_str(), work));
  run_tool({yosys, "-q", "-l", (work / "netlist.log").string(), (work / "netlist.ys").string()},
           work / "netlist.out", "yosys netlist of " + unit.to_string(), o.progress);
  check_netlist_ports(work / "netlist.v", params);
  const CmosStat c = read_cmos_stat((work / "flat_stat.json").string(), "shade_unit");
  n.cells = c.cells;
  n.flip_flops = c.flip_flops;
  n.ram_bits = ram_bits_of_parameters(params);  // the area report measures them with Yosys
  n.gate_equivalents = gate_equivalents(c.logic_transistors, c.flip_flops, n.ram_bits);
  n.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The netlist first, then its stat: an entry is complete once the .json exists.
  write_atomically(path, read_text_file((work / "netlist.v").string()));
  const Json j = {{"unit", unit.to_string()},   {"key", n.key},
                  {"yosys_version", version},   {"cells", n.cells},
                  {"flip_flops", n.flip_flops}, {"gate_equivalents", n.gate_equivalents},
                  {"ram_bits", n.ram_bits},     {"seconds", n.seconds}};
  write_atomically(info, j.dump(2) + "\n");
  std::error_code ec;
  fs::remove_all(work, ec);
  return n;
}

}  // namespace shadesim

// ---- estimate ------------------------------------------------------------------------------

namespace shadesim {
namespace {

using ParamMap = std::map<std::string, int64_t>;

// SPEC_PARAMS as one entry per slot, so a differing unit field counts as one parameter.
ParamMap param_map(const std::vector<VerilogParameter>& ps) { return parameter_map(ps); }

int64_t get(const ParamMap& p, const char* name) {
  const auto it = p.find(name);
  if (it == p.end())
    throw std::runtime_error(std::string("area estimate: parameter ") + name + " missing");
  return it->second;
}

// LANES, 1 for a measurement made before the parameter existed.
int64_t lanes_of(const ParamMap& p) {
  const auto it = p.find("LANES");
  return it == p.end() ? 1 : it->second;
}

// Host span setup (SPAN_SETUP 1): no span setup, coefficient banks or span queue; a start bank.
bool host_setup_of(const ParamMap& p) {
  const auto it = p.find("SPAN_SETUP");
  return it != p.end() && it->second == 1;
}

// OFS_BITS, 17 (screen-sized) when the unit does not set it.
int64_t offset_bits_of(const ParamMap& p) {
  const auto it = p.find("OFS_BITS");
  return it == p.end() ? UnitConfig::kMaxOffsetBits : it->second;
}

// Instances of each module (shade_unit.sv: NSer series, one slot per light, one combine; with
// LANES > 1 an engine per series, a slot per light and a combine per lane, one span setup).
int64_t instances_of(const std::string& module, const ParamMap& p) {
  const int64_t l = get(p, "LIGHTS"), diffuse = diffuse_series_of(p);
  const int64_t per_light = specular_config_of_parameters(p).series_per_light();
  const int64_t lanes = lanes_of(p);
  const bool host = host_setup_of(p);
  if (module == "span_setup") return host ? 0 : diffuse + l * per_light;
  if (module == "coef_bank" || module == "span_queue" || module == "setup_ctrl")
    return host ? 0 : 1;
  if (module == "start_bank") return host ? 1 : 0;
  if (module == "series_engine") return (diffuse + l * per_light) * lanes;
  if (module == "specular_unit") return per_light == 0 ? 0 : l * lanes;  // none: no slot
  if (module == "pixel_combine") return lanes;
  return 1;  // shade_unit glue
}

// Structural size of one instance: what its cells grow with (the RTL's widths, see area.h).
double size_of(const std::string& module, const ParamMap& p) {
  const double c = static_cast<double>(get(p, "COEF_WL")),
               ci = static_cast<double>(get(p, "COEF_IWL"));
  const double s = static_cast<double>(get(p, "SERIES_WL")),
               si = static_cast<double>(get(p, "SERIES_IWL"));
  const double ch = static_cast<double>(get(p, "CHANNELS")),
               l = static_cast<double>(get(p, "LIGHTS"));
  const double so = static_cast<double>(get(p, "SPECULAR_OUT_WL")),
               sc = static_cast<double>(get(p, "SPEC_COLOUR_WL"));
  if (module == "span_setup") {
    // Horner form (rtl/span_setup.sv): four coefficient x offset products (offsets of
    // OFS_BITS o) in stage 1 and two bracket x offset products ((c + o) x o) in stage 2; a
    // c x k product has c k partial-product bits, and with a wrapping series only the low w
    // bits (up to the series' top) reach the output, at most w(w+1)/2 of them. Plus the
    // registers: five brackets and two offsets, three sums, three outputs.
    const double o = static_cast<double>(offset_bits_of(p));
    const double sum_w = c + 2 * o + 3;
    const double drop = (c - ci) - (s - si);
    const double w = get(p, "SERIES_OVERFLOW") == 1 ? std::min(sum_w, drop + s + 1) : sum_w;
    const auto product = [w](double a, double b) { return std::min(a * b, w * (w + 1) / 2); };
    return 4 * product(c, o) + 2 * product(c + o, o) + 8 * w + 2 * o + 3 * s;
  }
  if (module == "series_engine") return s;
  // The start bank: v, d, d2 of every series (and the payload steering per bit) per entry.
  if (module == "start_bank") {
    const auto depth = p.find("START_DEPTH");
    const double entries = depth == p.end() ? UnitConfig::kStartDepth : depth->second;
    return 3 * static_cast<double>(instances_of("series_engine", p)) * s * entries;
  }
  if (module == "pixel_combine") {
    // With the diffuse multiply, a (series integer + colour fraction bits) x colour product per
    // light and channel too (rtl/pixel_combine.sv truncates N.L to the colour's fraction).
    const bool multiply = diffuse_series_of(p) != static_cast<int64_t>(ch * l);
    const double nl =
        si - 1 + std::min(s - si, sc - static_cast<double>(get(p, "SPEC_COLOUR_IWL")));
    return ch * (l * so * sc + (multiply ? l * nl * sc : 0) + (l + 1) * (s + 4));
  }
  if (module == "specular_unit") {
    // The unit's own size (model/specular_units.cpp), from its parameters.
    const SpecularConfig unit = specular_config_of_parameters(p);
    return specular_unit(unit.kind).slot_size(unit, static_cast<int>(s));
  }
  // shade_unit glue: coefficient, ambient and specular-colour registers, the metadata line,
  // decoder and span pipeline (a fixed part).
  const double nser = static_cast<double>(instances_of("series_engine", p) / lanes_of(p));
  const double coef_regs = host_setup_of(p) ? 0 : 6 * nser * c;  // host: no coefficients
  const double xy = static_cast<double>(get(p, "XY_BITS"));
  // Lanes add each lane's fan-out (three constant-multiplier adders per series, ~6 adder bits
  // per series bit) and widen the metadata line and the pix register.
  const double extra_lanes = static_cast<double>(lanes_of(p) - 1);
  const double diffuse_bits = static_cast<double>(diffuse_series_of(p)) * s;  // metadata line
  return coef_regs + ch * s + ch * l * sc + 2 * (2 * xy + diffuse_bits) + 400 +
         extra_lanes * (6 * nser * s + 2 * diffuse_bits);
}

}  // namespace

std::string AreaEstimate::label() const {
  return "estimate (scaled from Yosys run " + anchor_key + ", " +
         std::to_string(differing_parameters) + " parameter(s) differ)";
}

AreaEstimate estimate_area(const UnitConfig& unit, const std::vector<AreaReport>& anchors) {
  const ParamMap target = param_map(shade_unit_parameters(unit));
  const AreaReport* best = nullptr;
  int best_diff = 0;
  for (const auto& a : anchors) {
    // Only complete measurements: a breakdown, and no series lost by Yosys (check_series).
    if (a.modules.empty() || a.cells == 0 || a.breakdown_cells == 0 || !a.warnings.empty())
      continue;
    const ParamMap ap = param_map(a.parameters);
    if (get(ap, "SPECULAR_KIND") != get(target, "SPECULAR_KIND")) continue;
    // A host-setup anchor has no span setup, coefficient bank or span queue to scale: it is no
    // anchor for a unit-setup target.
    if (host_setup_of(ap) && !host_setup_of(target)) continue;
    // The other span setup site has other modules: only when no anchor of this one is there.
    constexpr int kOtherSite = 1000;
    int diff = host_setup_of(ap) != host_setup_of(target) ? kOtherSite : 0;
    for (const auto& [name, value] : target) {
      const auto it = ap.find(name);
      if (it == ap.end() || it->second != value) ++diff;
    }
    if (!best || diff < best_diff) {
      best = &a;
      best_diff = diff;
    }
  }
  if (!best) {
    throw std::runtime_error(
        "area estimate: no measured anchor with this specular unit (" +
        std::string(to_string(unit.specular.kind)) +
        ") and a per-module breakdown; run `shadesim area --config` on one first");
  }
  const ParamMap ap = param_map(best->parameters);
  double kept = 0;
  for (const auto& m : best->modules) {
    const double anchor_size = size_of(m.module, ap);
    const double ratio = anchor_size > 0 ? size_of(m.module, target) / anchor_size : 0.0;
    kept += static_cast<double>(m.cells_each) * ratio *
            static_cast<double>(instances_of(m.module, target));
  }
  // A host-setup target from a unit-setup anchor: the start bank the anchor lacks, at the
  // anchor's series engine cells per register bit (an engine is three registers and adders).
  if (host_setup_of(target) && !host_setup_of(ap)) {
    for (const auto& m : best->modules) {
      if (m.module != "series_engine" || size_of(m.module, ap) <= 0) continue;
      kept += static_cast<double>(m.cells_each) / (3 * size_of(m.module, ap)) *
              size_of("start_bank", target);
    }
  }
  const double flat =
      kept * static_cast<double>(best->cells) / static_cast<double>(best->breakdown_cells);
  AreaEstimate e;
  e.cells = static_cast<int64_t>(std::llround(flat));
  e.lut4 = static_cast<int64_t>(std::llround(flat * static_cast<double>(best->ice40.lut4) /
                                             static_cast<double>(best->cells)));
  if (best->has_gate_equivalents()) {
    e.gate_equivalents = static_cast<int64_t>(std::llround(
        flat * static_cast<double>(best->gate_equivalents()) / static_cast<double>(best->cells)));
  }
  e.anchor_key = best->key;
  e.differing_parameters = best_diff % 1000;  // (without the other site's penalty)
  return e;
}

std::vector<AreaReport> load_area_reports(const std::string& cache_dir) {
  std::vector<AreaReport> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(cache_dir, ec)) {
    if (!e.is_regular_file() || e.path().extension() != ".json") continue;
    try {
      AreaReport r = area_report_from_json(read_text_file((e.path()).string()), e.path().string());
      check_series(r);
      out.push_back(std::move(r));
    } catch (const std::exception&) {
      // not an area report (or an older format): not an anchor
    }
  }
  return out;
}

}  // namespace shadesim
