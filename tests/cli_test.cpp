// The shadesim CLI as a user runs it: outputs, JSON figures, and clear errors on bad input.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "host/image.h"

namespace shadesim {
namespace {

struct Result {
  int status = 0;
  std::string output;  // stdout and stderr
};

Result run(const std::string& args) {
  const std::string cmd = std::string(SHADESIM_BINARY_DIR) + "/shadesim " + args + " 2>&1";
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return {-1, "popen failed"};
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int raw = pclose(p);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

std::filesystem::path temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("shadesim_cli_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

const std::string kScenes = std::string(SHADESIM_SOURCE_DIR) + "/scenes/";

TEST(Cli, RenderWritesImagesAndJsonFigures) {
  const auto dir = temp_dir("render");
  const Result r = run("render " + kScenes + "sphere.json --out " + dir.string() + " --json " +
                       (dir / "r.json").string() + " --save-stream " + (dir / "s.cmd").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("PSNR"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ideal (exact pow"), std::string::npos) << "the ideal unit must be labelled";
  std::ifstream js(dir / "r.json");
  const auto j = nlohmann::json::parse(js);
  EXPECT_LE(j["error"]["max_code_lsb"].get<int>(), 1);
  EXPECT_GT(j["pixels"].get<int>(), 10000);
  for (const char* png : {"model.png", "reference.png", "error.png", "compare.png"}) {
    const Image img = read_png((dir / png).string());
    EXPECT_EQ(img.height, 256) << png;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "s.cmd"));
  std::filesystem::remove_all(dir);
}

TEST(Cli, AllUnitsWritesTheHighlightStripAndOneLinePerUnit) {
  const auto dir = temp_dir("units");
  const Result r = run("render " + kScenes + "specular.json --all-units --out " + dir.string() + " --json " +
                       (dir / "u.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream js(dir / "u.json");
  const auto j = nlohmann::json::parse(js);
  ASSERT_EQ(j["units"].size(), 4u);
  std::set<std::string> names;
  for (const auto& u : j["units"]) names.insert(u["unit"].get<std::string>());
  EXPECT_EQ(names, (std::set<std::string>{"ideal", "lut", "schlick", "wpow"}));
  // The ideal unit differs from the reference only by the setup budget and rounding.
  EXPECT_LE(j["units"][0]["max_code_lsb"].get<int>(), 1);
  const Image strip = read_png((dir / "units.png").string());
  EXPECT_EQ(strip.width, 5 * 256 + 4 * 4);  // reference + four units, 4-pixel gaps
  std::filesystem::remove_all(dir);
}

nlohmann::json run_json(const std::string& args, const std::filesystem::path& json_path) {
  const Result r = run(args + " --json " + json_path.string());
  EXPECT_EQ(r.status, 0) << args << "\n" << r.output;
  std::ifstream js(json_path);
  return nlohmann::json::parse(js);
}

TEST(Cli, CyclesBreakdownPartitionsTheRunAndShowsBackPressure) {
  const auto dir = temp_dir("cycles");
  const auto free_run = run_json("cycles " + kScenes + "sphere.json", dir / "a.json");
  const auto pressed = run_json("cycles " + kScenes + "sphere.json --stall-pct 50 --seed 3", dir / "b.json");
  for (const auto* j : {&free_run, &pressed}) {
    uint64_t sum = 0, pixel_row = 0;
    for (const auto& row : (*j)["breakdown"]) {
      sum += row["cycles"].get<uint64_t>();
      if (row["name"] == "pixel") pixel_row = row["cycles"].get<uint64_t>();
    }
    EXPECT_EQ(sum, (*j)["cycles"].get<uint64_t>());
    EXPECT_EQ(pixel_row, (*j)["pixels"].get<uint64_t>());  // one pixel leaves per pixel cycle
    EXPECT_GE((*j)["cycles_per_pixel"].get<double>(), 1.0);
  }
  EXPECT_GT(pressed["cycles"].get<uint64_t>(), free_run["cycles"].get<uint64_t>());
  for (const auto& row : pressed["breakdown"]) {
    if (row["name"] == "back_pressure") EXPECT_GT(row["cycles"].get<uint64_t>(), 0u);
  }
  std::filesystem::remove_all(dir);
}

TEST(Cli, CyclesEstimateEqualsTheRtlOnTheSameSceneAndStimulus) {
#ifndef SHADESIM_HAVE_RTL
  GTEST_SKIP() << "RTL not built (configure with -DSHADESIM_RTL=ON)";
#endif
  // The cycle model alone against the Verilated RTL (a named build via regress), with gaps and
  // back-pressure: the cycle counts must be equal, not close.
  const auto dir = temp_dir("cycles_rtl");
  const std::string stim = " --gap-pct 20 --max-gap 8 --stall-pct 20 --seed 7";
  const auto estimate = run_json("cycles " + kScenes + "sphere.json --channels 1 --lights 1 --coef s4.32:rnd" + stim,
                                 dir / "c.json");
  const auto regress = run_json("regress " + kScenes + "sphere.json --configs grey_s428w --backends cpp --out " +
                                    (dir / "reg").string() + stim,
                                dir / "r.json");
  ASSERT_EQ(regress["jobs"].size(), 1u);
  EXPECT_EQ(regress["jobs"][0]["status"], "pass") << regress.dump(2);
  EXPECT_EQ(regress["jobs"][0]["cycles"].get<uint64_t>(), estimate["cycles"].get<uint64_t>());
  std::filesystem::remove_all(dir);
}

void expect_error(const std::string& args, const std::string& needle) {
  const Result r = run(args);
  EXPECT_NE(r.status, 0) << args;
  EXPECT_NE(r.output.find(needle), std::string::npos) << args << "\n" << r.output;
  EXPECT_EQ(r.output.find("terminate called"), std::string::npos) << r.output;
}

TEST(Cli, BadInputGivesClearErrors) {
  const auto dir = temp_dir("bad");
  expect_error("render /nonexistent/scene.json", "scene.json");
  expect_error("render " + kScenes + "sphere.json --series q4.28", "--series");
  expect_error("render " + kScenes + "sphere.json --series s4.4", "out_bits");
  expect_error("render " + kScenes + "sphere.json --specular phong", "--specular");
  std::ofstream(dir / "broken.json") << "{\"image\": {\"width\": 64,";
  expect_error("render " + (dir / "broken.json").string(), "broken.json");
  expect_error("frobnicate", "subcommand");
  std::filesystem::remove_all(dir);
}

TEST(Cli, HelpListsSubcommandAndWidthDefaults) {
  const Result r = run("render --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("--series"), std::string::npos);
  EXPECT_NE(r.output.find("s4.28"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace shadesim
