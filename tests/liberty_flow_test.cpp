// The liberty flow of shadesim area (sim/eda/sta/liberty_flow.h) and its parts:
//   - the Liberty reader and function evaluator on a small library written here (areas, pins,
//     clocks, flip-flop groups; truth tables worked out by hand);
//   - fanout buffering (sim/eda/sta/fanout_buffer.h) on netlists built here: a 20-sink net becomes
//   a
//     tree, every sink still reaches the driver, no net drives more than the limit, a clock net and
//     an output port stay where they were;
//   - the OpenSTA report reader on a saved report (tests/data/liberty/sta_report_sphere.txt, the
//     figures read off the text by eye);
//   - end to end on a tiny module (two 4-bit registers into an adder into a 5-bit register) with
//     osu018 and OpenSTA: its area against Yosys's own `stat -liberty` of the flow's netlist, its
//     flip-flops by construction, its Fmax against this test's own OpenSTA run of the netlist;
//   - errors: a missing default library names its Debian package, a missing --liberty file and
//     a missing sta name themselves.
#include "sim/eda/sta/liberty_flow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "sim/eda/sta/fanout_buffer.h"
#include "sim/eda/sta/liberty.h"
#include "sim/eda/sta/sta_report.h"
#include "tests/support/cli_run.h"
#include "tests/support/eda_tools.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

void write(const fs::path& p, const std::string& text) {
  std::ofstream os(p);
  os << text;
}

std::string read(const fs::path& p) {
  std::ifstream is(p);
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

// The program's path on PATH, "" when it is not there.
std::string which(const std::string& program) {
  const Result r = run_shell("command -v " + program);
  return r.status == 0 ? r.output.substr(0, r.output.find('\n')) : "";
}

// A small library: two buffers (BUFA drives 1.0 pF from 0.01 pF of input, gain 100; BUFB 1.5 pF
// from 0.02, gain 75, and larger), a NAND2 in Liberty's juxtaposition syntax, an AOI21, a plain
// flip-flop and one with a reset. Comments, a line continuation and a group the reader skips
// (timing) are in it on purpose.
const char* kTinyLib = R"lib(/* a test library */
library (tiny_lib) {
  time_unit : "1ns";
  capacitive_load_unit (1, pf);
  cell (BUFA) {
    area : 10;
    pin (A) { direction : input; capacitance : 0.01; }
    pin (Y) { direction : output; max_capacitance : 1.0; function : "A";
      timing () { related_pin : "A"; cell_rise (t) { values ("1, 2", \
        "3, 4"); } } }
  }
  cell (BUFB) {
    area : 20;
    pin (A) { direction : input; capacitance : 0.02; }
    pin (Y) { direction : output; max_capacitance : 1.5; function : "A"; }
  }
  cell (NAND2) {
    area : 8;
    pin (A) { direction : input; capacitance : 0.01; }
    pin (B) { direction : input; capacitance : 0.01; }
    pin (Y) { direction : output; function : "(!(A B))"; }
  }
  cell (AOI21) {
    area : 12;
    pin (A, B, C) { direction : input; capacitance : 0.01; }
    pin (Y) { direction : output; function : "!((A*B)|C)"; }
  }
  cell (DFF) {
    area : 40;
    ff (IQ, IQN) { next_state : "D"; clocked_on : "CLK"; }
    pin (CLK) { direction : input; clock : true; capacitance : 0.01; }
    pin (D) { direction : input; capacitance : 0.01; }
    pin (Q) { direction : output; function : "IQ"; }
  }
  cell (DFFR) {
    area : 50;
    ff (P1, P2) { next_state : "D"; clocked_on : "CLK"; clear : "(!R)"; }
    pin (CLK) { direction : input; clock : true; }
    pin (D) { direction : input; }
    pin (R) { direction : input; }
    pin (Q) { direction : output; function : "P1"; }
  }
}
)lib";

LibertyLibrary tiny_library(const fs::path& dir) {
  write(dir / "tiny.lib", kTinyLib);
  return read_liberty((dir / "tiny.lib").string());
}

