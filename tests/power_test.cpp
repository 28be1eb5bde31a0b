// Power from a scene's switching activity (sim/eda/power/activity.h, sim/eda/power/power.h),
// validated where toggles can be counted by hand: tests/data/power/power_fixture.sv, a 4-bit
// counter (bit i toggles once every 2^i cycles) and a 4-stage shift register fed 1,1,0,0,...,
// driven by power_fixture_tb.cpp as the harness drives shade_unit, and mapped onto osu018
// (power_fixture_osu018.v). Expected values are hand counts and closed forms in this file:
//   - Verilator's toggle coverage counts exactly the toggles (the counts below, for 64 cycles
//     after 4 reset edges);
//   - the annotation gives the power OpenSTA reports for the same activities typed by hand;
//   - switching power doubles with the activity, and a shift-register stage's switching power is
//     1/2 C V^2 x toggles per cycle x f with C the next stage's D pin from the Liberty file;
//   - unmatched and re-encoded flip-flops are counted and get the default;
//   - on a real unit, the covered co-simulation's input-port toggles equal the harness's
//     stimulus replayed without the RTL.
#include "sim/eda/power/power.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "host/frame.h"
#include "model/unit_config_file.h"
#include "sim/eda/common/process.h"
#include "sim/eda/power/activity.h"
#include "sim/eda/power/power_netlist.h"
#include "sim/engines/area_report.h"
#include "sim/engines/scene_activity.h"
#include "sim/engines/unit_choice.h"
#include "sim/engines/unit_power.h"
#include "sim/harness/cosim.h"
#include "tests/support/cli_run.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

const std::string kLiberty = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib";
const std::string kData = std::string(SHADESIM_SOURCE_DIR) + "/tests/data/power/";
const std::string kNetlist = kData + "power_fixture_osu018.v";

std::string which(const std::string& program) {
  const Result r = run_shell("command -v " + program);
  return r.status == 0 ? r.output.substr(0, r.output.find('\n')) : "";
}

// OpenSTA and the osu018 library are the flow's tools: their absence fails the test unless the
// build allowed missing tools (tests/support/test_data.h's rule).
#if SHADESIM_TEST_DATA_OPTIONAL
#define SHADESIM_NEEDS_POWER_TOOLS()                                            \
  if (which("sta").empty() || !fs::exists(kLiberty))                            \
  GTEST_SKIP() << "sta or " << kLiberty << " absent (Debian packages opensta, " \
               << "qflow-tech-osu018; allowed by SHADESIM_ALLOW_MISSING_TOOLS)"
#else
#define SHADESIM_NEEDS_POWER_TOOLS()                                          \
  if (which("sta").empty() || !fs::exists(kLiberty))                          \
  FAIL() << "sta or " << kLiberty << " absent: install Debian's opensta and " \
         << "qflow-tech-osu018"
#endif

// The fixture's 64 traced cycles (after 4 reset edges, which are not traced).
constexpr uint64_t kCycles = 64;

// The hand counts (power_fixture_tb.cpp; the first sample, cycle 0's, is the baseline). d_i is
// 1,1,0,0,... so it changes on cycles 2, 4, ..., 62 (31 times). count_q bit i toggles 64 / 2^i
// times. shift_q[k] holds d_i of cycle c - k after edge c, so it changes after edges c with
// c - k in {0, 2, 4, ...} and c <= 63: 32, 32, 31, 31; g_blk.blk_q[j] holds d_i of cycle
// c - 4 - j: 30, 30. g_div[0] toggles on edges with count_q[0] set (odd cycles, 32), g_div[1]
// with count_q[1:0] set (cycles 3 mod 4, 16); g_div[1]'s enable is 1 in those 16 cycles, so
// it rises and falls 16 times each. clk_i: a rise and a fall per cycle but the last fall (127).
ToggleMap hand_counts() {
  return {{"count_q[0]", 64},
          {"count_q[1]", 32},
          {"count_q[2]", 16},
          {"count_q[3]", 8},
          {"shift_q[0]", 32},
          {"shift_q[1]", 32},
          {"shift_q[2]", 31},
          {"shift_q[3]", 31},
          {"g_blk.blk_q[0]", 30},
          {"g_blk.blk_q[1]", 30},
          {"g_div[0].u_toggle.q_q", 32},
          {"g_div[1].u_toggle.q_q", 16},
          {"g_div[1].u_toggle.en_i", 32},
          {"d_i", 31},
          {"rst_ni", 0},
          {"clk_i", 127}};
}

