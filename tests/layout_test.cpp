// shadesim layout's readers (sim/eda/layout/): the DEF, LEF sizes, magic's DRC count, netgen's
// LVS verdict, rc2dly's SPEF fix-up and the annotation count, and the picture - each on a small
// hand-written input whose figures are worked out here by hand.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <string>

#include "host/image.h"
#include "sim/eda/layout/layout_png.h"
#include "sim/eda/layout/layout_reports.h"
#include "sim/eda/layout/spef.h"

namespace shadesim {
namespace {

// Two cells (one FILL), two pins, two nets; units of 100 per micron.
constexpr const char* kDef = R"(VERSION 5.6 ;
DESIGN tiny ;
UNITS DISTANCE MICRONS 100 ;
DIEAREA ( -100 -200 ) ( 2900 1800 ) ;
COMPONENTS 3 ;
- INVX1_1 INVX1 + PLACED ( 0 0 ) N ;
- FILL_1 FILL + PLACED ( 240 0 ) FS ;
- NAND2X1_1 NAND2X1 + PLACED ( 320 0 ) N ;
END COMPONENTS
PINS 2 ;
- a + NET a
  + LAYER metal2 ( -10 -10 ) ( 10 10 )
  + PLACED ( 500 -200 ) N ;
- y + NET y
  + PLACED ( 2900 700 ) N ;
END PINS
NETS 2 ;
- a
  ( PIN a ) ( INVX1_1 A )
+ ROUTED metal2 ( 500 -200 ) ( * 400 ) M2_M1
  NEW metal1 ( 500 400 ) ( 100 * ) ;
- y
  ( NAND2X1_1 Y ) ( PIN y )
+ ROUTED metal3 ( 400 700 ) ( 2900 * ) M3_M2 M2_M1
  NEW metal1 ( 400 700 ) M2_M1 ;
END NETS
SPECIALNETS 1 ;
- vdd
+ ROUTED metal1 200 ( 0 1000 ) ( 2800 1000 ) ;
END SPECIALNETS
END DESIGN
)";

constexpr const char* kLef = R"(MACRO INVX1
  CLASS CORE ;
  SIZE 2.400 BY 10.000 ;
END INVX1
MACRO FILL
  SIZE 0.800 BY 10.000 ;
END FILL
MACRO NAND2X1
  SIZE 2.400 BY 10.000 ;
  PIN A
  END A
END NAND2X1
)";

TEST(Layout, LefSizesAreEveryMacrosSize) {
  const auto s = parse_lef_sizes(kLef);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s.at("FILL").width_um, 0.8);
  EXPECT_DOUBLE_EQ(s.at("NAND2X1").height_um, 10.0);
}

TEST(Layout, DefGivesDieCoreWireLengthAndVias) {
  const DefSummary d = parse_def(kDef, "tiny.def", parse_lef_sizes(kLef));
  EXPECT_DOUBLE_EQ(d.units_per_micron, 100);
  // Die (-1, -2) to (29, 18) um: 30 x 20.
  EXPECT_DOUBLE_EQ(d.die_area_um2(), 600);
  // Cells from x 0 to 3.2 + 2.4 = 5.6 um, y 0 to 10: 56 um^2.
  EXPECT_NEAR(d.core_area_um2(), 56, 1e-9);
  EXPECT_EQ(d.components, 3);
  EXPECT_EQ(d.fill_cells, 1);
  EXPECT_EQ(d.pins, 2);
  EXPECT_EQ(d.nets, 2);
  // a: metal2 6 um up, metal1 4 um left; y: metal3 25 um; the point-only NEW adds nothing.
  // SPECIALNETS (power) are not signal wiring.
  EXPECT_NEAR(d.wire_length_um, 35, 1e-9);
  EXPECT_NEAR(d.wire_length_by_layer_um.at("metal2"), 6, 1e-9);
  EXPECT_NEAR(d.wire_length_by_layer_um.at("metal1"), 4, 1e-9);
  EXPECT_NEAR(d.wire_length_by_layer_um.at("metal3"), 25, 1e-9);
  // M2_M1 on a, M3_M2 and M2_M1 on y's first row, M2_M1 on its NEW.
  EXPECT_EQ(d.vias, 4);
  EXPECT_EQ(d.segments.size(), 3u);
}

