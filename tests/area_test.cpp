// shadesim area against Yosys itself: the cell count of a small unit equals that of a Yosys run
// this test writes by hand (its own parameter list and script, not the code under test); the
// cache answers a repeated run without Yosys and misses on a changed parameter; bad input and
// a missing tool give clear errors. Small units (1 channel, 1 light, narrow widths) and no
// place and route keep it quick.
// Gate equivalents (sim/engines/area_report.h): against closed forms on tiny modules (NAND2 = 4
// transistors; Yosys 0.23's CMOS costs (its cost.h): NOT 2, NAND/NOR 4, AND/OR 6, XOR/XNOR/MUX 12,
// a plain flip-flop 16, other flip-flops nothing; every flip-flop 6 GE), shadesim area's GE against
// the same formula applied by this test to a direct Yosys stat, and a LUT unit's table RAM bits
// against 2^A x B. The tools' script files: read without their comment lines, filled in, and a
// missing one named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "sim/eda/common/build_paths.h"
#include "sim/eda/common/rtl_files.h"
#include "sim/eda/common/tool_script.h"
#include "sim/engines/area_report.h"
#include "tests/support/cli_run.h"
#include "tests/support/eda_tools.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

std::string shadesim(const std::string& env = "") {
  return env + (env.empty() ? "" : " ") + std::string(SHADESIM_BINARY_DIR) + "/shadesim ";
}

fs::path temp_dir(const std::string& name) { return shadesim::temp_dir("area", name); }

void write(const fs::path& p, const std::string& text) {
  std::ofstream os(p);
  os << text;
}

std::string find_yosys() {
  const Result r = run_shell("command -v yosys");
  std::string path = r.output.substr(0, r.output.find('\n'));
  return r.status == 0 ? path : "";
}

// A small unit: grey, one light, narrow widths, no specular hardware.
const char* kSmallConfig =
    R"({"channels":1,"lights":1,"xy_bits":4,"coef":"s2.6:rnd:wrap","series":"s2.6:trn:wrap",)"
    R"("spec_colour":"u1.3:rnd:sat","out_bits":4,"specular":{"kind":"ideal","out":"u1.3:sat"}})";
// The same unit as shade_unit parameters, written out by hand from rtl/shade_unit.sv's header:
// WL = integer + fraction bits, QUANT 0 truncate, OVERFLOW 1 wrap, SPECULAR_KIND 0 ideal.
const char* kSmallChparam =
    "-set CHANNELS 1 -set LIGHTS 1 -set XY_BITS 4 -set COEF_WL 8 -set COEF_IWL 2 "
    "-set SERIES_WL 8 -set SERIES_IWL 2 -set SERIES_QUANT 0 -set SERIES_OVERFLOW 1 "
    "-set SPEC_COLOUR_WL 4 -set SPEC_COLOUR_IWL 1 -set OUT_BITS 4 -set SPECULAR_KIND 0 "
    "-set SPECULAR_OUT_WL 4 -set SPECULAR_OUT_IWL 1";