SceneActivity hand_activity() {
  SceneActivity a;
  a.cycles = kCycles;
  a.pixels = 17;  // any: pJ/pixel only
  a.signals = hand_counts();
  a.duty = {{"count_q[3]", 0.25}, {"rst_ni", 1.0}};  // the rest: PowerOptions::duty, 0.5
  return a;
}

// The fixture Verilated as the traced builds are (--trace-fst), with toggle coverage too, run
// for kCycles cycles: returns the FST path ("" when it did not build or run).
std::string fixture_trace(const fs::path& dir) {
  const std::string verilator = which("verilator");
  if (verilator.empty()) return "";
  const ProcessResult b = run_process(
      {verilator, "--cc", "--exe", "--build", "-j", "1", "--trace-fst", "--coverage-toggle",
       "--Mdir", (dir / "obj").string(), "--top-module", "power_fixture",
       kData + "power_fixture.sv", kData + "power_fixture_tb.cpp", "-o", "fixture"},
      (dir / "verilator.log").string());
  if (b.exit_code != 0) return "";
  const std::string fst = (dir / "trace.fst").string();
  const ProcessResult r = run_process({(dir / "obj" / "fixture").string(), fst,
                                       std::to_string(kCycles), (dir / "coverage.dat").string()},
                                      "");
  return r.exit_code == 0 ? fst : "";
}

PowerFigures run_sta_script(const fs::path& dir, const std::string& name, const std::string& tcl) {
  const fs::path path = dir / name;
  std::ofstream(path) << tcl;
  const ProcessResult r = run_process({which("sta"), "-no_splash", "-exit", path.string()}, "");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return parse_report_power(r.output);
}

// The fixture's netlist as power.h says OpenSTA 2019 must see it, edited here by hand: an input
// port per flip-flop on its Q net, which carries the flip-flop's activity into the logic it drives.
std::string hand_netlist(const fs::path& dir) {
  std::ifstream is(kNetlist);
  std::string v(std::istreambuf_iterator<char>(is), {});
  const std::string head = "module power_fixture(";
  v.replace(v.find(head), head.size(),
            head + "h16, h17, h18, h19, h20, h21, h22, h23, h24, h25, h26, h27, ");
  v.replace(v.rfind("endmodule"), 9,
            R"(  input h16, h17, h18, h19, h20, h21, h22, h23, h24, h25, h26, h27;
  assign \g_blk.blk_q[0]  = h16;
  assign \g_blk.blk_q[1]  = h17;
  assign \shift_q[0]  = h18;
  assign \shift_q[1]  = h19;
  assign \shift_q[2]  = h20;
  assign \shift_q[3]  = h21;
  assign \count_q[0]  = h22;
  assign \count_q[1]  = h23;
  assign \count_q[2]  = h24;
  assign \count_q[3]  = h25;
  assign \g_div[1].u_toggle.q_q  = h26;
  assign \g_div[0].u_toggle.q_q  = h27;
endmodule)");
  const fs::path path = dir / "hand.v";
  std::ofstream(path) << v;
  return path.string();
}