TEST(Liberty, ReadsCellsPinsAndStateGroups) {
  const auto dir = temp_dir("liberty", "read");
  const LibertyLibrary lib = tiny_library(dir);
  EXPECT_EQ(lib.name, "tiny_lib");
  EXPECT_EQ(lib.cells.size(), 6u);
  EXPECT_EQ(lib.cell("NAND2").area, 8);
  EXPECT_EQ(lib.cell("AOI21").inputs().size(), 3u);  // pin (A, B, C)
  EXPECT_TRUE(lib.cell("DFF").sequential);
  EXPECT_TRUE(lib.cell("DFF").pin("CLK")->clock);
  EXPECT_FALSE(lib.cell("DFF").pin("D")->clock);
  EXPECT_EQ(lib.cell("DFF").state_vars, (std::vector<std::string>{"IQ", "IQN"}));
  EXPECT_EQ(lib.cell("BUFA").pin("Y")->max_capacitance, 1.0);
  EXPECT_FALSE(lib.cell("BUFA").sequential);
  // The cells the flow picks by what they compute: the buffer with the best gain (BUFA, 100
  // against BUFB's 75), the NAND2, and the flip-flop without a reset.
  EXPECT_EQ(strongest_buffer(lib).name, "BUFA");
  EXPECT_EQ(nand2_cell(lib).name, "NAND2");
  const PlainFlipFlop ff = plain_flip_flop(lib);
  ASSERT_NE(ff.cell, nullptr);
  EXPECT_EQ(ff.cell->name, "DFF");
  EXPECT_EQ(ff.d, "D");
  EXPECT_EQ(ff.clock, "CLK");
  EXPECT_EQ(ff.q, "Q");
  EXPECT_THROW(lib.cell("XOR9"), std::runtime_error);
  fs::remove_all(dir);
}

TEST(Liberty, FunctionsFollowLibertysOperators) {
  const auto f = [](const std::string& fn, bool a, bool b, bool c) {
    return eval_liberty_function(fn, {{"A", a}, {"B", b}, {"C", c}});
  };
  for (int v = 0; v < 8; ++v) {
    const bool a = v & 1, b = v & 2, c = v & 4;
    EXPECT_EQ(f("(!((A B)+C))", a, b, c), !((a && b) || c)) << v;
    EXPECT_EQ(f("A' | B & C", a, b, c), !a || (b && c)) << v;  // AND binds tighter than OR
    EXPECT_EQ(f("A ^ B C", a, b, c), (a != b) && c) << v;      // XOR tighter than AND
    EXPECT_EQ(f("!A*!B + 1 & C", a, b, c), (!a && !b) || c) << v;
  }
  EXPECT_THROW(eval_liberty_function("(A B", {{"A", true}, {"B", true}}), std::invalid_argument);
  EXPECT_THROW(eval_liberty_function("A Z", {{"A", true}}), std::invalid_argument);
}

TEST(Liberty, ErrorsNameTheFileAndLine) {
  const auto dir = temp_dir("liberty", "errors");
  write(dir / "broken.lib", "library (x) {\n  cell (A) {\n    area : 1;\n");
  try {
    read_liberty((dir / "broken.lib").string());
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "broken.lib").string() + ":"), std::string::npos)
        << e.what();
  }
  write(dir / "empty.lib", "library (x) { time_unit : \"1ns\"; }\n");
  EXPECT_THROW(read_liberty((dir / "empty.lib").string()), std::runtime_error);
  EXPECT_THROW(read_liberty((dir / "none.lib").string()), std::runtime_error);
  fs::remove_all(dir);
}

// ---- fanout buffering ------------------------------------------------------------------------

// A Yosys-JSON module: input port `a` (bit 2) and clk (bit 3); `n_and` NAND2 cells with A on a,
// B on their own input bits, Y on their own nets; `n_ff` DFFs clocked by clk; output port `y`
// on bit 2 too (an output port on the fanout net).
Json fanout_netlist(int n_and, int n_ff) {
  Json m = {
      {"ports",
       {{"a", {{"direction", "input"}, {"bits", {2}}}},
        {"clk", {{"direction", "input"}, {"bits", {3}}}},
        {"y", {{"direction", "output"}, {"bits", {2}}}}}},
      {"cells", Json::object()},
      {"netnames",
       {{"a", {{"hide_name", 0}, {"bits", {2}}}}, {"clk", {{"hide_name", 0}, {"bits", {3}}}}}}};
  int bit = 10;
  for (int i = 0; i < n_and; ++i, bit += 2) {
    m["cells"]["g" + std::to_string(i)] = {
        {"type", "NAND2"}, {"connections", {{"A", {2}}, {"B", {bit}}, {"Y", {bit + 1}}}}};
  }
  for (int i = 0; i < n_ff; ++i, bit += 2) {
    m["cells"]["f" + std::to_string(i)] = {
        {"type", "DFF"}, {"connections", {{"CLK", {3}}, {"D", {bit}}, {"Q", {bit + 1}}}}};
  }
  return {{"modules", {{"top", m}}}};
}