TEST(Area, CellCountEqualsADirectYosysRunAndTheCacheIsReused) {
  const std::string yosys = find_yosys();
  SHADESIM_NEEDS_TOOLS(!yosys.empty(), "yosys (Debian package yosys)");
  const auto dir = temp_dir("direct");
  write(dir / "small.json", kSmallConfig);

  // The direct run: rtl/files.f's sources, the chparam list above, synth -flatten and the gate
  // mapping. ABC's result depends on the netlist's order, so read the files in the list's order
  // (sim/engines/area_report.h).
  std::vector<std::string> sources;
  for (const auto& f : rtl_file_list(std::string(SHADESIM_SOURCE_DIR) + "/rtl"))
    sources.push_back(f.string());
  std::string files;
  for (const auto& f : sources) files += " " + f;
  write(dir / "direct.ys", "read_verilog -sv" + files + "\nchparam " + kSmallChparam +
                               " shade_unit\nsynth -flatten -top shade_unit\n"
                               "abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX\nopt_clean\n"
                               "tee -o " +
                               (dir / "direct_stat.txt").string() + " stat -tech cmos\n");
  auto direct = std::async(std::launch::async, [&] {
    return run_shell(yosys + " -q -l " + (dir / "direct.log").string() + " " +
                     (dir / "direct.ys").string());
  });
  const std::string cache = (dir / "cache").string();
  const Result area =
      run_shell(shadesim() + "area --config " + (dir / "small.json").string() +
                " --no-pnr --cache " + cache + " --json " + (dir / "area.json").string());
  const Result yr = direct.get();
  ASSERT_EQ(yr.status, 0) << yr.output;
  ASSERT_EQ(area.status, 0) << area.output;

  std::ifstream stat(dir / "direct_stat.txt");
  std::stringstream ss;
  ss << stat.rdbuf();
  std::smatch m;
  const std::string stat_text = ss.str();
  ASSERT_TRUE(std::regex_search(stat_text, m, std::regex(R"(Number of cells:\s+([0-9]+))")))
      << stat_text;
  const long direct_cells = std::stol(m[1].str());

  std::ifstream js(dir / "area.json");
  const auto j = nlohmann::json::parse(js);
  EXPECT_EQ(j["cells"].get<long>(), direct_cells);
  EXPECT_FALSE(j["from_cache"].get<bool>());
  // The breakdown rows add up to their own synthesis, which cannot beat the flat one.
  long rows = 0;
  for (const auto& row : j["modules"]) rows += row["cells"].get<long>();
  EXPECT_EQ(rows, j["breakdown_cells"].get<long>());
  EXPECT_GE(rows, direct_cells);
  EXPECT_GT(j["ice40"]["lut4"].get<long>(), 0);
  EXPECT_NE(area.output.find("span_setup"), std::string::npos) << area.output;

  // GE by the stated convention, computed here from the direct run's stat: transistors less
  // 16 per $_DFF_P_ / $_DFF_N_ (the only flip-flops Yosys's CMOS table costs), / 4, plus 6 per
  // flip-flop; no table RAM in an ideal unit.
  ASSERT_TRUE(
      std::regex_search(stat_text, m, std::regex(R"(Estimated number of transistors:\s+([0-9]+))")))
      << stat_text;
  const long transistors = std::stol(m[1].str());
  long ffs = 0, plain = 0;
  const std::regex ff_line(R"(\s(\$_[A-Z0-9_]*DFF[A-Z0-9_]*)\s+([0-9]+))");
  for (auto it = std::sregex_iterator(stat_text.begin(), stat_text.end(), ff_line);
       it != std::sregex_iterator(); ++it) {
    ffs += std::stol((*it)[2].str());
    if ((*it)[1].str() == "$_DFF_P_" || (*it)[1].str() == "$_DFF_N_")
      plain += std::stol((*it)[2].str());
  }
  const long logic = transistors - 16 * plain;
  EXPECT_EQ(j["flip_flops"].get<long>(), ffs);
  EXPECT_EQ(j["logic_transistors"].get<long>(), logic);
  EXPECT_EQ(j["ram_bits"].get<long>(), 0);
  EXPECT_EQ(j["gate_equivalents"].get<long>(), std::lround(logic / 4.0) + 6 * ffs);
  long module_ge = 0;
  for (const auto& row : j["modules"]) module_ge += row["gate_equivalents"].get<long>();
  EXPECT_GE(module_ge, j["gate_equivalents"].get<long>());  // kept hierarchy: at least flat
  EXPECT_NE(area.output.find("GE"), std::string::npos) << area.output;
  // The library mapping runs by default where osu018 and OpenSTA are installed. Its JSON states
  // the constraints it timed under (docs/area.md): the load is 4 of DFFPOSX1's D pins, read here
  // from the liberty's text; OpenSTA's own timing is checked against the liberty's tables in
  // sta_constraints_test.
  const bool liberty = fs::exists(kDefaultLiberty) && run_shell("command -v sta").status == 0;
  if (liberty) {
    ASSERT_TRUE(j.contains("liberty")) << j.dump();
    const auto& l = j["liberty"];
    EXPECT_EQ(l["library"], "osu018_stdcells");
    const auto& c = l["constraints"];
    std::ifstream lib_file(kDefaultLiberty);
    const std::string lib_text((std::istreambuf_iterator<char>(lib_file)), {});
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        lib_text, m,
        std::regex(
            R"(cell \(DFFPOSX1\)[^]*?pin\(D\)\s*\{\s*direction : input;\s*capacitance : ([0-9.]+))")));
    EXPECT_NEAR(c["output_load_pf"].get<double>(), 4 * std::stod(m[1].str()), 1e-12) << c.dump();
    EXPECT_EQ(c["input_driving_cell"], "BUFX2");
    EXPECT_EQ(c["clock_uncertainty_ns"].get<double>(), 0.2);
    EXPECT_EQ(c["guard_band"].get<double>(), 0.05);
    EXPECT_GT(c["input_delay_ns"].get<double>(), 0);   // DFFPOSX1's clock-to-Q
    EXPECT_GT(c["output_delay_ns"].get<double>(), 0);  // its setup
    EXPECT_NE(area.output.find("constraints  clock uncertainty 0.2 ns"), std::string::npos)
        << area.output;
    EXPECT_GT(l["area_um2"].get<double>(), 0);
    EXPECT_TRUE(l["mpixel_per_s"].is_null());  // no scene: no cycles per pixel
    EXPECT_NE(area.output.find("osu018 0.18 um"), std::string::npos) << area.output;
  }

  // A stand-in yosys that reports the real version (the key includes it) and fails on any
  // synthesis: a cache hit must not need it, a miss must.
  const fs::path fake = dir / "fakebin";
  fs::create_directories(fake);
  write(fake / "yosys", "#!/bin/sh\nif [ \"$1\" = -V ]; then exec " + yosys +
                            " -V; fi\necho 'fake yosys: synthesis requested' >&2\nexit 3\n");
  fs::permissions(fake / "yosys", fs::perms::owner_all);
  const std::string env = "PATH=" + fake.string() + ":\"$PATH\"";
  const Result again =
      run_shell(shadesim(env) + "area --config " + (dir / "small.json").string() +
                " --no-pnr --cache " + cache + " --json " + (dir / "again.json").string());
  ASSERT_EQ(again.status, 0) << again.output;
  std::ifstream js2(dir / "again.json");
  const auto j2 = nlohmann::json::parse(js2);
  EXPECT_TRUE(j2["from_cache"].get<bool>());
  if (liberty) {
    EXPECT_TRUE(j2["liberty"]["from_cache"].get<bool>());
  }
  EXPECT_EQ(j2["cells"].get<long>(), direct_cells);
  EXPECT_NE(again.output.find("cache hit"), std::string::npos) << again.output;

  std::string changed = kSmallConfig;
  changed.replace(changed.find("\"out_bits\":4"), 12, "\"out_bits\":3");
  write(dir / "changed.json", changed);
  const Result miss = run_shell(shadesim(env) + "area --config " + (dir / "changed.json").string() +
                                " --no-pnr --cache " + cache);
  EXPECT_NE(miss.status, 0) << miss.output;
  EXPECT_NE(miss.output.find("failed"), std::string::npos) << miss.output;
  EXPECT_EQ(miss.output.find("cache hit"), std::string::npos) << miss.output;
  fs::remove_all(dir);
}