// The activities of hand_activity() typed by hand (100 MHz, 64 cycles): each flip-flop's state
// pin (DFFPOSX1 DS0000, DFFSR P0002), Q and port, its inputs preset to 0 (power.h says why), the
// S pins tied to 1, the inputs. `scale` multiplies every activity.
std::string hand_script(const std::string& netlist, double scale) {
  std::ostringstream s;
  s << "read_liberty " << kLiberty << "\nread_verilog " << netlist << R"(
link_design power_fixture
create_clock -name clk -period 10 [get_ports clk_i]
set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports clk_i]]
set_output_delay 0 -clock clk [all_outputs]
proc ff {inst state port toggles duty} {
  global k
  sta::set_power_pin_activity [get_pins $inst/$state] [expr $toggles * $k] $duty
  sta::set_power_pin_activity [get_pins $inst/Q] [expr $toggles * $k] $duty
  sta::set_power_input_port_activity [get_ports $port] [expr $toggles * $k] $duty
}
)"
    << "set k [expr " << scale << " / 64.0]\n"
    << R"(
ff _16_ DS0000 h16 30 0.5
ff _17_ DS0000 h17 30 0.5
ff _18_ DS0000 h18 32 0.5
ff _19_ DS0000 h19 32 0.5
ff _20_ DS0000 h20 31 0.5
ff _21_ DS0000 h21 31 0.5
ff _22_ P0002 h22 64 0.5
ff _23_ P0002 h23 32 0.5
ff _24_ P0002 h24 16 0.5
ff _25_ P0002 h25 8 0.25
ff _26_ P0002 h26 16 0.5
ff _27_ P0002 h27 32 0.5
foreach inst {_16_ _17_ _18_ _19_ _20_ _21_} {
  foreach pin {D CLK} { sta::set_power_pin_activity [get_pins $inst/$pin] 0 0.5 }
}
foreach inst {_22_ _23_ _24_ _25_ _26_ _27_} {
  foreach pin {D CLK R} { sta::set_power_pin_activity [get_pins $inst/$pin] 0 0.5 }
  sta::set_power_pin_activity [get_pins $inst/S] 0 1
}
sta::set_power_input_port_activity [get_ports d_i] [expr 31 * $k] 0.5
sta::set_power_input_port_activity [get_ports rst_ni] 0 1
report_power -digits 6
)";
  return s.str();
}

void expect_near_rel(double got, double want, double rel, const char* what) {
  EXPECT_NEAR(got, want, std::abs(want) * rel) << what;
}

// The trace's counts are the hand counts, per instance of g_div and inside g_blk; the duty of
// a few bits by hand over [40, 680] (64 cycles from the first sample, 10 units each): count_q's
// bits are 1 for 32 of the 64 counter values, g_div[1]'s enable for 16, rst_ni always.
// And why not Verilator's toggle coverage (sim/eda/power/activity.h): on the same run it counts
// count_q right, but merges the two g_div instances into one point (32 + 16) and has no point for
// the register declared in a generate block. (One test: one Verilator build of the fixture.)
TEST(Activity, TheTraceGivesTheHandCountedTogglesWhereToggleCoverageCannot) {
  const fs::path dir = temp_dir("power", "trace");
  const std::string fst = fixture_trace(dir);
  ASSERT_FALSE(fst.empty()) << "the fixture did not build or run: " << dir / "verilator.log";
  const SceneActivity a = activity_from_trace(fst, "power_fixture", 17);
  EXPECT_EQ(a.cycles, kCycles);
  for (const auto& [name, toggles] : hand_counts()) {
    ASSERT_TRUE(a.signals.count(name)) << name;
    EXPECT_EQ(a.signals.at(name), toggles) << name;
  }
  EXPECT_EQ(a.signals.at("count_o[2]"), 16u);  // a port: the same bits
  EXPECT_DOUBLE_EQ(a.duty.at("count_q[0]"), 0.5);
  EXPECT_DOUBLE_EQ(a.duty.at("count_q[3]"), 0.5);
  EXPECT_DOUBLE_EQ(a.duty.at("g_div[1].u_toggle.en_i"), 0.25);
  EXPECT_DOUBLE_EQ(a.duty.at("rst_ni"), 1.0);
  EXPECT_DOUBLE_EQ(a.duty.at("clk_i"), 0.5);
  EXPECT_DOUBLE_EQ(a.rate(a.signals.at("count_q[2]")), 16.0 / 64.0);

  std::ifstream is(dir / "coverage.dat");
  std::map<std::string, uint64_t> points;
  const std::regex point("\x01o\x02([^\x01]*)\x01h\x02([^']*)' ([0-9]+)");
  std::smatch m;
  for (std::string line; std::getline(is, line);)
    if (std::regex_search(line, m, point))
      points[m[2].str() + "/" + m[1].str()] = std::stoull(m[3].str());
  EXPECT_EQ(points.at("TOP.power_fixture/count_q[3]"), 8u);
  EXPECT_EQ(points.at("TOP.power_fixture.g_div[*].u_toggle/q_q"), 32u + 16u);
  EXPECT_FALSE(points.count("TOP.power_fixture.g_div[0].u_toggle/q_q"));
  for (const auto& [name, count] : points) EXPECT_EQ(name.find("blk_q"), std::string::npos) << name;
}