// bit -> the cells' input pins on it, and bit -> the buffer driving it (its input bit).
struct Loads {
  std::map<int64_t, int> pins;
  std::map<int64_t, int64_t> buffered_from;
};

Loads loads_of(const Json& m) {
  Loads l;
  for (const auto& [name, c] : m.at("cells").items()) {
    for (const auto& [port, bits] : c.at("connections").items()) {
      const bool output = port == "Y" || port == "Q";
      if (!output) l.pins[bits[0].get<int64_t>()]++;
      if (c.at("type") == "BUFA" && output)
        l.buffered_from[bits[0].get<int64_t>()] = c.at("connections").at("A")[0].get<int64_t>();
    }
  }
  return l;
}

TEST(FanoutBuffer, ANetOfTwentySinksBecomesATreeOfAtMostEight) {
  const auto dir = temp_dir("liberty", "fanout");
  const LibertyLibrary lib = tiny_library(dir);
  Json doc = fanout_netlist(20, 20);
  const FanoutBufferResult r = buffer_fanout(doc, "top", lib, 8, "test");
  // 20 sinks: ceil(20 / 8) = 3 buffers (7, 7, 6 sinks), which the driver drives directly.
  EXPECT_EQ(r.buffer_cell, "BUFA");
  EXPECT_EQ(r.buffers, 3);
  EXPECT_EQ(r.nets_buffered, 1);
  EXPECT_EQ(r.largest_fanout, 20);
  EXPECT_EQ(r.clock_nets_skipped, 1);  // clk's 20 DFF clock pins stay
  const Json& m = doc["modules"]["top"];
  const Loads l = loads_of(m);
  for (const auto& [bit, n] : l.pins) {
    if (bit != 3) EXPECT_LE(n, 8) << "bit " << bit;
  }
  EXPECT_EQ(l.pins.at(3), 20);
  EXPECT_EQ(l.pins.at(2), 3);  // the driver: three buffers
  // Every NAND's A reaches bit 2 through buffers; the output port is still on bit 2.
  for (int i = 0; i < 20; ++i) {
    int64_t b = m["cells"]["g" + std::to_string(i)]["connections"]["A"][0];
    for (int hops = 0; b != 2 && hops < 10; ++hops) b = l.buffered_from.at(b);
    EXPECT_EQ(b, 2) << "g" << i;
  }
  EXPECT_EQ(m["ports"]["y"]["bits"][0], 2);
  fs::remove_all(dir);
}

