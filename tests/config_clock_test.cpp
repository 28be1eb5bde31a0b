// shadesim config --clock-mhz (sim/engines/clock_target.h) on the sphere, timed in osu018: a clock
// the unit meets leaves it unpipelined and times exactly the unit config writes (shadesim area
// on that file finds the same cached flow and Fmax); a clock no unit meets times every rung of the
// pipelining ladder, keeps the fastest unit, names the critical path and exits 1, and the unit
// still runs the scene within the cycles target by shadesim cycles. Without --clock-mhz the
// target is the default, 250 MHz; --clock-mhz 0 times nothing. Needs Yosys, OpenSTA and the
// osu018 cells.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/eda/sta/liberty_flow.h"
#include "tests/support/cli_run.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

const std::string kSphere = std::string(SHADESIM_SOURCE_DIR) + "/scenes/sphere.json";

bool tools_present() {
  return fs::exists(kDefaultLiberty) && run_shell("command -v sta").status == 0 &&
         run_shell("command -v yosys").status == 0;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream is(p);
  return nlohmann::json::parse(is);
}

TEST(ConfigClock, AMetClockTimesTheUnitConfigWritesAndAMissedOneNamesItsPath) {
  if (!tools_present()) GTEST_SKIP() << "yosys, sta or " << kDefaultLiberty << " missing";
  const fs::path dir = temp_dir("config_clock", "sphere");
  // The build's area cache, shared with silicon_table_sphere (the sphere's own unit, the same
  // library flow): one of the two synthesises it, the other finds it.
  const std::string cache_dir = std::string(SHADESIM_BINARY_DIR) + "/area-cache";
  const std::string cache = " --area-cache " + cache_dir;

  // 50 MHz: far below any unit's Fmax in 0.18 um.
  const Result met = run("config " + kSphere + " --clock-mhz 50" + cache + " --json " +
                         (dir / "u50.json").string());
  ASSERT_EQ(met.status, 0) << met.output;
  const auto u50 = read_json(dir / "u50.json");
  const auto& c50 = u50["derivation"]["clock"];
  EXPECT_TRUE(c50["meets"].get<bool>()) << c50.dump();
  ASSERT_EQ(c50["tried"].size(), 1u) << c50.dump();
  const double fmax = c50["tried"][0]["fmax_mhz"].get<double>();
  EXPECT_GE(fmax, 50.0);
  EXPECT_EQ(u50.value("combine_stages", 0), 0);
  EXPECT_NE(met.output.find("combine_stages = 0"), std::string::npos) << met.output;
  // shadesim area on the written unit: the same flow's key, so the same cached Fmax.
  const Result area =
      run("area --config " + (dir / "u50.json").string() + " --no-pnr --no-power --cache " +
          cache_dir + " --json " + (dir / "a.json").string());
  ASSERT_EQ(area.status, 0) << area.output;
  const auto a = read_json(dir / "a.json");
  EXPECT_TRUE(a["liberty"]["from_cache"].get<bool>()) << a["liberty"].dump();
  EXPECT_DOUBLE_EQ(a["liberty"]["fmax_mhz"].get<double>(), fmax);

  // No --clock-mhz: the default target, 250 MHz in osu018 (as --help says). The unit timed is
  // the same cached one; whether it meets is its measured Fmax against 250. --clock-mhz 0: no
  // clock target, nothing timed.
  const Result by_default =
      run("config " + kSphere + cache + " --json " + (dir / "udefault.json").string());
  const auto udefault = read_json(dir / "udefault.json");
  const auto& cdefault = udefault["derivation"]["clock"];
  EXPECT_DOUBLE_EQ(cdefault["target_mhz"].get<double>(), 250.0) << cdefault.dump();
  EXPECT_DOUBLE_EQ(cdefault["tried"][0]["fmax_mhz"].get<double>(), fmax);
  EXPECT_EQ(cdefault["meets"].get<bool>(), fmax >= 250.0) << cdefault.dump();
  EXPECT_EQ(by_default.status, fmax >= 250.0 ? 0 : 1) << by_default.output;
  const Result none =
      run("config " + kSphere + " --clock-mhz 0 --json " + (dir / "unone.json").string());
  ASSERT_EQ(none.status, 0) << none.output;
  EXPECT_FALSE(read_json(dir / "unone.json")["derivation"].contains("clock"));
  const Result help = run("config --help");
  EXPECT_NE(help.output.find("250 MHz by default"), std::string::npos) << help.output;

  // 5 GHz: no unit meets it. Every rung of the sphere's ladder (combine_stages 0, 1, 2; it has
  // no squarer) is timed, the fastest kept, its path named.
  const Result missed = run("config " + kSphere + " --clock-mhz 5000" + cache + " --json " +
                            (dir / "u5000.json").string());
  EXPECT_EQ(missed.status, 1) << missed.output;
  EXPECT_NE(missed.output.find("no unit meets 5000 MHz"), std::string::npos) << missed.output;
  EXPECT_NE(missed.output.find("critical path"), std::string::npos) << missed.output;
  const auto u5000 = read_json(dir / "u5000.json");
  const auto& c = u5000["derivation"]["clock"];
  EXPECT_FALSE(c["meets"].get<bool>());
  ASSERT_EQ(c["tried"].size(), 3u) << c.dump();
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(c["tried"][i]["combine_stages"], i);
    EXPECT_EQ(c["tried"][i]["square_stages"], 1);
  }
  EXPECT_DOUBLE_EQ(c["tried"][0]["fmax_mhz"].get<double>(), fmax);  // the same unit, cached
  const size_t chosen = c["chosen"].get<size_t>();
  for (size_t other = 0; other < 3; ++other) {
    EXPECT_GE(c["tried"][chosen]["fmax_mhz"].get<double>(),
              c["tried"][other]["fmax_mhz"].get<double>());
  }
  EXPECT_EQ(u5000.value("combine_stages", 0), c["tried"][chosen]["combine_stages"].get<int>());
  // The kept unit still runs the scene within 1.10 cycles per pixel (the cycle model).
  const Result cycles = run("cycles " + kSphere + " --config " + (dir / "u5000.json").string() +
                            " --json " + (dir / "cycles.json").string());
  ASSERT_EQ(cycles.status, 0) << cycles.output;
  EXPECT_LE(read_json(dir / "cycles.json")["cycles_per_pixel"].get<double>(), 1.10);

  const Result bad = run("config " + kSphere + " --clock-mhz 250 --clock-target asic");
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.output.find("--clock-target"), std::string::npos) << bad.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shadesim