TEST(Power, TheAnnotationGivesThePowerOfTheSameActivitiesTypedByHand) {
  SHADESIM_NEEDS_POWER_TOOLS();
  const fs::path dir = temp_dir("power", "by_hand");
  const PowerReport r = netlist_power(kNetlist, kLiberty, "power_fixture", hand_activity(), 100,
                                      (dir / "work").string());
  const PowerFigures hand = run_sta_script(dir, "hand.tcl", hand_script(hand_netlist(dir), 1.0));
  expect_near_rel(r.scene.total_mw, hand.total_mw, 1e-5, "total");
  expect_near_rel(r.scene.internal_mw, hand.internal_mw, 1e-5, "internal");
  expect_near_rel(r.scene.switching_mw, hand.switching_mw, 1e-5, "switching");
  expect_near_rel(r.scene.leakage_mw, hand.leakage_mw, 1e-5, "leakage");
  EXPECT_EQ(r.flip_flops, 12);
  EXPECT_EQ(r.flip_flops_annotated, 12);
  EXPECT_EQ(r.input_bits, 2);  // d_i, rst_ni (clk_i is the clock)
  EXPECT_EQ(r.input_bits_annotated, 2);
  EXPECT_EQ(r.constant_pins, 6);  // the DFFSRs' S
  EXPECT_TRUE(r.unannotated.empty());
  EXPECT_EQ(r.coverage_text().rfind("12 of 12 flip-flops annotated from the simulation", 0), 0u);
  // The comparison run: every pin at the global 0.1.
  EXPECT_NE(r.default_activity.total_mw, r.scene.total_mw);
}

TEST(Power, SwitchingPowerDoublesWhenTheActivityDoubles) {
  SHADESIM_NEEDS_POWER_TOOLS();
  const fs::path dir = temp_dir("power", "double");
  SceneActivity twice = hand_activity();
  for (auto& [name, t] : twice.signals) t *= 2;
  const PowerReport one = netlist_power(kNetlist, kLiberty, "power_fixture", hand_activity(), 100,
                                        (dir / "one").string());
  const PowerReport two =
      netlist_power(kNetlist, kLiberty, "power_fixture", twice, 100, (dir / "two").string());
  // Every activity OpenSTA propagates is linear in its inputs' at fixed duty; the fixture's clock
  // comes from a port (no clock cell whose switching would stay put).
  expect_near_rel(two.scene.switching_mw, 2 * one.scene.switching_mw, 1e-5, "switching");
  expect_near_rel(two.scene.leakage_mw, one.scene.leakage_mw, 1e-9, "leakage");
  EXPECT_GT(two.scene.internal_mw, one.scene.internal_mw);
  // And typed by hand at twice the activity.
  const PowerFigures hand = run_sta_script(dir, "hand2.tcl", hand_script(hand_netlist(dir), 2.0));
  expect_near_rel(two.scene.total_mw, hand.total_mw, 1e-5, "total at twice the activity");
}