// Yosys's flat flow (the one shadesim area uses) on a tiny module; its stat -json -tech cmos.
CmosStat tiny(const std::string& yosys, const fs::path& dir, const std::string& name,
              const std::string& verilog) {
  write(dir / (name + ".v"), verilog);
  const Result r = run_shell(yosys + " -q -p 'read_verilog " + (dir / (name + ".v")).string() +
                             "; synth -flatten -top " + name +
                             "; abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX; opt_clean; tee -q -o " +
                             (dir / (name + ".json")).string() + " stat -json -tech cmos'");
  EXPECT_EQ(r.status, 0) << r.output;
  return read_cmos_stat((dir / (name + ".json")).string(), name);
}

TEST(Area, GateEquivalentsFollowTheClosedFormOnTinyModules) {
  const std::string yosys = find_yosys();
  SHADESIM_NEEDS_TOOLS(!yosys.empty(), "yosys (Debian package yosys)");
  const auto dir = temp_dir("tiny");
  // A 4-bit register: 4 flip-flops, no logic: 24 GE (Yosys charges $_DFF_P_ 16 transistors,
  // which GE takes off: a flip-flop is 6 GE whatever its type).
  const CmosStat reg = tiny(yosys, dir, "reg4",
                            "module reg4(input clk, input [3:0] d, output reg [3:0] q);\n"
                            "  always @(posedge clk) q <= d;\nendmodule\n");
  EXPECT_EQ(reg.flip_flops, 4);
  EXPECT_EQ(reg.transistors, 4 * 16);
  EXPECT_EQ(reg.logic_transistors, 0);
  EXPECT_EQ(gate_equivalents(reg.logic_transistors, reg.flip_flops, 0), 24);
  // The same with an enable ($_DFFE_PP_, which Yosys does not cost): still 24 GE.
  const CmosStat en = tiny(yosys, dir, "reg4en",
                           "module reg4en(input clk, en, input [3:0] d, output reg [3:0] q);\n"
                           "  always @(posedge clk) if (en) q <= d;\nendmodule\n");
  EXPECT_EQ(en.flip_flops, 4);
  EXPECT_EQ(en.logic_transistors, 0);
  EXPECT_EQ(gate_equivalents(en.logic_transistors, en.flip_flops, 0), 24);
  // Four XORs into the register: 4 x 12 transistors = 12 GE, + 24.
  const CmosStat x = tiny(yosys, dir, "xreg4",
                          "module xreg4(input clk, input [3:0] a, b, output reg [3:0] q);\n"
                          "  always @(posedge clk) q <= a ^ b;\nendmodule\n");
  EXPECT_EQ(x.flip_flops, 4);
  EXPECT_EQ(x.logic_transistors, 48);
  EXPECT_EQ(gate_equivalents(x.logic_transistors, x.flip_flops, 0), 36);
  // One gate of each kind: AND 6 + NAND 4 + OR 6 + NOR 4 + XOR 12 + XNOR 12 + NOT 2 + MUX 12.
  const CmosStat g = tiny(yosys, dir, "gates",
                          "module gates(input a, b, c, output [7:0] y);\n"
                          "  assign y = {a & b, ~(a & b), a | b, ~(a | b), a ^ b, ~(a ^ b), ~a,"
                          " c ? a : b};\nendmodule\n");
  EXPECT_EQ(g.cells, 8);
  EXPECT_EQ(g.flip_flops, 0);
  EXPECT_EQ(g.logic_transistors, 58);
  EXPECT_EQ(gate_equivalents(g.logic_transistors, 0, 0), 15);  // 14.5 rounds to 15
  // RAM bits are not flip-flops of GE.
  EXPECT_EQ(gate_equivalents(400, 100, 64), 100 + 6 * 36);
  fs::remove_all(dir);
}