TEST(Layout, DefWithoutUnitsOrDieIsAnErrorNamingTheFile) {
  try {
    parse_def("DESIGN x ;\nDIEAREA ( 0 0 ) ( 1 1 ) ;\n", "x.def", {});
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.def: no UNITS"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_def("UNITS DISTANCE MICRONS 100 ;\n", "y.def", {}), std::runtime_error);
}

TEST(Layout, MagicDrcCount) {
  EXPECT_EQ(parse_magic_drc_count("Loading ...\ndrc = 14\nDRC failure\n"), 14);
  EXPECT_EQ(parse_magic_drc_count("drc = 0\n"), 0);
  EXPECT_EQ(parse_magic_drc_count("magic crashed\n"), -1);
}

TEST(Layout, NetgenLvsVerdict) {
  const LvsResult clean = parse_netgen_lvs(
      "Circuit 1 contains 1958 devices, Circuit 2 contains 1958 devices.\n"
      "Netlists match uniquely.\nResult: Circuits match uniquely.\nTotal errors = 0\n");
  EXPECT_TRUE(clean.found);
  EXPECT_TRUE(clean.clean);
  EXPECT_EQ(clean.total_errors, 0);
  EXPECT_EQ(clean.verdict, "Circuits match uniquely.");
  const LvsResult bad = parse_netgen_lvs(
      "Subcircuit pins:\nNetlists do not match.\nResult: Netlists do not match.\n"
      "Total errors = 3\n");
  EXPECT_TRUE(bad.found);
  EXPECT_FALSE(bad.clean);
  EXPECT_EQ(bad.total_errors, 3);
  EXPECT_FALSE(parse_netgen_lvs("netgen: command not found\n").found);
  EXPECT_FALSE(parse_netgen_lvs("netgen: command not found\n").clean);
}

// rc2dly's output shape: internal nodes "N_K", values in pF under a C_UNIT of FF, Yosys's bit
// names; one bus port (d).
constexpr const char* kRc2dlySpef = R"(*SPEF "IEEE 1481.1999"
*DESIGN "tiny"
*DIVIDER /
*DELIMITER :
*BUS_DELIMITER <>
*T_UNIT 1 PS
*C_UNIT 1 FF
*R_UNIT 1 OHM

*NAME_MAP
*1 d[0]
*2 INVX1_1
*3 eng_q[9]
*4 DFFPOSX1_2

*PORTS
d[0] I

*D_NET *1 0.0123
*CONN
*P *1 I
*I *2:A I *L 0.0089
*CAP
1 1_1 0.004
2 1_2 0.0031
*RES
1 *1 1_1 1.25
2 1_1 1_2 0.5
3 1_2 *2:A 0.25
*END

*D_NET *3 0.002
*CONN
*I *4:Q O *D DFFPOSX1
*I *2:A I *L 0.0089
*CAP
1 3_1 0.002
*RES
1 *4:Q 3_1 2.5
2 3_1 *2:A 2.5
*END
)";

TEST(Layout, SpefFixNodesUnitsAndNames) {
  const std::string fixed = fix_qflow_spef(kRc2dlySpef, {"d"});
  EXPECT_NE(fixed.find("*C_UNIT 1 PF\n"), std::string::npos);
  EXPECT_EQ(fixed.find("*C_UNIT 1 FF"), std::string::npos);
  EXPECT_NE(fixed.find("1 *1:1 0.004\n"), std::string::npos);
  EXPECT_NE(fixed.find("2 *1:1 *1:2 0.5\n"), std::string::npos);
  EXPECT_NE(fixed.find("3 *1:2 *2:A 0.25\n"), std::string::npos);
  EXPECT_NE(fixed.find("1 *4:Q *3:1 2.5\n"), std::string::npos);
  // A bus port's bit keeps its brackets; another bit name is written as blif2Verilog does.
  EXPECT_NE(fixed.find("*1 d[0]\n"), std::string::npos);
  EXPECT_NE(fixed.find("*3 eng_q_9_\n"), std::string::npos);
  // Values, the connection section and the ports are untouched.
  EXPECT_NE(fixed.find("*I *2:A I *L 0.0089\n"), std::string::npos);
  EXPECT_NE(fixed.find("*PORTS\nd[0] I\n"), std::string::npos);
  EXPECT_EQ(spef_net_names(fixed), (std::set<std::string>{"d[0]", "eng_q_9_"}));
}

TEST(Layout, UnannotatedNetsAreTheNetlistsNetsTheSpefLacks) {
  const VerilogNets v = verilog_nets(
      "module tiny (clk_i, d, y);\ninput clk_i;\ninput [1:0] d;\noutput y;\n"
      "INVX1 INVX1_1 ( .A(d[0]), .Y(eng_q_9_) );\n"
      "NAND2X1 NAND2X1_1 ( .A(eng_q_9_), .B(d[1]), .Y(y) );\nendmodule\n");
  EXPECT_EQ(v.bus_ports, (std::set<std::string>{"d"}));
  EXPECT_EQ(v.connected, (std::set<std::string>{"d[0]", "d[1]", "eng_q_9_", "y"}));
}

TEST(Layout, PictureHasTheDiesAspectAndShowsCellsAndWires) {
  const DefSummary d = parse_def(kDef, "tiny.def", parse_lef_sizes(kLef));
  const Image im = draw_layout(d, parse_lef_sizes(kLef), 300);
  EXPECT_EQ(im.width, 300);  // 30 x 20 um at 10 px/um
  EXPECT_EQ(im.height, 200);
  EXPECT_EQ(im.channels, 3);
  // The metal3 wire of y runs along y = 7 um (row 200 - 1 - 90 = 109), x 4..29 um.
  const auto px = [&](int x, int y) {
    const size_t at = 3 * (static_cast<size_t>(y) * 300 + static_cast<size_t>(x));
    return std::array<int, 3>{im.pixels[at], im.pixels[at + 1], im.pixels[at + 2]};
  };
  EXPECT_EQ(px(200, 109), (std::array<int, 3>{60, 200, 90}));
  // The INVX1 body (0..2.4 um, 0..10 um): x 10..33, rows 100..179, away from wires.
  EXPECT_EQ(px(20, 150), (std::array<int, 3>{105, 105, 115}));
  EXPECT_THROW(draw_layout(d, {}, 8), std::invalid_argument);
}

}  // namespace
}  // namespace shadesim