// Each shift register stage (_18_ .. _21_: shift_q[0..3], _16_: g_blk.blk_q[0]) drives one
// DFFPOSX1's D and no cell else: its switching power is 1/2 C V^2 a f with C = DFFPOSX1's D
// capacitance (osu018: 0.00882947 pF rise, 0.00881001 fall; OpenSTA takes the larger),
// V = 1.8 V, a its toggles per cycle, f = 100 MHz.
TEST(Power, AShiftRegisterStageSwitchesHalfCVSquaredPerToggle) {
  SHADESIM_NEEDS_POWER_TOOLS();
  const fs::path dir = temp_dir("power", "closed_form");
  const std::string tcl = hand_script(hand_netlist(dir), 1.0) +
                          "report_power -instances [get_cells {_16_ _18_ _19_ _20_ _21_}] "
                          "-digits 6\n";
  std::ofstream(dir / "inst.tcl") << tcl;
  const ProcessResult r =
      run_process({which("sta"), "-no_splash", "-exit", (dir / "inst.tcl").string()}, "");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double c = 0.00882947e-12, v = 1.8, f = 100e6;
  const std::map<std::string, double> toggles = {
      {"_16_", 30}, {"_18_", 32}, {"_19_", 32}, {"_20_", 31}, {"_21_", 31}};
  for (const auto& [inst, t] : toggles) {
    const std::regex row(R"(\s*(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+)" + inst + R"(\s*)");
    std::smatch m;
    bool found = false;
    std::istringstream is(r.output);
    for (std::string line; std::getline(is, line);) {
      if (!std::regex_match(line, m, row)) continue;
      found = true;
      expect_near_rel(std::stod(m[2].str()), 0.5 * c * v * v * (t / 64.0) * f, 1e-4, inst.c_str());
    }
    EXPECT_TRUE(found) << inst << " not in\n" << r.output;
  }
}

TEST(Power, UnmatchedAndReencodedFlipFlopsAreCountedAndGetTheDefault) {
  SHADESIM_NEEDS_POWER_TOOLS();
  const fs::path dir = temp_dir("power", "unmatched");
  // No shift register in the map: its four flip-flops have no RTL name.
  SceneActivity a = hand_activity();
  for (int k = 0; k < 4; ++k) a.signals.erase("shift_q[" + std::to_string(k) + "]");
  PowerReport r = netlist_power(kNetlist, kLiberty, "power_fixture", a, 100, (dir / "a").string());
  EXPECT_EQ(r.flip_flops_annotated, 8);
  ASSERT_EQ(r.unannotated.size(), 4u);
  EXPECT_NE(r.unannotated[0].find("no RTL name"), std::string::npos) << r.unannotated[0];
  // count_q with bits 0..2 only in the RTL: the netlist's count_q[3] says it was re-encoded, so
  // none of its bits is trusted.
  a = hand_activity();
  a.signals.erase("count_q[3]");
  r = netlist_power(kNetlist, kLiberty, "power_fixture", a, 100, (dir / "b").string());
  EXPECT_EQ(r.flip_flops_annotated, 8);
  for (const auto& u : r.unannotated) EXPECT_NE(u.find("re-encoded"), std::string::npos) << u;
  // Named as re-encoded (fsm_recoded_registers of Yosys's log).
  PowerOptions o;
  o.excluded_registers = {"shift_q"};
  r = netlist_power(kNetlist, kLiberty, "power_fixture", hand_activity(), 100, (dir / "c").string(),
                    o);
  EXPECT_EQ(r.flip_flops_annotated, 8);
  EXPECT_EQ(r.coverage_text().rfind("8 of 12 flip-flops annotated from the simulation (4 at the "
                                    "default 0.1 toggles/cycle)",
                                    0),
            0u)
      << r.coverage_text();
}