// read_cmos_stat reads `stat -json`: its figures (the "+" of a partial transistor estimate, a
// public module's "\\" dropped), and errors that name the file: not JSON (as Yosys 0.23 writes
// with a nested hierarchy: the text's lines inside the JSON), a missing field, a bad estimate.
TEST(Area, StatJsonIsReadAndItsErrorsNameTheFile) {
  const auto dir = temp_dir("statjson");
  const auto report = [](const std::string& module) {
    return R"({"modules": {")" + module + R"(": {"num_cells": 5,
      "num_cells_by_type": {"$_DFF_P_": 2, "$_DFFE_PP_": 1, "$_XOR_": 2},
      "estimated_num_transistors": "56+"}}})";
  };
  write(dir / "ok.json", report("\\\\m"));
  const CmosStat c = read_cmos_stat((dir / "ok.json").string(), "m");
  EXPECT_EQ(c.cells, 5);
  EXPECT_EQ(c.transistors, 56);
  EXPECT_TRUE(c.transistors_partial);
  EXPECT_EQ(c.flip_flops, 3);
  EXPECT_EQ(c.logic_transistors, 56 - 2 * kYosysCmosPlainDffTransistors);
  EXPECT_EQ(read_cmos_stat((dir / "ok.json").string()).cells, 5);  // the only module
  const auto error = [&](const std::string& name, const std::string& text) {
    write(dir / name, text);
    try {
      read_cmos_stat((dir / name).string(), "m");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::string nested = report("m");
  nested.insert(nested.size() - 1, ",\n       leaf                          2\n  \"design\": {}");
  const std::string bad = error("nested.json", nested);
  EXPECT_NE(bad.find((dir / "nested.json").string() + ":4:"), std::string::npos) << bad;
  EXPECT_NE(bad.find("not valid JSON"), std::string::npos) << bad;
  std::string missing = report("m");
  missing.replace(missing.find("num_cells\""), 10, "cells\"");
  const std::string field = error("missing.json", missing);
  EXPECT_NE(field.find((dir / "missing.json").string() + ": "), std::string::npos) << field;
  EXPECT_NE(field.find("module m"), std::string::npos) << field;
  EXPECT_NE(field.find("num_cells"), std::string::npos) << field;
  std::string estimate = report("m");
  estimate.replace(estimate.find("56+"), 3, "56?");
  const std::string count = error("estimate.json", estimate);
  EXPECT_NE(count.find((dir / "estimate.json").string()), std::string::npos) << count;
  EXPECT_NE(count.find("\"56?\" is not a count"), std::string::npos) << count;
  EXPECT_NE(error("other.json", report("n")).find("no statistics for module 'm'"),
            std::string::npos);
  fs::remove_all(dir);
}

// Logic depth (`ltp -noff` after the flat flow's abc): a register fed straight from a port is 0
// levels; an 8-input AND needs ceil(log2 8) = 3 levels of 2-input gates, and ABC reaches it.
TEST(Area, LogicDepthIsTheLongestGatePathBetweenRegisters) {
  const std::string yosys = find_yosys();
  SHADESIM_NEEDS_TOOLS(!yosys.empty(), "yosys (Debian package yosys)");
  const auto dir = temp_dir("depth");
  auto depth = [&](const std::string& name, const std::string& verilog) {
    write(dir / (name + ".v"), verilog);
    const Result r = run_shell(yosys + " -q -p 'read_verilog " + (dir / (name + ".v")).string() +
                               "; synth -flatten -top " + name +
                               "; abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX; opt_clean; tee -q -o " +
                               (dir / (name + ".ltp")).string() + " ltp -noff'");
    EXPECT_EQ(r.status, 0) << r.output;
    return read_logic_depth((dir / (name + ".ltp")).string());
  };
  const LogicDepth reg = depth("reg4",
                               "module reg4(input clk, input [3:0] d, output reg [3:0] q);\n"
                               "  always @(posedge clk) q <= d;\nendmodule\n");
  EXPECT_EQ(reg.gates, 0);
  const LogicDepth and8 = depth("and8",
                                "module and8(input clk, input [7:0] a, output reg q);\n"
                                "  always @(posedge clk) q <= &a;\nendmodule\n");
  EXPECT_EQ(and8.gates, 3);
  EXPECT_EQ(and8.from.rfind("a [", 0), 0u) << and8.from;  // a port bit
  EXPECT_EQ(and8.to, "q");                                // the flip-flop it ends at
  write(dir / "none.ltp", "nothing here\n");
  EXPECT_THROW(read_logic_depth((dir / "none.ltp").string()), std::runtime_error);
  fs::remove_all(dir);
}

// A LUT unit: its table (2^A x B bits, one bank, one light) is reported as RAM bits, measured
// by Yosys and equal to the closed form, and left out of GE's flip-flops.
TEST(Area, TableRamBitsAreApartFromGateEquivalents) {
  SHADESIM_NEEDS_TOOLS(!find_yosys().empty(), "yosys (Debian package yosys)");
  const auto dir = temp_dir("ram");
  write(dir / "lut.json",
        R"({"channels":1,"lights":1,"xy_bits":4,"offset_bits":4,"coef":"s2.6:rnd:wrap",)"
        R"("series":"s2.6:trn:wrap","spec_colour":"u1.3:rnd:sat","out_bits":4,)"
        R"("specular":{"kind":"lut","out":"u1.3:sat","lut":{"addr_bits":4,"entry_bits":5}}})");
  const Result area =
      run_shell(shadesim() + "area --config " + (dir / "lut.json").string() + " --no-pnr --cache " +
                (dir / "cache").string() + " --json " + (dir / "area.json").string());
  ASSERT_EQ(area.status, 0) << area.output;
  std::ifstream js(dir / "area.json");
  const auto j = nlohmann::json::parse(js);
  EXPECT_EQ(j["ram_bits"].get<long>(), 16 * 5);
  EXPECT_EQ(j["ram_bits_expected"].get<long>(), 16 * 5);
  const long ffs = j["flip_flops"].get<long>();
  EXPECT_GE(ffs, 16 * 5);  // synth maps the table to flip-flops; GE leaves them out
  EXPECT_EQ(j["gate_equivalents"].get<long>(),
            std::lround(j["logic_transistors"].get<long>() / 4.0) + 6 * (ffs - 16L * 5));
  long row_ram = 0;
  for (const auto& row : j["modules"]) {
    row_ram += row["ram_bits_each"].get<long>() * row["instances"].get<long>();
    if (row["module"] == "specular_unit") {
      EXPECT_EQ(row["ram_bits_each"].get<long>(), 16 * 5);
    }
  }
  EXPECT_EQ(row_ram, 16 * 5);
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"].dump();
  EXPECT_NE(area.output.find("RAM bits"), std::string::npos) << area.output;
  // The library mapping keeps the table as a register file of the library's flip-flops (timed
  // like the rest): more library flip-flops than the generic count less the 3 bits of
  // each of the 16 entries that reach the 3-bit output fraction, which a macro kept apart would
  // take out.
  if (j.contains("liberty")) {
    EXPECT_FALSE(j["liberty"].contains("table_macros")) << j["liberty"].dump();
    EXPECT_GT(j["liberty"]["flip_flops"].get<long>(), ffs - 16L * 3);
    EXPECT_EQ(area.output.find("\n  table RAM "), std::string::npos) << area.output;  // no macro
  }
  fs::remove_all(dir);
}

// nextpnr prints a critical path report after placement and again after routing; the last one
// is the post-route path; its first and last nets name it. (The lines follow nextpnr's format.)
TEST(Area, NextpnrCriticalPathIsTheLastReportsSourceAndSink) {
  const std::string log =
      "Info: Critical path report for clock 'clk_i$SB_IO_IN_$glb_clk' (posedge -> posedge):\n"
      "Info: curr total\n"
      "Info:  0.5  0.5  Source early_q_SB_DFF_Q_DFFLC.O\n"
      "Info:  0.6  1.1    Net early_q budget 0.000000 ns (5,25) -> (5,25)\n"
      "Info:                Sink early_d_SB_LUT4_O_LC.I3\n"
      "Info: 0.5 ns logic, 0.6 ns routing\n"
      "\n"
      "Info: Max frequency for clock 'clk_i$SB_IO_IN_$glb_clk': 99.00 MHz (PASS at 12.00 MHz)\n"
      "Info: Critical path report for clock 'clk_i$SB_IO_IN_$glb_clk' (posedge -> posedge):\n"
      "Info: curr total\n"
      "Info:  0.5  0.5  Source u_unit.spec_q_SB_DFF_Q_DFFLC.O\n"
      "Info:  1.2  1.7    Net u_unit.spec_q[3] budget 0.000000 ns (7,20) -> (8,20)\n"
      "Info:                Sink u_unit.prod_SB_LUT4_O_LC.I1\n"
      "Info:  0.4  2.1  Source u_unit.prod_SB_LUT4_O_LC.O\n"
      "Info:  0.9  3.0    Net u_unit.prod[0] budget 0.000000 ns (8,20) -> (9,21)\n"
      "Info:                Sink u_unit.pix_q_SB_DFF_Q_DFFLC.I0\n"
      "Info:  0.4  3.4  Setup u_unit.pix_q_SB_DFF_Q_DFFLC.I0\n"
      "Info: 1.3 ns logic, 2.1 ns routing\n"
      "\n"
      "Info: Max frequency for clock 'clk_i$SB_IO_IN_$glb_clk': 29.41 MHz (PASS at 12.00 MHz)\n";
  EXPECT_EQ(ice40_flow::read_critical_path(log),
            "net u_unit.spec_q[3] -> net u_unit.prod[0] (1.3 ns logic, 2.1 ns routing)");
  EXPECT_EQ(ice40_flow::read_critical_path("Info: Max frequency for clock 'c': 9 MHz\n"), "");
}

// The scripts beside the drivers reach the tools as commands only; a missing one is named.
TEST(Area, ToolScriptsAreReadWithoutCommentsAndAMissingOneIsNamed) {
  EXPECT_EQ(script_commands("# what it does\n  # indented\nsynth -top t\n\ntee -o x.json stat\n"),
            "synth -top t\n\ntee -o x.json stat\n");
  EXPECT_EQ(fill_placeholders("a @W@/x @W@/y @L@", {{"@W@", "/tmp/w"}, {"@L@", "L"}}),
            "a /tmp/w/x /tmp/w/y L");
  // A value holding its own field is filled in once, not again and again.
  EXPECT_EQ(fill_placeholders("@W@ @W@", {{"@W@", "[@W@]"}}), "[@W@] [@W@]");
  // flat.ys's first command, as this test's own hand-written Yosys run has it (above).
  const std::string flat = tool_script("sim/eda/yosys/flat.ys");
  EXPECT_EQ(flat.rfind("synth -flatten -top shade_unit\n", 0), 0u) << flat;
  EXPECT_EQ(flat.find('#'), std::string::npos) << flat;
  try {
    tool_script("sim/eda/yosys/no_such_script.ys");
    ADD_FAILURE() << "a missing script was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(source_dir() + "/sim/eda/yosys/no_such_script.ys"),
              std::string::npos)
        << e.what();
  }
}