TEST(FanoutBuffer, AHundredSinksTakeTwoLevelsAndSmallNetsStay) {
  const auto dir = temp_dir("liberty", "fanout2");
  const LibertyLibrary lib = tiny_library(dir);
  Json doc = fanout_netlist(100, 0);
  const FanoutBufferResult r = buffer_fanout(doc, "top", lib, 8, "test");
  // 100 -> 13 buffers of 7 or 8 sinks -> 2 buffers of 6 and 7 -> the driver: 15 buffers.
  EXPECT_EQ(r.buffers, 15);
  const Loads l = loads_of(doc["modules"]["top"]);
  for (const auto& [bit, n] : l.pins) EXPECT_LE(n, 8) << "bit " << bit;
  EXPECT_EQ(l.pins.at(2), 2);
  int depth = 0;
  for (int64_t b = doc["modules"]["top"]["cells"]["g99"]["connections"]["A"][0]; b != 2; ++depth)
    b = l.buffered_from.at(b);
  EXPECT_EQ(depth, 2);

  Json small = fanout_netlist(8, 0);
  EXPECT_EQ(buffer_fanout(small, "top", lib, 8, "test").buffers, 0);
  EXPECT_THROW(buffer_fanout(small, "top", lib, 1, "test"), std::invalid_argument);
  Json unknown = fanout_netlist(2, 0);
  unknown["modules"]["top"]["cells"]["g0"]["type"] = "MYSTERY";
  try {
    buffer_fanout(unknown, "top", lib, 8, "net.json");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("net.json: cell type MYSTERY"), std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

// ---- OpenSTA's report ------------------------------------------------------------------------

TEST(StaReport, ASavedReportGivesItsPathsAndTheWorstSlack) {
  const std::string path =
      std::string(SHADESIM_SOURCE_DIR) + "/tests/data/liberty/sta_report_sphere.txt";
  const std::string text = read(path);
  const std::vector<StaPath> paths = parse_sta_paths(text, path);
  ASSERT_EQ(paths.size(), 2u);
  // The reset's recovery path: rst_ni, one buffer, the DFFSR's S pin.
  EXPECT_EQ(paths[0].startpoint, "rst_ni");
  EXPECT_EQ(paths[0].group, "**async_default**");
  EXPECT_EQ(paths[0].stages.size(), 3u);
  EXPECT_DOUBLE_EQ(paths[0].slack_ns, 3.829);
  EXPECT_DOUBLE_EQ(paths[0].setup_ns, 0.012);
  // The clock group's path, the worst: 38 pin rows from _2791_/CLK to _2801_/D.
  const StaPath& w = worst_path(paths);
  EXPECT_EQ(&w, &paths[1]);
  EXPECT_EQ(w.startpoint, "_2791_");
  EXPECT_EQ(w.endpoint, "_2801_");
  EXPECT_EQ(w.group, "clk");
  EXPECT_DOUBLE_EQ(w.slack_ns, -0.984);
  EXPECT_DOUBLE_EQ(w.arrival_ns, 4.889);
  EXPECT_DOUBLE_EQ(w.required_ns, 3.905);
  EXPECT_DOUBLE_EQ(w.setup_ns, 0.095);
  ASSERT_EQ(w.stages.size(), 38u);
  EXPECT_EQ(w.stages[1].instance, "_2791_");
  EXPECT_EQ(w.stages[1].pin, "Q");
  EXPECT_EQ(w.stages[1].cell, "DFFSR");
  EXPECT_DOUBLE_EQ(w.stages[1].delay_ns, 0.325);
  EXPECT_EQ(w.stages[1].net, "u_decoder.u_payload.pay_rem_q[5]");
  EXPECT_EQ(w.stages[1].fanout, 4);
  EXPECT_EQ(w.stages[2].edge, 'v');
  EXPECT_EQ(w.stages.back().instance, "_2801_");
  EXPECT_EQ(w.stages.back().pin, "D");
  EXPECT_EQ(parse_worst_slack(text), -0.984);
  EXPECT_THROW(parse_sta_paths("nothing\n", "x.out"), std::runtime_error);
  EXPECT_THROW(parse_sta_paths(text.substr(0, text.find("slack (MET)")), "cut.out"),
               std::runtime_error);
}

// ---- end to end --------------------------------------------------------------------------------

// Two 4-bit registers into an adder into a 5-bit register: 13 flip-flops; the critical path runs
// from a_q or b_q to s_q through the carry chain.
const char* kTinyUnit = R"(module shade_unit (input logic clk_i, input logic [3:0] a_i, b_i,
                   output logic [4:0] s_o);
  logic [3:0] a_q, b_q;
  logic [4:0] s_q;
  always_ff @(posedge clk_i) begin
    a_q <= a_i;
    b_q <= b_i;
    s_q <= a_q + b_q;
  end
  assign s_o = s_q;
endmodule
)";