TEST(Power, FsmRecodedRegistersAreReadFromYosysLog) {
  const std::string log =
      "28.8.6. Executing FSM_RECODE pass (re-assigning FSM state encoding).\n"
      "Recoding FSM `$fsm$\\u_decoder.u_payload.pay_op_q$5511' from module `\\shade_unit' using "
      "`auto' encoding:\n  mapping auto encoding to `one-hot` for this FSM.\n";
  EXPECT_EQ(fsm_recoded_registers(log), std::vector<std::string>{"u_decoder.u_payload.pay_op_q"});
}

// 10 mW for 1000 cycles at 100 MHz is 100 nJ; over 500 pixels, 200 pJ each.
TEST(Power, EnergyPerPixelIsPowerTimesTheRunsTimeOverItsPixels) {
  EXPECT_DOUBLE_EQ(pj_per_pixel(10, 1000, 100, 500), 200);
  EXPECT_DOUBLE_EQ(pj_per_pixel(10, 1000, 100, 0), 0);
}

TEST(Power, ReadsTheLibertyStatePinsAndTheNetlistsFlipFlops) {
  SHADESIM_NEEDS_POWER_TOOLS();
  const auto cells = read_liberty_cells(kLiberty);
  EXPECT_EQ(cells.at("DFFPOSX1").state_pin, "DS0000");
  EXPECT_EQ(cells.at("DFFSR").state_pin, "P0002");
  EXPECT_EQ(cells.at("DFFSR").state_outputs(), std::vector<std::string>{"Q"});
  EXPECT_FALSE(cells.at("NAND2X1").sequential());
  EXPECT_EQ(cells.at("NAND2X1").direction.at("A"), "input");
  const MappedNetlist n = read_mapped_netlist(kNetlist, "power_fixture");
  EXPECT_EQ(n.instances.size(), 20u);
  EXPECT_EQ(n.inputs, (std::vector<std::string>{"clk_i", "d_i", "rst_ni"}));
  const auto aliases = net_aliases(n);
  EXPECT_EQ(aliases.at("count_q[2]"), (std::vector<std::string>{"count_o[2]", "count_q[2]"}));
  EXPECT_EQ(constant_value("1'h1"), 1);
  EXPECT_EQ(constant_value("1'b0"), 0);
  EXPECT_EQ(constant_value("count_q[1]"), -1);
}

TEST(Power, ReportsAndActivitiesRoundTripThroughJson) {
  SceneActivity a = hand_activity();
  a.scene = "s.json";
  a.unit = "u";
  a.run_cycles = 60;
  a.idle_noise_toggles = 3;
  a.notes = {"n"};
  const SceneActivity b = activity_from_json(activity_to_json(a));
  EXPECT_EQ(b.signals, a.signals);
  EXPECT_EQ(activity_to_json(b), activity_to_json(a));
  PowerReport r;
  r.clock_mhz = 145;
  r.scene.total_mw = 1.5;
  r.flip_flops = 9;
  r.unannotated = {"x (y): z"};
  EXPECT_EQ(power_report_to_json(power_report_from_json(power_report_to_json(r))),
            power_report_to_json(r));
}

// A real unit (sphere's own): the input ports' toggles in the co-simulation's trace equal the
// harness's stimulus replayed through the lockstep block without the RTL, and the cycles traced
// equal the cycles the replay clocked.
TEST(Activity, TheTracedCosimulationsPortTogglesEqualTheHarnessStimulus) {
  const std::string scene = std::string(SHADESIM_SOURCE_DIR) + "/scenes/sphere.json";
  const UnitConfig unit = own_unit(scene).unit;
  const fs::path dir = temp_dir("power", "sphere");
  ActivityOptions o;
  o.work_dir = (dir / "work").string();
  const SceneActivity a = scene_activity(unit, scene, o);
  FrameOptions fo;
  fo.base = unit;
  fo.fixed_unit = true;
  const PreparedFrame f = prepare_frame(scene, fo);
  EXPECT_EQ(a.pixels, f.encoded.stats.pixels);
  const PortStimulus ps = port_stimulus(f.encoded.stream.config, f.encoded.stream);
  EXPECT_EQ(a.cycles, ps.run_cycles);
  EXPECT_GE(ps.run_cycles, a.run_cycles);
  for (const auto& [port, toggles] : ps.ports) {
    ASSERT_TRUE(a.signals.count(port)) << port;
    EXPECT_EQ(a.signals.at(port), toggles) << port;
  }
  EXPECT_EQ(ps.ports.size(), 3u + 64u * static_cast<size_t>(unit.port_words));
  EXPECT_EQ(a.idle_noise_toggles, ps.idle_noise);
}

