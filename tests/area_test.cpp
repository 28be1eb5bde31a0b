// shadesim area against Yosys itself: the cell count of a small unit equals that of a Yosys run
// this test writes by hand (its own parameter list and script, not the code under test); the
// cache answers a repeated run without Yosys and misses on a changed parameter; bad input and
// a missing tool give clear errors. Small units (1 channel, 1 light, narrow widths) and no
// place and route keep it quick.
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

#include "tests/support/cli_run.h"

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
    R"("spec_colour":"u1.3:rnd:sat","out_bits":4,"specular":{"kind":"ideal","out":"u1.3"}})";
// The same unit as shade_unit parameters, written out by hand from rtl/shade_unit.sv's header:
// WL = integer + fraction bits, QUANT 0 truncate, OVERFLOW 1 wrap, SPECULAR_KIND 0 ideal.
const char* kSmallChparam =
    "-set CHANNELS 1 -set LIGHTS 1 -set XY_BITS 4 -set COEF_WL 8 -set COEF_IWL 2 "
    "-set SERIES_WL 8 -set SERIES_IWL 2 -set SERIES_QUANT 0 -set SERIES_OVERFLOW 1 "
    "-set SPEC_COLOUR_WL 4 -set SPEC_COLOUR_IWL 1 -set OUT_BITS 4 -set SPECULAR_KIND 0 "
    "-set SPECULAR_OUT_WL 4 -set SPECULAR_OUT_IWL 1";

TEST(Area, CellCountEqualsADirectYosysRunAndTheCacheIsReused) {
  const std::string yosys = find_yosys();
  if (yosys.empty()) GTEST_SKIP() << "yosys not installed";
  const auto dir = temp_dir("direct");
  write(dir / "small.json", kSmallConfig);

  // The direct run: every rtl/*.sv, the chparam list above, synth -flatten and the gate mapping.
  // ABC's result depends on the netlist's order, so read the files in the documented order
  // (packages first, then by name; sim/area.h).
  std::vector<std::string> sources;
  for (const auto& e : fs::directory_iterator(std::string(SHADESIM_SOURCE_DIR) + "/rtl")) {
    if (e.path().extension() == ".sv") sources.push_back(e.path().string());
  }
  const auto package = [](const std::string& f) {
    return f.size() > 7 && f.compare(f.size() - 7, 7, "_pkg.sv") == 0;
  };
  std::sort(sources.begin(), sources.end(), [&](const std::string& a, const std::string& b) {
    return package(a) != package(b) ? package(a) : a < b;
  });
  std::string files;
  for (const auto& f : sources) files += " " + f;
  write(dir / "direct.ys", "read_verilog -sv" + files + "\nchparam " + kSmallChparam +
                               " shade_unit\nsynth -flatten -top shade_unit\n"
                               "abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX\nopt_clean\n"
                               "tee -o " +
                               (dir / "direct_stat.txt").string() + " stat\n");
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