TEST(Area, BadInputGivesAClearError) {
  const auto dir = temp_dir("bad");
  const Result missing = run_shell(shadesim() + "area --config " + (dir / "nope.json").string());
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("nope.json"), std::string::npos) << missing.output;

  std::string bad = kSmallConfig;
  bad.replace(bad.find("\"coef\":\"s2.6:rnd:wrap\""), 22, "\"coef\":12");
  write(dir / "bad.json", bad);
  const Result field = run_shell(shadesim() + "area --config " + (dir / "bad.json").string());
  EXPECT_EQ(field.status, 2) << field.output;
  EXPECT_NE(field.output.find("coef"), std::string::npos) << field.output;

  write(dir / "broken.json", "{\"channels\": 1,");
  const Result syntax = run_shell(shadesim() + "area --config " + (dir / "broken.json").string());
  EXPECT_EQ(syntax.status, 2) << syntax.output;
  EXPECT_NE(syntax.output.find("broken.json"), std::string::npos) << syntax.output;

  write(dir / "small.json", kSmallConfig);
  const Result no_tool =
      run_shell(shadesim("PATH=/nonexistent") + "area --config " + (dir / "small.json").string() +
                " --cache " + (dir / "cache").string());
  EXPECT_EQ(no_tool.status, 2) << no_tool.output;
  EXPECT_NE(no_tool.output.find("'yosys' not found"), std::string::npos) << no_tool.output;
  EXPECT_NE(no_tool.output.find("Debian package yosys"), std::string::npos) << no_tool.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shadesim