// sim/engines/unit_power.cpp end to end on sphere's own unit (its osu018 netlist from the build's
// area cache, shared with silicon_table_sphere and config_clock_test): the cycles and pixels it
// divides by are the harness's replay and the model's frame; the clock is the netlist's Fmax;
// pJ/pixel is the definition worked here; and energy per pixel, leakage apart, does not depend on
// the clock: the same run at half the clock gives half the dynamic power and the same dynamic
// energy (a wrong period or a wrong cycle count breaks it). A second call is a cache hit. Needs
// Yosys, OpenSTA and the traced build of the unit (minutes once, cached).
TEST(AreaPower, SpheresEnergyPerPixelEndToEnd) {
  SHADESIM_NEEDS_POWER_TOOLS();
  const std::string scene = std::string(SHADESIM_SOURCE_DIR) + "/scenes/sphere.json";
  const UnitConfig unit = own_unit(scene).unit;
  AreaOptions ao;
  ao.cache_dir = std::string(SHADESIM_BINARY_DIR) + "/area-cache";
  ao.breakdown = false;
  ao.place_and_route = false;
  ao.liberty = LibertyOptions{};
  ao.liberty->liberty_path = kLiberty;
  const AreaReport area = unit_area(unit, ao);
  ASSERT_TRUE(area.liberty);
  const LibertyReport& lib = *area.liberty;
  const fs::path dir = temp_dir("power", "area_power");
  const AreaPower p = scene_power(unit, scene, lib, dir.string(), nullptr);
  EXPECT_FALSE(p.from_cache);
  const PowerReport& r = p.report;

  FrameOptions fo;
  fo.base = unit;
  fo.fixed_unit = true;
  const PreparedFrame f = prepare_frame(scene, fo);
  EXPECT_EQ(r.pixels, f.encoded.stats.pixels);
  EXPECT_EQ(r.cycles, port_stimulus(f.encoded.stream.config, f.encoded.stream).run_cycles);
  EXPECT_EQ(r.clock_mhz, lib.fmax_mhz);
  EXPECT_EQ(static_cast<int64_t>(r.flip_flops), lib.flip_flops);
  // pJ = mW x ns: the run lasts cycles x 1000 / f ns.
  const double run_ns = static_cast<double>(r.cycles) * 1000.0 / lib.fmax_mhz;
  EXPECT_NEAR(r.pj_per_pixel, r.scene.total_mw * run_ns / static_cast<double>(r.pixels),
              1e-9 * r.pj_per_pixel);
  EXPECT_GT(r.scene.total_mw, r.clock_only.total_mw);  // the data toggles on top of the clock

  // Half the clock: the dynamic power halves, the dynamic energy per pixel stays.
  LibertyReport slow = lib;
  slow.fmax_mhz = lib.fmax_mhz / 2;
  const AreaPower half = scene_power(unit, scene, slow, dir.string(), nullptr);
  const double dynamic = r.scene.internal_mw + r.scene.switching_mw;
  EXPECT_NEAR(half.report.scene.internal_mw + half.report.scene.switching_mw, dynamic / 2,
              1e-4 * dynamic);
  EXPECT_NEAR(half.report.scene.leakage_mw, r.scene.leakage_mw, 1e-9 + 1e-6 * r.scene.leakage_mw);

  const AreaPower again = scene_power(unit, scene, lib, dir.string(), nullptr);
  EXPECT_TRUE(again.from_cache);
  EXPECT_DOUBLE_EQ(again.report.pj_per_pixel, r.pj_per_pixel);
  std::ostringstream text;
  print_area_power(text, p);
  char figure[32];
  std::snprintf(figure, sizeof figure, "%.1f pJ/pixel", r.pj_per_pixel);
  EXPECT_NE(text.str().find(figure), std::string::npos) << text.str();
  fs::remove_all(dir);
}