TEST(LibertyFlow, ATinyAdderMatchesYosysAreaAndItsOwnTiming) {
  SHADESIM_NEEDS_TOOLS(
      !which("yosys").empty() && !which("sta").empty() && fs::exists(kDefaultLiberty),
      "yosys, sta or " << kDefaultLiberty
                       << " (Debian packages yosys, opensta, qflow-tech-osu018)");
  const auto dir = temp_dir("liberty", "e2e");
  write(dir / "tiny.sv", kTinyUnit);
  FlowInputs in;
  in.yosys = which("yosys");
  in.files = {dir / "tiny.sv"};
  in.yosys_version = "test";
  const LibertyRun run = prepare_liberty_run(in, LibertyOptions{});
  fs::create_directories(dir / "work");
  const LibertyReport r = run_liberty_flow(run, dir / "work", (dir / "cache").string());
  EXPECT_EQ(r.library, "osu018_stdcells");
  EXPECT_EQ(r.flip_flops, 13);
  EXPECT_TRUE(fs::exists(r.netlist_path));

  // Area: Yosys's own sum of the liberty's cell areas over the flow's netlist.
  const Result stat =
      run_shell(in.yosys + " -q -p 'read_liberty -lib " + kDefaultLiberty + "; read_verilog " +
                r.netlist_path + "; tee -o " + (dir / "stat.txt").string() + " stat -liberty " +
                kDefaultLiberty + "'");
  ASSERT_EQ(stat.status, 0) << stat.output;
  std::smatch m;
  const std::string stat_text = read(dir / "stat.txt");
  ASSERT_TRUE(std::regex_search(stat_text, m, std::regex(R"(Chip area for module .*: ([0-9.]+))")));
  EXPECT_NEAR(r.area_um2, std::stod(m[1].str()), 1e-6);
  // NAND2X1's area, from the liberty's text.
  const std::string lib_text = read(kDefaultLiberty);
  ASSERT_TRUE(
      std::regex_search(lib_text, m, std::regex(R"(cell \(NAND2X1\) \{\s*area : ([0-9.]+))")));
  EXPECT_EQ(r.nand2_area_um2, std::stod(m[1].str()));

  // Timing: this test's own OpenSTA run on the netlist, its worst register-to-register path's
  // arrival + setup (the ports unconstrained: their paths are a wire in and clock-to-Q out,
  // shorter than the adder).
  write(dir / "check.tcl", std::string("read_liberty ") + kDefaultLiberty + "\nread_verilog " +
                               r.netlist_path + "\nlink_design shade_unit\n" +
                               "create_clock -period 4 [get_ports clk_i]\n" +
                               "report_checks -path_delay max -digits 3\n");
  const Result sta = run_shell("sta -no_splash -exit " + (dir / "check.tcl").string());
  ASSERT_EQ(sta.status, 0) << sta.output;
  ASSERT_TRUE(std::regex_search(sta.output, m, std::regex(R"(([0-9.]+)\s+data arrival time)")));
  const double arrival = std::stod(m[1].str());
  ASSERT_TRUE(
      std::regex_search(sta.output, m, std::regex(R"(-([0-9.]+)\s+[0-9.]+\s+library setup time)")));
  const double setup = std::stod(m[1].str());
  // The flow's clock carries docs/area.md's 0.2 ns setup uncertainty; this run's clock none.
  EXPECT_NEAR(r.fmax_mhz, 1000.0 / (arrival + setup + 0.2), 0.01 * r.fmax_mhz);
  EXPECT_NEAR(r.path_arrival_ns, arrival, 0.0015);
  EXPECT_NE(r.path_from.find("_q["), std::string::npos) << r.path_from;  // a_q or b_q
  // The endpoint: the sum register, named by its Q net (Yosys keeps the output port's name for it).
  EXPECT_TRUE(r.path_to.rfind("s_q[", 0) == 0 || r.path_to.rfind("s_o[", 0) == 0) << r.path_to;
  double sum = 0;
  for (const auto& c : r.path) sum += c.delay_ns;
  EXPECT_NEAR(sum, r.path_arrival_ns, 0.001 * r.path.size() + 1e-9);
  EXPECT_GE(r.path.size(), 3u);  // the flip-flop, some of the adder, the endpoint

  // A second run is answered by the cache.
  const std::optional<LibertyReport> again = cached_liberty(run, (dir / "cache").string());
  ASSERT_TRUE(again);
  EXPECT_TRUE(again->from_cache);
  EXPECT_EQ(again->area_um2, r.area_um2);
  EXPECT_EQ(again->path_to, r.path_to);
  fs::remove_all(dir);
}

// ---- errors ------------------------------------------------------------------------------------

TEST(LibertyFlow, AMissingLibraryOrToolIsNamed) {
  try {
    resolve_liberty("", "/nonexistent/osu018_stdcells.lib");
    ADD_FAILURE() << "no error";
  } catch (const MissingToolError& e) {
    EXPECT_NE(std::string(e.what()).find("qflow-tech-osu018"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/nonexistent/osu018_stdcells.lib"), std::string::npos);
  }
  try {
    resolve_liberty("/nonexistent/foundry.lib");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/foundry.lib"), std::string::npos);
  }
  const auto dir = temp_dir("liberty", "missing");
  write(dir / "tiny.lib", kTinyLib);
  LibertyOptions o;
  o.liberty_path = (dir / "tiny.lib").string();
  o.sta = "/nonexistent/sta";
  try {
    prepare_liberty_run(FlowInputs{}, o);
    ADD_FAILURE() << "no error";
  } catch (const MissingToolError& e) {
    EXPECT_NE(std::string(e.what()).find("opensta"), std::string::npos) << e.what();
  }
  // From the command line: a --liberty file that does not exist is a usage error naming it.
  const std::string scene = std::string(SHADESIM_SOURCE_DIR) + "/scenes/sphere.json";
  const Result cli = run("area " + scene + " --liberty /nonexistent/foundry.lib");
  EXPECT_EQ(cli.status, 2) << cli.output;
  EXPECT_NE(cli.output.find("/nonexistent/foundry.lib"), std::string::npos) << cli.output;
  const Result both =
      run("area " + scene + " --liberty " + (dir / "tiny.lib").string() + " --no-liberty");
  EXPECT_EQ(both.status, 2) << both.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shadesim
