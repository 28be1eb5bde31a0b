// Power of a mapped netlist from a scene's activity with OpenSTA 2019 (sim/eda/power/power.h).
#include "sim/eda/power/power.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "model/text_file.h"
#include "sim/eda/common/process.h"
#include "sim/eda/common/tool_script.h"
#include "sim/eda/power/power_netlist.h"

namespace shadesim {
// A named namespace, not an anonymous one: sim/ is compiled as unity files (CMakeLists.txt).
namespace power_impl {

namespace fs = std::filesystem;

// One flip-flop of the netlist and where its activity comes from.
struct Flop {
  std::string instance, cell, state_pin, net, net_text;
  bool net_inverted = false;                          // `net` is QN's
  std::vector<std::pair<std::string, bool>> outputs;  // connected state outputs (Q, QN: inverted)
  std::vector<std::string> names;  // the output net's names: itself, then its assign aliases
  std::string rtl_name;            // the name found in the activity map; empty: none
  uint64_t toggles = 0;
  std::string reason;  // why it is not annotated (empty: annotated)
};

// "a.b[3]" -> "a.b"; "a.b[2][3]" -> "a.b[2]"; "x" -> "x".
std::string register_of(const std::string& bit) {
  if (bit.empty() || bit.back() != ']') return bit;
  const auto open = bit.rfind('[');
  return open == std::string::npos ? bit : bit.substr(0, open);
}

// The flip-flops of the netlist with the names of their output nets.
std::vector<Flop> find_flops(const MappedNetlist& n,
                             const std::map<std::string, LibertyCellPins>& cells) {
  const auto aliases = net_aliases(n);
  std::vector<Flop> out;
  for (const auto& inst : n.instances) {
    const auto cell = cells.find(inst.cell);
    if (cell == cells.end() || !cell->second.sequential()) continue;
    Flop f;
    f.instance = inst.name;
    f.cell = inst.cell;
    f.state_pin = cell->second.state_pin;
    const std::vector<std::string> outs = cell->second.state_outputs();
    for (const auto& c : inst.pins) {
      if (std::find(outs.begin(), outs.end(), c.pin) == outs.end() || c.net.empty()) continue;
      f.outputs.emplace_back(c.pin, cell->second.inverted_output(c.pin));
      if (f.net.empty()) {
        f.net = c.net;
        f.net_text = c.text;
        f.net_inverted = f.outputs.back().second;
      }
    }
    if (!f.net.empty()) f.names.push_back(f.net);
    const auto al = aliases.find(f.net);
    if (al != aliases.end())
      for (const auto& a : al->second)
        if (a != f.net) f.names.push_back(a);
    out.push_back(f);
  }
  return out;
}

// "a.genblk1.genblk2.b" -> "a.b": Yosys keeps an unnamed generate block's scope (genblkN, as
// IEEE 1800 names it), Verilator's trace leaves it out.
std::string without_genblk(const std::string& name) {
  static const std::regex genblk(R"((^|\.)genblk[0-9]+\.)");
  std::string out = name, before;
  while (out != before) {  // one pass leaves every second of adjacent ones
    before = out;
    out = std::regex_replace(out, genblk, "$1");
  }
  return out;
}

// The activity map's entry for a netlist name: itself or without its genblk scopes, each also
// as the same one-bit signal with or without a "[0]" (Yosys names a [0:0] vector's bit x[0]).
const std::pair<const std::string, uint64_t>* lookup(const SceneActivity& a,
                                                     const std::string& name) {
  for (const std::string& n : {name, without_genblk(name)}) {
    auto it = a.signals.find(n);
    if (it == a.signals.end() && n.size() > 3 && n.compare(n.size() - 3, 3, "[0]") == 0)
      it = a.signals.find(n.substr(0, n.size() - 3));
    if (it == a.signals.end() && (n.empty() || n.back() != ']')) it = a.signals.find(n + "[0]");
    if (it != a.signals.end()) return &*it;
  }
  return nullptr;
}

double duty_of(const SceneActivity& a, const std::string& rtl_name, double fallback) {
  const auto it = a.duty.find(rtl_name);
  return it != a.duty.end() ? it->second : fallback;
}

// Registers whose netlist bits include one the RTL does not have (fsm_recode's one-hot bits):
// the names on them no longer mean the RTL's bits.
std::set<std::string> reencoded_registers(const std::vector<Flop>& flops, const SceneActivity& a) {
  std::set<std::string> rtl_registers, out;
  for (const auto& [name, t] : a.signals) rtl_registers.insert(register_of(name));
  for (const auto& f : flops)
    for (const auto& name : f.names)
      if (rtl_registers.count(register_of(without_genblk(name))) && !lookup(a, name))
        out.insert(register_of(name));
  return out;
}

void match_flops(std::vector<Flop>& flops, const SceneActivity& a, const PowerOptions& o) {
  const std::set<std::string> reencoded = reencoded_registers(flops, a);
  std::set<std::string> excluded;  // as the trace names them
  for (const auto& e : o.excluded_registers) excluded.insert(without_genblk(e));
  for (auto& f : flops) {
    for (const auto& name : f.names) {
      if (const auto* e = lookup(a, name)) {
        f.rtl_name = e->first;
        f.toggles = e->second;
        break;
      }
    }
    std::string reg = register_of(f.rtl_name);
    for (const auto& name : f.names)
      if (reencoded.count(register_of(name))) reg = register_of(name);
    if (f.net.empty())
      f.reason = "no output pin connected";
    else if (excluded.count(without_genblk(reg)))
      f.reason = "register " + reg + " excluded (re-encoded by synthesis)";
    else if (reencoded.count(reg))
      f.reason = "register " + reg + " has netlist bits the RTL lacks (re-encoded by synthesis)";
    else if (f.rtl_name.empty())
      f.reason = "no RTL name on its output net";
  }
}

// A name as an OpenSTA pattern: brackets escaped, in braces.
std::string pattern(const std::string& name) {
  std::string s;
  for (char c : name) {
    if (c == '[' || c == ']') s += '\\';
    s += c;
  }
  return "{" + s + "}";
}

std::string number(double v) {
  std::ostringstream os;
  os << std::setprecision(9) << v;
  return os.str();
}

// The power scripts beside this file; their headers say what each does.
std::string script_head(const std::string& liberty, const std::string& netlist,
                        const std::string& top, double clock_mhz, const PowerOptions& o) {
  return fill_placeholders(tool_script("sim/eda/power/power_setup.tcl"),
                           {{"@LIBERTY@", liberty},
                            {"@NETLIST@", netlist},
                            {"@TOP@", top},
                            {"@PERIOD@", number(1000.0 / clock_mhz)},
                            {"@CLOCK@", pattern(o.clock_port)}});
}

struct Annotation {
  std::string script;
  int flops = 0, flops_annotated = 0, inputs = 0, inputs_annotated = 0, constants = 0;
  std::vector<std::string> unannotated;
};

// The name of the input port that carries flip-flop i's activity in the power netlist.
std::string flop_port(size_t i) { return "shadesim_ff_" + std::to_string(i); }

// Each flip-flop's activity on its state pin, its state outputs and its port (power.h says why
// all three), and its sequential inputs preset.
void annotate_flops(const std::vector<Flop>& flops, const MappedNetlist& n,
                    const std::map<std::string, LibertyCellPins>& cells, const SceneActivity& a,
                    const PowerOptions& o, Annotation& out) {
  std::ostringstream s;
  for (size_t i = 0; i < flops.size(); ++i) {
    const Flop& f = flops[i];
    ++out.flops;
    const bool ok = f.reason.empty();
    const std::string act = number(ok ? a.rate(f.toggles) : o.default_activity);
    const double d = ok ? duty_of(a, f.rtl_name, o.duty) : o.duty;
    const std::string duty = number(d);
    s << "# " << f.instance << ": " << (ok ? f.rtl_name : "default: " + f.reason) << '\n';
    s << "shadesim_pin " << pattern(f.instance + "/" + f.state_pin) << ' ' << act << ' ' << duty
      << '\n';
    for (const auto& [q, inverted] : f.outputs)
      s << "shadesim_pin " << pattern(f.instance + "/" + q) << ' ' << act << ' '
        << (inverted ? number(1 - d) : duty) << '\n';
    if (!f.net.empty())
      s << "shadesim_port " << flop_port(i) << ' ' << act << ' '
        << (f.net_inverted ? number(1 - d) : duty) << '\n';
    if (ok)
      ++out.flops_annotated;
    else
      out.unannotated.push_back(f.instance + " (" + (f.net.empty() ? "-" : f.net) +
                                "): " + f.reason);
  }
  for (const auto& inst : n.instances) {
    const auto cell = cells.find(inst.cell);
    if (cell == cells.end() || !cell->second.sequential()) continue;
    for (const auto& c : inst.pins) {
      const auto dir = cell->second.direction.find(c.pin);
      if (dir == cell->second.direction.end() || dir->second != "input") continue;
      if (constant_value(c.net) < 0)
        s << "shadesim_pin " << pattern(inst.name + "/" + c.pin) << " 0 0.5\n";
    }
  }
  out.script += s.str();
}

// The netlist OpenSTA annotates: the mapped one with an input port per flip-flop on its output
// net (power.h says why).
std::string write_power_netlist(const std::string& netlist_v, const std::string& top,
                                const std::vector<Flop>& flops, const fs::path& path) {
  const std::string text = read_text_file(netlist_v);
  std::vector<std::pair<std::string, std::string>> ports;
  for (size_t i = 0; i < flops.size(); ++i)
    if (!flops[i].net.empty()) ports.emplace_back(flop_port(i), flops[i].net_text);
  std::ofstream os(path);
  os << add_input_ports(text, top, ports);
  if (!os) throw std::runtime_error("power: cannot write " + path.string());
  return path.string();
}

// Pins tied to constants (any cell): activity 0, duty the value.
void annotate_constants(const MappedNetlist& n, const std::map<std::string, LibertyCellPins>& cells,
                        Annotation& out) {
  std::ostringstream s;
  for (const auto& inst : n.instances) {
    const auto cell = cells.find(inst.cell);
    if (cell == cells.end()) continue;
    for (const auto& c : inst.pins) {
      const int v = constant_value(c.net);
      const auto dir = cell->second.direction.find(c.pin);
      if (v < 0 || dir == cell->second.direction.end() || dir->second != "input") continue;
      s << "shadesim_pin " << pattern(inst.name + "/" + c.pin) << " 0 " << v << '\n';
      ++out.constants;
    }
  }
  out.script += s.str();
}

void annotate_inputs(const MappedNetlist& n, const SceneActivity& a, const PowerOptions& o,
                     Annotation& out) {
  std::ostringstream s;
  for (const auto& port : n.inputs) {
    if (port == o.clock_port) continue;
    ++out.inputs;
    const auto it = a.signals.find(port);
    const bool ok = it != a.signals.end();
    out.inputs_annotated += ok ? 1 : 0;
    s << "shadesim_port " << pattern(port) << ' '
      << number(ok ? a.rate(it->second) : o.default_activity) << ' '
      << number(ok ? duty_of(a, port, o.duty) : o.duty)
      << (ok ? "" : "  ;# default: not in the simulation's ports") << '\n';
  }
  out.script += s.str();
}

std::string run_sta(const std::string& sta, const fs::path& tcl, const std::string& text) {
  {
    std::ofstream os(tcl);
    os << text;
    if (!os) throw std::runtime_error("power: cannot write " + tcl.string());
  }
  fs::path out = tcl;
  out.replace_extension(".out");
  const ProcessResult r = run_process({sta, "-no_splash", "-exit", tcl.string()}, out.string());
  std::string output = read_text_file(out.string());  // returned: moved
  if (r.exit_code != 0 || output.find("Error") != std::string::npos)
    throw std::runtime_error("power: sta " + tcl.string() + " failed (exit " +
                             std::to_string(r.exit_code) + "):\n" + output);
  return output;
}

void check_nothing_missing(const std::string& output, const std::string& what) {
  if (output.find("shadesim: missing 0") == std::string::npos)
    throw std::runtime_error("power: OpenSTA did not find every pin the netlist reader saw (" +
                             what + "):\n" + output);
}

std::vector<std::string> method_notes(const PowerOptions& o, const Annotation& an) {
  // NOLINTBEGIN(bugprone-suspicious-missing-comma): each note is one literal, in pieces
  return {
      "flip-flops: the RTL register bit's toggles per cycle and time at 1 (the trace) on the "
      "cell's state pin, Q and an added input port on Q's net (OpenSTA 2019 would otherwise "
      "recompute Q from D; its set_power_activity -pins is broken)",
      "inputs: each port bit's toggles per cycle and time at 1; the clock 2 transitions per "
      "period",
      "combinational nets: OpenSTA's propagation from annotated sequential outputs and inputs, "
      "zero-delay, no glitches, inputs of a gate taken as independent",
      "unmatched flip-flops and input bits: " + number(o.default_activity) +
          " toggles per cycle, duty " + number(o.duty),
      std::to_string(an.constants) + " input pins tied to constants: activity 0",
      "OpenSTA 2019 charges rise + fall internal energy on every transition of a clock-related "
      "arc (clock pins, clock-to-Q): about twice its later versions' figure for those",
      "left out: glitches, wires (no wire load), a clock tree, any corner but the "
      "library's typical"};
  // NOLINTEND(bugprone-suspicious-missing-comma)
}

}  // namespace power_impl

double pj_per_pixel(double total_mw, uint64_t cycles, double clock_mhz, uint64_t pixels) {
  if (pixels == 0 || clock_mhz <= 0) return 0;
  return 1000.0 * total_mw * static_cast<double>(cycles) /
         (clock_mhz * static_cast<double>(pixels));
}

std::string PowerReport::coverage_text() const {
  std::ostringstream s;
  s << flip_flops_annotated << " of " << flip_flops << " flip-flops annotated from the simulation ("
    << flip_flops - flip_flops_annotated << " at the default " << default_activity_value
    << " toggles/cycle), " << input_bits_annotated << " of " << input_bits << " input bits";
  return s.str();
}

PowerFigures parse_report_power(const std::string& sta_output) {
  PowerFigures p;
  bool total = false;
  std::istringstream is(sta_output);
  for (std::string line; std::getline(is, line);) {
    std::istringstream ls(line);
    std::string row;
    double v[4];
    if (!(ls >> row >> v[0] >> v[1] >> v[2] >> v[3])) continue;
    if (row == "Sequential") p.sequential_mw = v[3] * 1e3;
    if (row == "Combinational") p.combinational_mw = v[3] * 1e3;
    if (row != "Total") continue;
    p.internal_mw = v[0] * 1e3;
    p.switching_mw = v[1] * 1e3;
    p.leakage_mw = v[2] * 1e3;
    p.total_mw = v[3] * 1e3;
    total = true;
  }
  if (!total) throw std::runtime_error("power: no Total row in report_power's output");
  return p;
}

namespace power_impl {

// The scene's run: the annotated script on the netlist with a port per flip-flop.
Annotation annotate_scene(const std::string& netlist_v, const std::string& liberty,
                          const std::string& top, const SceneActivity& activity, double clock_mhz,
                          const fs::path& work, const PowerOptions& o) {
  const auto cells = read_liberty_cells(liberty);
  const MappedNetlist n = read_mapped_netlist(netlist_v, top);
  std::vector<Flop> flops = find_flops(n, cells);
  match_flops(flops, activity, o);
  const std::string power_v = write_power_netlist(netlist_v, top, flops, work / "power_netlist.v");
  Annotation an;
  an.script = script_head(liberty, power_v, top, clock_mhz, o) +
              tool_script("sim/eda/power/power_procs.tcl");
  annotate_constants(n, cells, an);
  annotate_flops(flops, n, cells, activity, o, an);
  annotate_inputs(n, activity, o, an);
  an.script += tool_script("sim/eda/power/power_report.tcl");
  return an;
}

PowerReport report_of(const Annotation& an, const SceneActivity& activity, double clock_mhz,
                      const PowerOptions& o) {
  PowerReport r;
  r.clock_mhz = clock_mhz;
  r.cycles = activity.cycles;
  r.pixels = activity.pixels;
  r.flip_flops = an.flops;
  r.flip_flops_annotated = an.flops_annotated;
  r.input_bits = an.inputs;
  r.input_bits_annotated = an.inputs_annotated;
  r.constant_pins = an.constants;
  r.default_activity_value = o.default_activity;
  r.duty = o.duty;
  r.unannotated = an.unannotated;
  r.notes = method_notes(o, an);
  return r;
}

}  // namespace power_impl

PowerReport netlist_power(const std::string& netlist_v, const std::string& liberty,
                          const std::string& top, const SceneActivity& activity, double clock_mhz,
                          const std::string& work_dir, const PowerOptions& o) {
  using namespace power_impl;
  if (clock_mhz <= 0) throw std::invalid_argument("netlist_power: clock must be > 0 MHz");
  const std::string sta = find_program(o.sta, "opensta", "power");
  const fs::path work(work_dir);
  fs::create_directories(work);
  const Annotation an = annotate_scene(netlist_v, liberty, top, activity, clock_mhz, work, o);
  const std::string scene_out = run_sta(sta, work / "power.tcl", an.script);
  check_nothing_missing(scene_out, "power.tcl");
  const auto global_run = [&](const char* name, double a) {
    return parse_report_power(
        run_sta(sta, work / name,
                script_head(liberty, netlist_v, top, clock_mhz, o) +
                    fill_placeholders(tool_script("sim/eda/power/power_global.tcl"),
                                      {{"@ACTIVITY@", number(a)}, {"@DUTY@", number(o.duty)}})));
  };
  PowerReport r = report_of(an, activity, clock_mhz, o);
  r.scene = parse_report_power(scene_out);
  r.default_activity = global_run("default.tcl", o.default_activity);
  r.clock_only = global_run("clock.tcl", 0.0);
  r.pj_per_pixel = pj_per_pixel(r.scene.total_mw, r.cycles, clock_mhz, r.pixels);
  r.default_pj_per_pixel = pj_per_pixel(r.default_activity.total_mw, r.cycles, clock_mhz, r.pixels);
  return r;
}

std::vector<std::string> fsm_recoded_registers(const std::string& yosys_log) {
  static const std::regex re(R"(Recoding FSM `\$fsm\$\\?(.*)\$[0-9]+')");
  std::set<std::string> names;
  std::istringstream is(yosys_log);
  std::smatch m;
  for (std::string line; std::getline(is, line);)
    if (std::regex_search(line, m, re)) names.insert(m[1].str());
  return {names.begin(), names.end()};
}

namespace power_impl {

nlohmann::json figures_json(const PowerFigures& p) {
  return {{"internal_mw", p.internal_mw},     {"switching_mw", p.switching_mw},
          {"leakage_mw", p.leakage_mw},       {"total_mw", p.total_mw},
          {"sequential_mw", p.sequential_mw}, {"combinational_mw", p.combinational_mw}};
}

PowerFigures figures_from(const nlohmann::json& j) {
  PowerFigures p;
  p.internal_mw = j.at("internal_mw").get<double>();
  p.switching_mw = j.at("switching_mw").get<double>();
  p.leakage_mw = j.at("leakage_mw").get<double>();
  p.total_mw = j.at("total_mw").get<double>();
  p.sequential_mw = j.at("sequential_mw").get<double>();
  p.combinational_mw = j.at("combinational_mw").get<double>();
  return p;
}

}  // namespace power_impl

std::string power_scripts_commands() {
  std::string commands;
  for (const char* script : {"sim/eda/power/power_setup.tcl", "sim/eda/power/power_procs.tcl",
                             "sim/eda/power/power_report.tcl", "sim/eda/power/power_global.tcl"})
    commands += tool_script(script);
  return commands;
}

std::string power_report_to_json(const PowerReport& r) {
  nlohmann::json j;
  j["clock_mhz"] = r.clock_mhz;
  j["cycles"] = r.cycles;
  j["pixels"] = r.pixels;
  j["scene"] = power_impl::figures_json(r.scene);
  j["default_activity"] = power_impl::figures_json(r.default_activity);
  j["clock_only"] = power_impl::figures_json(r.clock_only);
  j["pj_per_pixel"] = r.pj_per_pixel;
  j["default_pj_per_pixel"] = r.default_pj_per_pixel;
  j["flip_flops"] = r.flip_flops;
  j["flip_flops_annotated"] = r.flip_flops_annotated;
  j["input_bits"] = r.input_bits;
  j["input_bits_annotated"] = r.input_bits_annotated;
  j["constant_pins"] = r.constant_pins;
  j["default_activity_value"] = r.default_activity_value;
  j["duty"] = r.duty;
  j["unannotated"] = r.unannotated;
  j["notes"] = r.notes;
  return j.dump(2);
}

PowerReport power_report_from_json(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  PowerReport r;
  r.clock_mhz = j.at("clock_mhz").get<double>();
  r.cycles = j.at("cycles").get<uint64_t>();
  r.pixels = j.at("pixels").get<uint64_t>();
  r.scene = power_impl::figures_from(j.at("scene"));
  r.default_activity = power_impl::figures_from(j.at("default_activity"));
  r.clock_only = power_impl::figures_from(j.at("clock_only"));
  r.pj_per_pixel = j.at("pj_per_pixel").get<double>();
  r.default_pj_per_pixel = j.at("default_pj_per_pixel").get<double>();
  r.flip_flops = j.at("flip_flops").get<int>();
  r.flip_flops_annotated = j.at("flip_flops_annotated").get<int>();
  r.input_bits = j.at("input_bits").get<int>();
  r.input_bits_annotated = j.at("input_bits_annotated").get<int>();
  r.constant_pins = j.at("constant_pins").get<int>();
  r.default_activity_value = j.at("default_activity_value").get<double>();
  r.duty = j.at("duty").get<double>();
  r.unannotated = j.at("unannotated").get<std::vector<std::string>>();
  r.notes = j.at("notes").get<std::vector<std::string>>();
  return r;
}

}  // namespace shadesim
