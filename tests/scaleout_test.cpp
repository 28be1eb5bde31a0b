// Regression beyond one machine: shards through GNU parallel merged back into what one
// unsharded regress reports, a shard killed mid-run (merge names what is missing, --resume
// finishes it), job lines, the watchdog on an RTL that stops emitting, per-run timeouts, and
// merge's errors on folders and result files it cannot use.
//
// The RTL tests reuse the builds the default regression needs (the shipped scenes on their own
// configurations) and the named build grey_s428w with its hang fault; the kill test runs a subset
// of the scenes on one backend.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <thread>

#include "support/cli_run.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

const std::string kSource = SHADESIM_SOURCE_DIR;
const std::string kShadesim = std::string(SHADESIM_BINARY_DIR) + "/shadesim";
const std::string kCache = std::string(SHADESIM_BINARY_DIR) + "/rtl-cache";

nlohmann::json read_json(const fs::path& p) {
  std::ifstream is(p);
  EXPECT_TRUE(is.good()) << p;
  return nlohmann::json::parse(is);
}

void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// shadesim from the checkout's root (the scenes are named relative to it).
Result in_source(const std::string& cmd) { return run_shell("cd " + kSource + " && " + cmd); }

size_t count_lines_matching(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return static_cast<size_t>(
      std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

// A run's figures without what differs between two sessions of the same run: wall time, speed,
// and where its files are.
nlohmann::json comparable(nlohmann::json job) {
  for (const char* k : {"seconds", "cycles_per_second", "dir", "stream", "log", "waves", "replay"})
    job.erase(k);
  return job;
}

// ---- merge on folders made by hand: no RTL needed ---------------------------------------------

nlohmann::json spec(const std::string& scene, const std::string& backend, int seed) {
  const std::string stem = fs::path(scene).stem().string();
  return {{"id", stem + "__own_" + stem + "__" + backend + "__seed" + std::to_string(seed)},
          {"scene", scene},
          {"config_kind", "own"},
          {"config", "own:" + stem},
          {"backend", backend},
          {"seed", seed}};
}

nlohmann::json passed_record(const nlohmann::json& s, uint64_t pixels, uint64_t cycles) {
  nlohmann::json r = s;
  r["status"] = "pass";
  r["pixels"] = pixels;
  r["cycles"] = cycles;
  return r;
}

void write_plan(const fs::path& dir, const std::string& name,
                const std::vector<nlohmann::json>& runs) {
  nlohmann::json ids = nlohmann::json::array();
  for (const auto& r : runs) ids.push_back(r["id"]);
  write_text(dir / "plans" / (name + ".json"), nlohmann::json{{"tool", "shadesim regress"},
                                                              {"shard", nullptr},
                                                              {"settings",
                                                               {{"gap_pct", 20},
                                                                {"max_gap", 8},
                                                                {"stall_pct", 20},
                                                                {"timeout", 1800},
                                                                {"watchdog", 0}}},
                                                              {"runs", runs},
                                                              {"selected", ids}}
                                                   .dump());
}

TEST(Merge, NamesMissingRunsAndFailsThenPassesWhenTheyArrive) {
  const fs::path d = temp_dir("scaleout", "merge_missing");
  const auto a = spec("scenes/a.json", "cpp", 1), b = spec("scenes/b.json", "cpp", 2);
  write_plan(d / "one", "all", {a, b});
  write_text(d / "one" / "runs" / a["id"].get<std::string>() / "run.json",
             passed_record(a, 10, 30).dump());
  // Started (its simulator's log is there), never finished.
  write_text(d / "one" / "runs" / b["id"].get<std::string>() / "cosim.log", "");
  Result r = run(("merge " + (d / "one").string() + " --json " + (d / "m.json").string()));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(b["id"].get<std::string>() + ": planned in"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("started, never finished"), std::string::npos) << r.output;
  const auto m = read_json(d / "m.json");
  EXPECT_EQ(m["missing_runs"], nlohmann::json::array({b["id"]}));
  EXPECT_EQ(m["passed"], 1);
  EXPECT_EQ(m["missing"], 1);

  // The missing run arrives in a second folder: the merge of both is whole.
  write_text(d / "two" / "runs" / b["id"].get<std::string>() / "run.json",
             passed_record(b, 5, 9).dump());
  r = run("merge " + (d / "one").string() + " " + (d / "two").string() + " --json " +
          (d / "m2.json").string() + " --junit " + (d / "m2.xml").string());
  EXPECT_EQ(r.status, 0) << r.output;
  const auto m2 = read_json(d / "m2.json");
  ASSERT_EQ(m2["jobs"].size(), 2u);
  EXPECT_EQ(m2["jobs"][1]["cycles"], 9);
  EXPECT_EQ(m2["missing"], 0);

  // The same run in two folders is a duplicate, named.
  write_text(d / "three" / "runs" / b["id"].get<std::string>() / "run.json",
             passed_record(b, 5, 9).dump());
  r = run("merge " + (d / "one").string() + " " + (d / "two").string() + " " +
          (d / "three").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("duplicate run " + b["id"].get<std::string>()), std::string::npos)
      << r.output;
}

TEST(Merge, RefusesBadFoldersAndNamesMalformedResultFiles) {
  const fs::path d = temp_dir("scaleout", "merge_bad");
  Result r = run("merge " + (d / "nowhere").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find((d / "nowhere").string() + ": no such folder"), std::string::npos)
      << r.output;
  r = run("merge " + d.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("not a regress output folder"), std::string::npos) << r.output;

  const auto a = spec("scenes/a.json", "cpp", 1), b = spec("scenes/b.json", "systemc", 1);
  write_plan(d / "out", "all", {a, b});
  const fs::path bad = d / "out" / "runs" / a["id"].get<std::string>() / "run.json";
  write_text(bad, "{\"scene\": ");
  nlohmann::json wrong = passed_record(b, 1, 2);
  wrong["cycles"] = "many";
  const fs::path typed = d / "out" / "runs" / b["id"].get<std::string>() / "run.json";
  write_text(typed, wrong.dump());
  r = run("merge " + (d / "out").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(bad.string() + ": not valid JSON"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(typed.string() +
                          ": field 'cycles' is \"many\", expected an unsigned cycle count"),
            std::string::npos)
      << r.output;
}

TEST(Regress, RefusesBadShardsAndResumeFolders) {
  for (const std::string s : {"0/3", "4/3", "3", "a/b", "2/0", "1/3x"}) {
    const Result r = in_source(kShadesim + " regress --shard " + s + " --out /tmp/shadesim_never");
    EXPECT_EQ(r.status, 2) << s << ": " << r.output;
    EXPECT_NE(r.output.find("--shard '" + s + "': expected I/N with 1 <= I <= N"),
              std::string::npos)
        << r.output;
  }
  const fs::path d = temp_dir("scaleout", "resume_bad");
  Result r = run("regress --resume " + (d / "none").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("no such folder"), std::string::npos) << r.output;
  r = run("regress --resume " + d.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("has no plans/ folder"), std::string::npos) << r.output;
}

TEST(Regress, EmitsOneSelfContainedLinePerRunNamingSceneConfigBackendSeed) {
  const fs::path d = temp_dir("scaleout", "emit");
  const Result r =
      in_source(kShadesim +
                " regress scenes/sphere.json scenes/torus.json --configs lut_d,wpow16_n"
                " --seed 7 --emit-jobs " +
                (d / "jobs.txt").string() + " --out " + (d / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream is(d / "jobs.txt");
  std::vector<std::string> lines;
  for (std::string l; std::getline(is, l);) lines.push_back(l);
  // 2 scenes x 2 configurations x 2 backends; each scene x configuration the next seed.
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_NE(lines[0].find("scenes/sphere.json --configs lut_d --backends cpp --seed 7"),
            std::string::npos)
      << lines[0];
  EXPECT_NE(lines[1].find("scenes/sphere.json --configs lut_d --backends systemc --seed 7"),
            std::string::npos);
  EXPECT_NE(lines[2].find("scenes/sphere.json --configs wpow16_n --backends cpp --seed 8"),
            std::string::npos);
  EXPECT_NE(lines[7].find("scenes/torus.json --configs wpow16_n --backends systemc --seed 10"),
            std::string::npos);
  for (const auto& l : lines) {
    EXPECT_EQ(l.rfind("cd " + kSource + " && ", 0), 0u) << l;
    EXPECT_NE(l.find("--out " + (d / "out").string()), std::string::npos) << l;
  }
  // Every line's run is planned: merging before any ran names all 8 as never started.
  const Result m = run("merge " + (d / "out").string());
  EXPECT_EQ(m.status, 1);
  EXPECT_EQ(count_lines_matching(m.output, "never started"), 8u) << m.output;
}

// --random: each scenario on each named or file configuration, after every scene run, the seeds
// numbered on; own has no unit without a scene, so it gets none. Ids name the scenario.
TEST(Regress, PlansRandomRunsPerConfigurationAfterTheSceneRunsWithStableIds) {
  const fs::path d = temp_dir("scaleout", "emit_random");
  std::vector<std::string> ids[2];
  for (int pass = 0; pass < 2; ++pass) {
    const fs::path out = d / ("out" + std::to_string(pass));
    const Result r =
        in_source(kShadesim +
                  " regress scenes/sphere.json --configs lut_d,wpow16_n --config own --random edge"
                  " --backends cpp --seed 7 --emit-jobs " +
                  (d / "jobs.txt").string() + " --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    std::ifstream is(d / "jobs.txt");
    std::vector<std::string> lines;
    for (std::string l; std::getline(is, l);) lines.push_back(l);
    // sphere on lut_d (seed 7), wpow16_n (8), its own unit (9); edge on lut_d (10), wpow16_n (11).
    ASSERT_EQ(lines.size(), 5u) << r.output;
    EXPECT_NE(lines[2].find("regress scenes/sphere.json --backends cpp --seed 9"),
              std::string::npos)
        << lines[2];
    EXPECT_NE(lines[3].find("regress --random-only --random edge --configs lut_d --backends cpp "
                            "--seed 10"),
              std::string::npos)
        << lines[3];
    EXPECT_NE(lines[4].find("--random edge --configs wpow16_n --backends cpp --seed 11"),
              std::string::npos)
        << lines[4];
    const nlohmann::json plan = read_json(out / "plans" / "emitted.json");
    for (const auto& run : plan.at("runs")) ids[pass].push_back(run.at("id").get<std::string>());
  }
  const std::vector<std::string> expected = {
      "sphere__lut_d__cpp__seed7", "sphere__wpow16_n__cpp__seed8", "sphere__own_sphere__cpp__seed9",
      "random-edge__lut_d__cpp__seed10", "random-edge__wpow16_n__cpp__seed11"};
  EXPECT_EQ(ids[0], expected);
  EXPECT_EQ(ids[1], expected);  // the same command plans the same ids
  // Sharding splits the random runs with the rest: shard 2/2 is runs 2 and 4.
  const Result sh =
      in_source(kShadesim +
                " regress scenes/sphere.json --configs lut_d,wpow16_n --config own --random edge"
                " --backends cpp --seed 7 --shard 2/2 --emit-jobs " +
                (d / "shard.txt").string() + " --out " + (d / "shard").string());
  ASSERT_EQ(sh.status, 0) << sh.output;
  const nlohmann::json plan = read_json(d / "shard" / "plans" / "emitted.json");
  EXPECT_EQ(plan.at("selected"),
            nlohmann::json({"sphere__wpow16_n__cpp__seed8", "random-edge__lut_d__cpp__seed10"}));
  // Every planned run, random ones too, is named by merge before any ran.
  const Result m = run("merge " + (d / "out0").string());
  EXPECT_EQ(m.status, 1);
  EXPECT_EQ(count_lines_matching(m.output, "never started"), 5u) << m.output;
  EXPECT_NE(m.output.find("random-edge__wpow16_n__cpp__seed11"), std::string::npos) << m.output;
}

TEST(Regress, RefusesAnUnknownRandomScenarioNamingTheValidOnes) {
  const Result r = in_source(kShadesim + " regress --random nosuch --out /tmp/shadesim_never");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--random 'nosuch': unknown scenario"), std::string::npos) << r.output;
  for (const char* name : {"mixed", "long", "short", "slow", "maxbp", "switch", "tiny", "edge"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name << ": " << r.output;
  EXPECT_FALSE(fs::exists("/tmp/shadesim_never/plans"));
  // Only the own unit: a random stream has no unit to run on.
  const Result own = in_source(kShadesim +
                               " regress --random edge --random-only --config own --emit-jobs "
                               "/tmp/shadesim_never.txt --out /tmp/shadesim_never");
  EXPECT_EQ(own.status, 2) << own.output;
  EXPECT_NE(own.output.find("--random: no configuration to run it on"), std::string::npos)
      << own.output;
}

TEST(Explore, EmitsTheRunsOfItsVerificationAsRegressJobLines) {
  // The model-only search, then the chosen point's regress runs as lines instead of in RTL (the
  // area estimate's anchor is synthesised into the build's area cache once, as explore_test does).
  const fs::path d = temp_dir("scaleout", "explore_emit");
  const Result r =
      in_source(kShadesim + " explore scenes/sphere.json --budget 1 --estimate-only --area-cache " +
                SHADESIM_BINARY_DIR + "/area-cache --out " + (d / "ex").string() + " --emit-jobs " +
                (d / "jobs.txt").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream is(d / "jobs.txt");
  std::vector<std::string> lines;
  for (std::string l; std::getline(is, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 2u);  // one scene x the chosen point x 2 backends
  const std::string chosen = (d / "ex" / "chosen.json").string(),
                    out = (d / "ex" / "verify" / "chosen").string();
  EXPECT_NE(
      lines[0].find("regress scenes/sphere.json --config " + chosen + " --backends cpp --seed 1"),
      std::string::npos)
      << lines[0];
  EXPECT_NE(lines[1].find("--backends systemc"), std::string::npos) << lines[1];
  EXPECT_NE(lines[0].find("--out " + out), std::string::npos) << lines[0];
  EXPECT_TRUE(fs::exists(d / "ex" / "verify" / "chosen" / "plans" / "emitted.json"));
}

#ifdef SHADESIM_HAVE_RTL

TEST(Scaleout, ThreeShardsThroughGnuParallelMergeToTheUnshardedRun) {
  const fs::path d = temp_dir("scaleout", "shards");
  const std::string common = " --cache " + kCache + " -j 1";
  Result r = in_source("nice -n 10 " + kShadesim + " regress" + common + " --out " +
                       (d / "full").string() + " --json " + (d / "full.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  r = in_source("nice -n 10 parallel -j 3 " + kShadesim + " regress" + common +
                " --shard {}/3 --out " + (d / "shard{}").string() + " ::: 1 2 3");
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("merge " + (d / "shard1").string() + " " + (d / "shard2").string() + " " +
          (d / "shard3").string() + " --json " + (d / "merged.json").string() + " --junit " +
          (d / "merged.xml").string());
  ASSERT_EQ(r.status, 0) << r.output;

  const auto full = read_json(d / "full.json"), merged = read_json(d / "merged.json");
  // The default regression: every shipped scene on its own configuration x 2 backends.
  size_t scenes = 0;
  for (const auto& e : fs::directory_iterator(kSource + "/scenes"))
    scenes += e.path().extension() == ".json";
  ASSERT_EQ(full["jobs"].size(), 2 * scenes);
  ASSERT_EQ(merged["jobs"].size(), full["jobs"].size());
  for (size_t i = 0; i < full["jobs"].size(); ++i) {
    EXPECT_EQ(comparable(merged["jobs"][i]), comparable(full["jobs"][i])) << "run " << i;
  }
  for (const char* k :
       {"passed", "mismatched", "errors", "skipped", "hangs", "timeouts", "missing"}) {
    EXPECT_EQ(merged[k], full[k]) << k;
  }
  EXPECT_EQ(merged["passed"], 2 * scenes);
  // Each shard ran its equal share: ceil or floor of 10 / 3.
  for (int s = 1; s <= 3; ++s) {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(d / ("shard" + std::to_string(s)) / "runs")) {
      n += fs::exists(e.path() / "run.json");
    }
    EXPECT_GE(n, (2 * scenes) / 3);
    EXPECT_LE(n, (2 * scenes + 2) / 3);
  }
  std::ifstream xml(d / "merged.xml");
  const std::string junit((std::istreambuf_iterator<char>(xml)), std::istreambuf_iterator<char>());
  EXPECT_EQ(count_lines_matching(junit, "<testcase "), 2 * scenes);
}

// Starts a shard in the background, stops it once its first run's record is there (SIGSTOP, so no
// later record can be written), then kills it. Returns the records it left.
size_t run_and_kill_after_first_record(const std::string& cmd, const fs::path& out) {
  const Result started =
      in_source("(" + cmd + " > " + (out.string() + ".log") + " 2>&1 & echo $!)");
  const pid_t pid = static_cast<pid_t>(std::stol(started.output));
  const auto records = [&]() {
    size_t n = 0;
    if (fs::is_directory(out / "runs")) {
      for (const auto& e : fs::directory_iterator(out / "runs"))
        n += fs::exists(e.path() / "run.json");
    }
    return n;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  while (records() == 0 && std::chrono::steady_clock::now() < deadline && kill(pid, 0) == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kill(pid, SIGSTOP);
  kill(pid, SIGKILL);
  run_shell("sleep 1");  // its co-simulation child, orphaned, finishes on its own
  return records();
}

TEST(Scaleout, AKilledShardIsNamedByMergeAndResumeCompletesIt) {
  const std::string scenes =
      " scenes/specular.json scenes/sphere.json scenes/torus.json --backends cpp";
  // Long runs (90 % back-pressure) so the shard is caught between its runs.
  const std::string common = scenes + " --stall-pct 90 --cache " + kCache + " -j 1";
  fs::path d;
  size_t left = 0;
  // The kill lands after the first record; if the shard raced past it, try again in a fresh folder.
  for (int attempt = 0; attempt < 3 && left != 1; ++attempt) {
    d = temp_dir("scaleout", "kill" + std::to_string(attempt));
    left = run_and_kill_after_first_record(
        kShadesim + " regress" + common + " --shard 1/2 --out " + (d / "s1").string(), d / "s1");
  }
  ASSERT_EQ(left, 1u) << "the killed shard (2 runs) should have left exactly its first record";
  Result r =
      in_source(kShadesim + " regress" + common + " --shard 2/2 --out " + (d / "s2").string());
  ASSERT_EQ(r.status, 0) << r.output;

  // The job list is specular (seed 1), sphere (2), torus (3); shard 1 of 2 holds specular and
  // torus.
  const std::set<std::string> shard1 = {"specular__own_specular__cpp__seed1",
                                        "torus__own_torus__cpp__seed3"};
  r = run("merge " + (d / "s1").string() + " " + (d / "s2").string() + " --json " +
          (d / "m.json").string());
  EXPECT_EQ(r.status, 1) << r.output;
  const auto m = read_json(d / "m.json");
  ASSERT_EQ(m["missing_runs"].size(), 1u) << r.output;
  EXPECT_TRUE(shard1.count(m["missing_runs"][0].get<std::string>())) << m["missing_runs"];
  EXPECT_NE(r.output.find(m["missing_runs"][0].get<std::string>() + ": planned in"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(m["passed"], 2);

  const auto first = fs::last_write_time(d / "s1" / "runs" / *shard1.begin() / "run.json");
  r = run("regress --resume " + (d / "s1").string() + " --cache " + kCache);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("1 run(s) already there, 1 to run"), std::string::npos) << r.output;
  if (m["missing_runs"][0] != *shard1.begin()) {
    EXPECT_EQ(fs::last_write_time(d / "s1" / "runs" / *shard1.begin() / "run.json"), first)
        << "a finished run was run again";
  }
  r = run("merge " + (d / "s1").string() + " " + (d / "s2").string() + " --json " +
          (d / "m2.json").string());
  EXPECT_EQ(r.status, 0) << r.output;
  const auto m2 = read_json(d / "m2.json");
  EXPECT_EQ(m2["passed"], 3);
  EXPECT_EQ(m2["missing"], 0);
}

// Ctrl-C (SIGINT to regress alone: the run in flight finishes) once the first record is there:
// regress records every run it did not finish as interrupted, says how to resume and exits
// 128 + 2; merge counts them; --resume runs exactly them.
TEST(Scaleout, SigintRecordsUnfinishedRunsAsInterruptedAndResumeRunsThem) {
  const std::string common =
      " scenes/specular.json scenes/sphere.json scenes/torus.json --backends cpp"
      " --stall-pct 90 --cache " +
      kCache + " -j 1";
  fs::path d;
  std::map<std::string, int> statuses;
  std::string log;
  for (int attempt = 0; attempt < 3 && statuses["interrupted"] == 0; ++attempt) {
    d = temp_dir("scaleout", "sigint" + std::to_string(attempt));
    // The shell keeps regress's pid and, once it ends, its exit status.
    const std::string rc_tmp = (d / "rc.tmp").string();
    in_source("(" + kShadesim + " regress" + common + " --out " + (d / "out").string() + " > " +
              (d / "log").string() + " 2>&1 & echo $! > " + (d / "pid").string() +
              "; wait $!; echo $? > " + rc_tmp + "; mv " + rc_tmp + " " + (d / "rc").string() +
              ") > /dev/null 2>&1 &");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
    const auto records = [&]() {
      size_t n = 0;
      if (fs::is_directory(d / "out" / "runs")) {
        for (const auto& e : fs::directory_iterator(d / "out" / "runs"))
          n += fs::exists(e.path() / "run.json");
      }
      return n;
    };
    while (records() == 0 && !fs::exists(d / "rc") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    pid_t pid = 0;
    std::ifstream(d / "pid") >> pid;
    ASSERT_GT(pid, 0) << "no pid of the regression";
    kill(pid, SIGINT);
    while (!fs::exists(d / "rc") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    statuses.clear();
    for (const auto& e : fs::directory_iterator(d / "out" / "runs")) {
      ASSERT_TRUE(fs::exists(e.path() / "run.json")) << e.path() << ": no record";
      ++statuses[read_json(e.path() / "run.json")["status"].get<std::string>()];
    }
    std::ifstream lf(d / "log");
    log.assign(std::istreambuf_iterator<char>(lf), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(statuses["interrupted"], 0) << log;
  EXPECT_EQ(statuses["pass"] + statuses["interrupted"], 3) << log;
  std::ifstream rc(d / "rc");
  int code = -1;
  rc >> code;
  EXPECT_EQ(code, 130) << log;
  EXPECT_NE(log.find("interrupted by signal 2"), std::string::npos) << log;
  EXPECT_NE(log.find("regress --resume"), std::string::npos) << log;

  Result r = run("merge " + (d / "out").string() + " --json " + (d / "m.json").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(read_json(d / "m.json")["interrupted"], statuses["interrupted"]) << r.output;
  r = run("regress --resume " + (d / "out").string() + " --cache " + kCache);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(std::to_string(statuses["pass"]) + " run(s) already there, " +
                          std::to_string(statuses["interrupted"]) + " to run"),
            std::string::npos)
      << r.output;
}

TEST(Scaleout, TheWatchdogReportsAnRtlThatStopsEmittingAsAHangWithAReplay) {
  const fs::path d = temp_dir("scaleout", "hang");
  // The hang fault: grey_s428w's engines never take a span of row 100, so no pixel leaves
  // after row 99.
  const uint64_t limit = 300;
  Result r = run("cosim --backend cpp --cache " + kCache +
                 " --config grey_s428w --fault hang@100 --scenario short --seed 3 --stall-pct 0"
                 " --watchdog " +
                 std::to_string(limit) + " --save-dir " + d.string() + " --json " +
                 (d / "hang.json").string());
  ASSERT_EQ(r.status, 1) << r.output;
  const auto j = read_json(d / "hang.json");
  ASSERT_EQ(j["first_mismatch"]["kind"], "hang") << j.dump(2);
  EXPECT_EQ(j["first_mismatch"]["y"], 100);
  // Reported the cycle the limit ran out: the last pixel left on cycle `cycles` - 1, then the
  // limit's worth of cycles without pix_valid_o.
  const uint64_t last_pixel = j["cycles"].get<uint64_t>() - 1;
  EXPECT_EQ(j["first_mismatch"]["cycle"].get<uint64_t>(), last_pixel + limit + 1);
  EXPECT_NE(j["first_mismatch"]["message"].get<std::string>().find("no pix_valid_o for " +
                                                                   std::to_string(limit + 1)),
            std::string::npos);
  ASSERT_TRUE(j["replay"].is_string());
  const std::string replay = j["replay"];
  EXPECT_NE(replay.find("--watchdog " + std::to_string(limit)), std::string::npos) << replay;
  EXPECT_NE(replay.find("--config grey_s428w --fault hang@100"), std::string::npos) << replay;
  // The replay command (it names the build cache) reproduces the hang.
  ASSERT_EQ(replay.rfind("shadesim ", 0), 0u);
  EXPECT_NE(replay.find("--cache " + kCache), std::string::npos) << replay;
  r = run(replay.substr(9) + " --save-dir " + (d / "replayed").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("HANG: hang in configuration grey_s428w"), std::string::npos) << r.output;

  // Under regress with the default limit: status hang, a replay line, and the regression fails.
  r = in_source(
      kShadesim +
      " regress scenes/sphere.json --configs grey_s428w --fault hang@100 --backends cpp --cache " +
      kCache + " --out " + (d / "regress").string() + " --json " + (d / "regress.json").string());
  EXPECT_EQ(r.status, 1) << r.output;
  const auto reg = read_json(d / "regress.json");
  ASSERT_EQ(reg["jobs"].size(), 1u);
  EXPECT_EQ(reg["jobs"][0]["status"], "hang") << reg.dump(2);
  EXPECT_EQ(reg["hangs"], 1);
  EXPECT_NE(
      reg["jobs"][0]["replay"].get<std::string>().find("--config grey_s428w --fault hang@100"),
      std::string::npos);
  EXPECT_NE(r.output.find("replay: shadesim cosim"), std::string::npos) << r.output;
}

TEST(Scaleout, ARunPastItsTimeoutIsKilledAndReportedWithAReplay) {
  const fs::path d = temp_dir("scaleout", "timeout");
  const Result r =
      in_source(kShadesim +
                " regress scenes/sphere.json --backends cpp --stall-pct 99 --timeout 0.05"
                " --cache " +
                kCache + " --out " + (d / "out").string() + " --json " + (d / "r.json").string());
  EXPECT_EQ(r.status, 1) << r.output;
  const auto j = read_json(d / "r.json");
  ASSERT_EQ(j["jobs"].size(), 1u);
  EXPECT_EQ(j["jobs"][0]["status"], "timeout") << j.dump(2);
  EXPECT_EQ(j["timeouts"], 1);
  EXPECT_NE(j["jobs"][0]["message"].get<std::string>().find("killed after 0.05 s"),
            std::string::npos);
  EXPECT_NE(j["jobs"][0]["replay"].get<std::string>().find("--stall-pct 99"), std::string::npos);
  // Its record was written as it ended: merge sees the timeout, not a missing run.
  const Result m = run("merge " + (d / "out").string());
  EXPECT_EQ(m.status, 1);
  EXPECT_NE(m.output.find("timeout: sphere__own_sphere__cpp__seed1"), std::string::npos)
      << m.output;
}

#endif  // SHADESIM_HAVE_RTL

}  // namespace
}  // namespace shadesim