// Not a test: a scene on a mapped netlist by hand (docs/power.md), run with
//   SHADESIM_POWER_UNIT=unit.json SHADESIM_POWER_SCENE=SCENE.json SHADESIM_POWER_NETLIST=n.v
//   [SHADESIM_POWER_MHZ=145] [SHADESIM_POWER_YOSYS_LOG=synth.log] [SHADESIM_POWER_WORK=dir]
//   build/tests/power_test --gtest_also_run_disabled_tests --gtest_filter='*Probe*'
TEST(PowerProbe, DISABLED_SceneOnAMappedNetlist) {
  const auto env = [](const char* name, const std::string& fallback = "") {
    const char* v = std::getenv(name);
    return v ? std::string(v) : fallback;
  };
  const std::string unit = env("SHADESIM_POWER_UNIT"), scene = env("SHADESIM_POWER_SCENE"),
                    netlist = env("SHADESIM_POWER_NETLIST");
  ASSERT_FALSE(unit.empty() || scene.empty() || netlist.empty())
      << "set SHADESIM_POWER_UNIT, SHADESIM_POWER_SCENE and SHADESIM_POWER_NETLIST";
  const fs::path work = env("SHADESIM_POWER_WORK", temp_dir("power", "probe").string());
  ActivityOptions ao;
  ao.work_dir = (work / "activity").string();
  const SceneActivity a = scene_activity(load_unit_config(unit), scene, ao);
  std::ofstream(work / "activity.json") << activity_to_json(a) << '\n';
  PowerOptions po;
  const std::string log = env("SHADESIM_POWER_YOSYS_LOG");
  if (!log.empty()) {
    std::ifstream is(log);
    po.excluded_registers =
        fsm_recoded_registers(std::string(std::istreambuf_iterator<char>(is), {}));
  }
  const double mhz = std::stod(env("SHADESIM_POWER_MHZ", "145"));
  const PowerReport r =
      netlist_power(netlist, kLiberty, "shade_unit", a, mhz, (work / "power").string(), po);
  std::ofstream(work / "power.json") << power_report_to_json(r) << '\n';
  std::printf("cycles %llu (frame %llu), pixels %llu; idle-noise toggles %llu\n",
              static_cast<unsigned long long>(a.cycles),
              static_cast<unsigned long long>(a.run_cycles),
              static_cast<unsigned long long>(a.pixels),
              static_cast<unsigned long long>(a.idle_noise_toggles));
  std::printf("%s\n", r.coverage_text().c_str());
  std::printf(
      "scene activity  %.3f mW (internal %.3f, switching %.3f, leakage %.6f) at %.1f MHz, "
      "%.2f pJ/pixel\n",
      r.scene.total_mw, r.scene.internal_mw, r.scene.switching_mw, r.scene.leakage_mw, mhz,
      r.pj_per_pixel);
  std::printf("global %.2f      %.3f mW (internal %.3f, switching %.3f), %.2f pJ/pixel\n",
              r.default_activity_value, r.default_activity.total_mw, r.default_activity.internal_mw,
              r.default_activity.switching_mw, r.default_pj_per_pixel);
  std::printf("clock only      %.3f mW (internal %.3f, switching %.3f)\n", r.clock_only.total_mw,
              r.clock_only.internal_mw, r.clock_only.switching_mw);
  for (const auto& u : r.unannotated) std::printf("  unannotated %s\n", u.c_str());
  std::printf("work folder %s\n", work.c_str());
}

}  // namespace
}  // namespace shadesim
