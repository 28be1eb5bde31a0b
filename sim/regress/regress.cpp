// shadesim regress's engine (its options: sim/cli/regress.cpp): the main job. Every scene x
// configuration x simulation backend: the host encodes the scene for the configuration's unit,
// shadesim builds the configuration's RTL on demand (sim/eda/verilator/rtl_build.h) and its
// co-simulation executable replays the stream against the bit-accurate model and the cycle model;
// this command collects, tabulates and reports.
//
// By default each scene runs on its own configuration (the smallest unit that shades it); the
// named builds (sim/harness/builds.json) with --configs, any other unit with --config FILE.json.
//
// Beyond one machine (README "Regression on many machines"): the job list is fixed before any
// run (scenes x configurations x backends, seeds numbered in that order), so --shard I/N and
// --emit-jobs FILE split it the same way on every host; each run writes its record into its own
// folder as soon as it ends (sim/regress/regress_results.h), --resume DIR runs only what is not
// there, and `shadesim merge` puts the folders back together.
#include "sim/regress/regress.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "derive/derive_config.h"
#include "host/frame.h"
#include "model/text_file.h"
#include "sim/eda/common/process.h"
#include "sim/eda/verilator/coverage.h"
#include "sim/eda/verilator/replay.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/eda/yosys/unit_netlist.h"
#include "sim/engines/fixed_text.h"
#include "sim/engines/unit_choice.h"
#include "sim/harness/random_stream.h"
#include "sim/regress/interrupt.h"
#include "sim/regress/regress_results.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

struct Shard {
  int index = 1, count = 1;  // 1-based, as Slurm's array task ids are
};

Shard parse_shard(const std::string& text) {
  const std::string expected = "--shard '" + text + "': expected I/N with 1 <= I <= N, e.g. 2/3";
  const auto slash = text.find('/');
  if (slash == std::string::npos) throw std::invalid_argument(expected);
  Shard s;
  try {
    size_t used_i = 0, used_n = 0;
    const std::string i = text.substr(0, slash), n = text.substr(slash + 1);
    s.index = std::stoi(i, &used_i);
    s.count = std::stoi(n, &used_n);
    if (used_i != i.size() || used_n != n.size()) throw std::invalid_argument(expected);
  } catch (const std::logic_error&) {
    throw std::invalid_argument(expected);
  }
  if (s.count < 1 || s.index < 1 || s.index > s.count) throw std::invalid_argument(expected);
  return s;
}

// The stimulus and run limits a plan fixes; every process running part of it uses the same.
struct RunSettings {
  int gap_pct = kRegressStimulus.gap_pct, max_gap = kRegressStimulus.max_gap,
      stall_pct = kRegressStimulus.stall_pct;
  double timeout = 1800;
  uint64_t watchdog = 0;
  std::string fault;  // SITE@Y or empty (sim/harness/fault_site.h)
};

nlohmann::json settings_json(const RunSettings& s) {
  nlohmann::json j = {{"gap_pct", s.gap_pct},
                      {"max_gap", s.max_gap},
                      {"stall_pct", s.stall_pct},
                      {"timeout", s.timeout},
                      {"watchdog", s.watchdog}};
  if (!s.fault.empty()) j["fault"] = s.fault;  // plans without it stay as they were
  return j;
}

struct Job {
  RunSpec spec;
  RtlConfig build;
  std::string executable;  // the build's co-simulation executable
  std::string unit_path;   // the unit as JSON, for --unit
  RunRecord rec;
};

void save_record(const Job& j);

RtlBuildOptions build_options(const RegressOptions& o) {
  RtlBuildOptions b;
  b.cache_dir = o.cache;
  b.make_jobs = 1;  // builds run side by side
  b.coverage = o.coverage;
  return b;
}

fs::path run_dir(const fs::path& out, const RunSpec& s) { return out / "runs" / s.id(); }

// --netlist: each configuration's gate-level netlist (sim/eda/yosys/unit_netlist.h),
// synthesised in the background while the host sets up the scenes, at most `workers` Yosys runs at
// once.
class NetlistSource {
 public:
  NetlistSource(const RegressOptions& o, int workers) : workers_(std::max(1, workers)) {
    options_.cache_dir = o.netlist_cache.empty() ? default_netlist_cache_dir() : o.netlist_cache;
  }
  // Starts (once per unit) the netlist of `unit`; the token names it for get().
  std::string start(const UnitConfig& unit) {
    const std::string token = config_to_json(unit);
    std::lock_guard<std::mutex> lock(m_);
    if (!jobs_.count(token)) {
      jobs_.emplace(token, std::async(std::launch::async, [this, unit] {
                             Slot slot(*this);
                             return unit_netlist(unit, options_);
                           }).share());
    }
    return token;
  }
  // The netlist `token` names (waits for it); throws what its synthesis threw.
  UnitNetlist get(const std::string& token) {
    std::shared_future<UnitNetlist> f;
    {
      std::lock_guard<std::mutex> lock(m_);
      f = jobs_.at(token);
    }
    return f.get();
  }

 private:
  struct Slot {  // one of `workers_` Yosys slots
    explicit Slot(NetlistSource& s) : s(s) {
      std::unique_lock<std::mutex> lock(s.slots_m_);
      s.free_.wait(lock, [&] { return s.running_ < s.workers_; });
      ++s.running_;
    }
    ~Slot() {
      {
        std::lock_guard<std::mutex> lock(s.slots_m_);
        --s.running_;
      }
      s.free_.notify_one();
    }
    NetlistSource& s;
  };
  NetlistOptions options_;
  int workers_;
  std::mutex m_, slots_m_;
  std::condition_variable free_;
  int running_ = 0;
  std::map<std::string, std::shared_future<UnitNetlist>> jobs_;
};

// Replaces each pending job's netlist token by the netlist's path (an error for the job when
// Yosys failed), and says what each netlist is.
void resolve_netlists(std::vector<Job>& jobs, NetlistSource& netlists) {
  std::set<std::string> told;
  for (auto& j : jobs) {
    if (j.build.netlist.empty()) continue;
    const std::string token = j.build.netlist;
    j.build.netlist.clear();
    if (j.rec.status != "pending") continue;
    try {
      const UnitNetlist n = netlists.get(token);
      j.build.netlist = n.path;
      j.rec.unit_text += " [gate-level netlist, " + std::to_string(n.gate_equivalents) + " GE]";
      if (told.insert(n.path).second) {
        std::cout << "regress: netlist of " << j.build.name << ": " << n.path << " (" << n.cells
                  << " cells, " << n.flip_flops << " flip-flops, " << n.gate_equivalents << " GE"
                  << (n.ram_bits ? ", " + std::to_string(n.ram_bits) + " table RAM bits" : "")
                  << "; " << (n.from_cache ? "cached, Yosys took " : "Yosys ") << std::fixed
                  << std::setprecision(1) << n.seconds << " s" << std::defaultfloat << ")"
                  << std::endl;
      }
    } catch (const std::exception& e) {
      j.rec.status = "error";
      j.rec.message = std::string("netlist synthesis failed: ") + e.what();
      save_record(j);
    }
  }
}

// A path of a plan, from the folder the plan was made in.
std::string from_base(const fs::path& base, const std::string& path) {
  return base.empty() || fs::path(path).is_absolute() ? path : (base / path).string();
}

// `origin`: for an own unit, whether it was derived now or reused (own_unit).
RtlConfig resolve_config(const RunSpec& s, const fs::path& base, std::string* origin) {
  if (s.config_kind == kOwnUnit) return own_unit(from_base(base, s.scene), origin);
  if (s.config_kind == kDefaultUnit) return resolve_unit(kDefaultUnit, from_base(base, s.scene));
  if (s.config_kind == "named") return named_build(named_builds_path(), s.config);
  return resolve_rtl_config(from_base(base, s.config), "--config");
}

// Whether any material of the stream lights a specular term (a build with no specular hardware
// cannot match the model there).
bool has_highlights(const CommandStream& stream) {
  for (const auto& cmd : stream.commands) {
    if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
      for (auto v : m->spec_colour)
        if (v != 0) return true;
    }
  }
  return false;
}

std::vector<std::string> default_scenes() {
  // Run from the project folder, the shipped scenes are ./scenes; elsewhere, the checkout's.
  fs::path dir = "scenes";
  if (!fs::is_directory(dir)) dir = fs::path(source_dir()) / "scenes";
  if (!fs::is_directory(dir)) {
    throw std::invalid_argument("regress: no scene files given, and neither ./scenes nor " +
                                dir.string() +
                                " exists; name scene files, or run from the project folder");
  }
  std::vector<std::string> scenes;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".json") scenes.push_back(e.path().string());
  }
  std::sort(scenes.begin(), scenes.end());
  if (scenes.empty())
    throw std::invalid_argument("regress: no scenes given and none in " + dir.string());
  return scenes;
}

// The whole job list, before any host work: scenes x configurations x backends. Each scene and
// configuration gets the next seed (both backends the same one), so a run's seed depends only on
// its place in this list, never on what another run found.
std::vector<RunSpec> full_run_list(const RegressOptions& o,
                                   const std::vector<std::string>& scenes) {
  std::vector<std::pair<std::string, std::string>> configs;  // kind, name
  for (const auto& name : o.configs) {
    named_build(named_builds_path(), name);  // an unknown name fails here, listing the names
    configs.push_back({"named", name});
  }
  for (const auto& text : o.config_files) {  // --config: own | default | NAME | FILE.json
    if (text == kOwnUnit || text == kDefaultUnit) {
      configs.push_back({text, text});
    } else if (fs::path(text).extension() == ".json") {
      resolve_rtl_config(text, "--config");  // an unreadable file fails here, naming the field
      configs.push_back({"file", text});
    } else {
      named_build(named_builds_path(), text);
      configs.push_back({"named", text});
    }
  }
  if (configs.empty()) configs.push_back({kOwnUnit, kOwnUnit});
  std::vector<RunSpec> runs;
  uint64_t seed = o.seed;
  for (const auto& scene : scenes) {
    for (auto [kind, name] : configs) {
      if (kind == kOwnUnit) name = std::string(kOwnUnit) + ":" + fs::path(scene).stem().string();
      for (const auto& b : o.backends) runs.push_back({scene, kind, name, b, seed});
      ++seed;
    }
  }
  // --random: after every scene run, each scenario on each configuration that is a unit without a
  // scene (a named build or a FILE.json; own and default are derived from a scene), seeds
  // numbered on.
  for (const auto& scenario : o.random) {
    for (const auto& [kind, name] : configs) {
      if (kind == kOwnUnit || kind == kDefaultUnit) continue;
      for (const auto& b : o.backends)
        runs.push_back({kRandomScenePrefix + scenario, kind, name, b, seed});
      ++seed;
    }
  }
  return runs;
}

// What a regress process was asked to run, written into OUT/plans/ before it runs anything:
// merge compares it with the results to name what is missing; --resume runs the rest of it.
void write_plan(const fs::path& out, const std::string& name, const RunSettings& settings,
                const std::string& shard, const std::vector<RunSpec>& all,
                const std::vector<RunSpec>& selected) {
  nlohmann::json runs = nlohmann::json::array(), ids = nlohmann::json::array();
  for (const auto& s : all) runs.push_back(spec_json(s));
  for (const auto& s : selected) ids.push_back(s.id());
  // Relative scene and config paths are relative to the folder regress ran in: --resume from
  // anywhere finds them there.
  const nlohmann::json plan = {{"tool", "shadesim regress"},
                               {"shard", shard.empty() ? nlohmann::json() : nlohmann::json(shard)},
                               {"cwd", fs::current_path().string()},
                               {"settings", settings_json(settings)},
                               {"runs", runs},
                               {"selected", ids}};
  write_file_atomically((out / "plans" / (name + ".json")).string(), plan.dump(2) + '\n');
}

struct LoadedPlans {
  RunSettings settings;
  std::vector<RunSpec> selected;
  fs::path base;  // the folder the plans' relative paths are relative to
};

// --resume DIR: the runs DIR's plans selected, with their settings (which must agree).
LoadedPlans load_plans(const fs::path& dir) {
  if (!fs::is_directory(dir))
    throw std::invalid_argument("--resume " + dir.string() + ": no such folder");
  if (!fs::is_directory(dir / "plans")) {
    throw std::invalid_argument("--resume " + dir.string() +
                                ": not a regress output folder (it has no plans/ folder)");
  }
  LoadedPlans lp;
  std::string settings_from;
  std::set<std::string> seen;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir / "plans")) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw std::invalid_argument("--resume " + dir.string() + ": plans/ holds no plan (*.json)");
  for (const auto& f : files) {
    nlohmann::json j;
    try {
      std::ifstream is(f);
      j = nlohmann::json::parse(is);
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(f.string() + ": not valid JSON (" + e.what() + ")");
    }
    if (!j.is_object() || !j.contains("settings") || !j.contains("runs") ||
        !j.contains("selected")) {
      throw std::invalid_argument(f.string() +
                                  ": expected a regress plan with settings, runs and selected");
    }
    RunSettings s;
    try {
      const auto& js = j.at("settings");
      s.gap_pct = js.at("gap_pct").get<int>();
      s.max_gap = js.at("max_gap").get<int>();
      s.stall_pct = js.at("stall_pct").get<int>();
      s.timeout = js.at("timeout").get<double>();
      s.watchdog = js.at("watchdog").get<uint64_t>();
      if (js.contains("fault")) s.fault = js.at("fault").get<std::string>();
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(f.string() + ": settings: " + e.what());
    }
    if (settings_from.empty()) {
      lp.settings = s;
      if (j.contains("cwd") && j.at("cwd").is_string()) lp.base = j.at("cwd").get<std::string>();
      settings_from = f.string();
    } else if (settings_json(s) != settings_json(lp.settings)) {
      throw std::invalid_argument(f.string() + ": its settings " + settings_json(s).dump() +
                                  " differ from " + settings_from + "'s " +
                                  settings_json(lp.settings).dump());
    }
    std::map<std::string, RunSpec> by_id;
    for (size_t i = 0; i < j.at("runs").size(); ++i) {
      const RunSpec spec =
          spec_from_json(j.at("runs")[i], f.string() + ": runs[" + std::to_string(i) + "]");
      by_id[spec.id()] = spec;
    }
    for (const auto& id : j.at("selected")) {
      const auto it = by_id.find(id.is_string() ? id.get<std::string>() : std::string());
      if (it == by_id.end())
        throw std::invalid_argument(f.string() + ": selected run " + id.dump() + " is not in runs");
      if (seen.insert(it->first).second) lp.selected.push_back(it->second);
    }
  }
  return lp;
}

// A number as a person writes it: 1800, 0.5.
std::string number_text(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// This shadesim, as a path that works from the current folder on every host with the same
// checkout: relative when it is below the current folder, absolute otherwise.
std::string self_path() {
  const fs::path self = self_executable("--emit-jobs");
  std::error_code ec;
  const fs::path rel = fs::relative(self, fs::current_path(), ec);
  if (!ec && !rel.empty() && *rel.begin() != "..") return rel.string();
  return self.string();
}

// One self-contained command per run: it plans exactly that run (one scene, one configuration,
// one backend, its seed) into the same OUT/runs/<id>/ the whole regression would use.
void emit_jobs(const RegressOptions& o, const RunSettings& settings, const fs::path& out,
               const std::vector<RunSpec>& all, const std::vector<RunSpec>& selected) {
  const std::string exe = self_path();
  std::ostringstream lines;
  for (const auto& s : selected) {
    std::vector<std::string> a = {"cd", fs::current_path().string(), "&&", exe, "regress"};
    if (is_random_scene(s.scene))
      a.insert(a.end(), {"--random-only", "--random", random_scenario(s.scene)});
    else
      a.push_back(s.scene);
    if (s.config_kind == "named") a.insert(a.end(), {"--configs", s.config});
    if (s.config_kind == "file" || s.config_kind == kDefaultUnit)
      a.insert(a.end(), {"--config", s.config});
    a.insert(a.end(),
             {"--backends", s.backend, "--seed", std::to_string(s.seed), "--gap-pct",
              std::to_string(settings.gap_pct), "--max-gap", std::to_string(settings.max_gap),
              "--stall-pct", std::to_string(settings.stall_pct), "--timeout",
              number_text(settings.timeout), "--jobs", "1", "--out", out.string()});
    if (settings.watchdog > 0) a.insert(a.end(), {"--watchdog", std::to_string(settings.watchdog)});
    if (!settings.fault.empty()) a.insert(a.end(), {"--fault", settings.fault});
    if (!o.cache.empty()) a.insert(a.end(), {"--cache", o.cache});
    if (o.waves) a.push_back("--waves");
    if (o.coverage) a.push_back("--coverage");  // each line's run writes its coverage.dat
    if (o.netlist) a.push_back("--netlist");
    if (o.netlist && !o.netlist_cache.empty())
      a.insert(a.end(), {"--netlist-cache", o.netlist_cache});
    std::string line;
    for (const auto& w : a) line += (line.empty() ? "" : " ") + (w == "&&" ? w : shell_word(w));
    lines << line << '\n';
  }
  write_text_file(o.emit_jobs, lines.str());
  // Every line's run is planned, so merge names a line that never ran.
  write_plan(out, "emitted", settings, "", all, selected);
  std::cout << "regress: wrote " << selected.size() << " job line(s) to " << o.emit_jobs
            << " (results into " << (out / "runs").string()
            << "/<scene>__<config>__<backend>__seed<S>/)\n"
            << "  run them:  parallel -j 8 < " << o.emit_jobs << "\n"
            << "  then:      shadesim merge " << out.string()
            << " --json merged.json --junit merged.xml\n";
}

void save_record(const Job& j) {
  write_file_atomically((fs::path(j.rec.dir) / "run.json").string(),
                        record_json(j.rec).dump(2) + '\n');
}

// The replay command for a run the harness gave none for (a timeout, a crash).
std::string replay_command(const Job& j, const RunSettings& settings, const RegressOptions& o) {
  std::string cmd = cosim_replay_prefix(j.spec.backend, o.cache, o.netlist, o.netlist_cache);
  if (j.spec.config_kind == "named" || j.spec.config_kind == "file")
    cmd += " --config " + j.spec.config;
  cmd += " --stream " + j.rec.stream + " --seed " + std::to_string(j.spec.seed) + " --gap-pct " +
         std::to_string(settings.gap_pct) + " --max-gap " + std::to_string(settings.max_gap) +
         " --stall-pct " + std::to_string(settings.stall_pct);
  if (settings.watchdog > 0) cmd += " --watchdog " + std::to_string(settings.watchdog);
  if (!settings.fault.empty()) cmd += " --fault " + settings.fault;
  return cmd;
}

// An upper estimate of the cycles a run of `pixels` pixels simulates: under the regression's gaps
// and back-pressure a pixel takes under 2 cycles on every shipped unit (1.28-1.49); 4 leaves room
// for slow specular units.
uint64_t expected_cycles(uint64_t pixels) { return 4 * pixels; }

// The optimisation of a build whose runs simulate `cycles` (--opt, else by their length).
RtlOptimization build_optimization(const RegressOptions& o, uint64_t cycles) {
  return o.optimization.empty() ? choose_optimization(cycles, o.coverage)
                                : parse_rtl_optimization(o.optimization);
}

// Host side: encode each scene for each configuration, into each of its runs' folders. One scene
// and configuration at a time (mesh import limits the process's address space while it runs, so
// it is not done on several threads at once). A run the scene does not fit is skipped, one the
// host cannot prepare is an error; either is recorded at once.
// `prefetch` starts each configuration's Verilation as soon as its first run is set up (its
// length says whether the build checks the SVA: checks_assertions), beside the host setup of
// the scenes that follow.
std::vector<Job> plan_jobs(const std::vector<RunSpec>& specs, const fs::path& out,
                           const fs::path& base, RtlPrefetch& prefetch, NetlistSource* netlists,
                           const RegressOptions& o, const RunSettings& settings) {
  std::vector<Job> jobs;
  std::map<std::string, size_t> first_of_pair;  // scene + config -> its first job
  for (const auto& spec : specs) {
    Job j;
    j.spec = spec;
    j.rec.spec = spec;
    j.rec.scene_name = scene_label(spec.scene);
    j.rec.dir = run_dir(out, spec).string();
    j.rec.stream = (fs::path(j.rec.dir) / "stream.cmds").string();
    j.unit_path = (fs::path(j.rec.dir) / "unit.json").string();
    fs::create_directories(j.rec.dir);
    const std::string pair = spec.scene + '\n' + spec.config + '\n' + std::to_string(spec.seed);
    const auto done = first_of_pair.find(pair);
    if (done != first_of_pair.end()) {
      // The pair's other backend: the same unit and stream.
      const Job& twin = jobs[done->second];
      j.build = twin.build;
      if (twin.rec.status == "pending" && !netlists) {
        prefetch.add(j.build, parse_cosim_backend(spec.backend),
                     build_optimization(o, expected_cycles(twin.rec.pixels)));
      }
      j.rec.unit = twin.rec.unit;
      j.rec.unit_text = twin.rec.unit_text;
      j.rec.pixels = twin.rec.pixels;
      j.rec.status = twin.rec.status;
      j.rec.message = twin.rec.message;
      if (j.rec.status == "pending") {
        fs::copy_file(twin.rec.stream, j.rec.stream, fs::copy_options::overwrite_existing);
        fs::copy_file(twin.unit_path, j.unit_path, fs::copy_options::overwrite_existing);
      }
    } else {
      first_of_pair[pair] = jobs.size();
      try {
        std::string origin;
        j.build = build_for_run(resolve_config(spec, base, &origin), !settings.fault.empty());
        j.build.name = spec.config;
        if (netlists) {
          // A token until resolve_netlists (the build's key needs the netlist's contents).
          j.build.netlist = netlists->start(j.build.unit);
        }
        j.rec.unit = nlohmann::json::parse(config_to_json(j.build.unit));
        j.rec.unit_text = j.build.unit.to_string() + fault_text(j.build.faults);
        if (!origin.empty()) j.rec.unit_text += "  (" + origin + ")";
        std::ofstream(j.unit_path) << config_to_json(j.build.unit) << '\n';
        FrameOptions fo;
        fo.base = j.build.unit;
        fo.fixed_unit = true;
        if (is_random_scene(spec.scene)) {
          // The co-simulation's random stream for this unit and seed, saved like a scene's.
          const CommandStream s = random_stream(
              j.build.unit, scenario_by_name(random_scenario(spec.scene)).shape, spec.seed);
          for (const auto& cmd : s.commands) {
            if (const auto* span = std::get_if<SpanCmd>(&cmd))
              j.rec.pixels += static_cast<uint64_t>(span->length);
          }
          s.save(j.rec.stream);
        } else {
          try {
            const PreparedFrame f = prepare_frame(from_base(base, spec.scene), fo);
            j.rec.pixels = f.encoded.stats.pixels;
            if (j.build.unit.specular.kind == SpecularUnitKind::kIdeal &&
                has_highlights(f.encoded.stream)) {
              j.rec.status = "skipped";
              j.rec.message = "configuration " + spec.config +
                              " has no specular hardware (the ideal unit's RTL slot outputs 0) "
                              "and the scene has highlights: its pixels cannot match the model";
            } else {
              f.encoded.stream.save(j.rec.stream);
            }
          } catch (const std::invalid_argument& e) {
            j.rec.status = "skipped";  // the scene needs more than this build has (lights,
                                       // channels, coordinates)
            j.rec.message = e.what();
          }
        }
        if (j.rec.status == "pending" && !netlists) {
          prefetch.add(j.build, parse_cosim_backend(spec.backend),
                       build_optimization(o, expected_cycles(j.rec.pixels)));
        }
      } catch (const std::exception& e) {
        j.rec.status = "error";
        j.rec.message = std::string("host setup failed: ") + e.what();
      }
    }
    if (j.rec.status != "pending") save_record(j);
    jobs.push_back(j);
  }
  return jobs;
}

// Runs `work(i)` for i in [0, n) on `workers` threads.
template <typename F>
void parallel_for(size_t n, int workers, F work) {
  std::atomic<size_t> next{0};
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) {
    pool.emplace_back([&]() {
      for (size_t i = next++; i < n; i = next++) work(i);
    });
  }
  for (auto& t : pool) t.join();
}

// Every (configuration, backend) the pending jobs need, built once; a job whose build failed is
// an error (recorded at once).
void build_all(std::vector<Job>& jobs, const RegressOptions& o, int workers) {
  struct Need {
    RtlConfig build;
    CosimBackend backend;
    std::string key, executable, error;
    uint64_t cycles = 0;  // an upper estimate of what its runs simulate
  };
  std::vector<Need> needs;
  for (auto& j : jobs) {
    if (j.rec.status != "pending") continue;
    const CosimBackend be = parse_cosim_backend(j.spec.backend);
    const std::string key = rtl_build_key(j.build, be, o.coverage, o.cache);
    auto it = std::find_if(needs.begin(), needs.end(), [&](const Need& n) { return n.key == key; });
    if (it == needs.end()) it = needs.insert(needs.end(), {j.build, be, key, "", "", 0});
    it->cycles += expected_cycles(j.rec.pixels);
  }
  std::cout << "regress: " << needs.size() << " RTL build(s) needed (cache: "
            << (o.cache.empty() ? default_rtl_cache_dir() : o.cache) << ")" << std::endl;
  // Fewer builds than workers: each build's compiler runs on the spare cores.
  const int per_build =
      std::max<int>(1, workers / std::max<int>(1, static_cast<int>(needs.size())));
  parallel_for(needs.size(), workers, [&](size_t i) {
    try {
      RtlBuildOptions b = build_options(o);
      b.make_jobs = per_build;
      b.optimization = build_optimization(o, needs[i].cycles);
      needs[i].executable = ensure_rtl_build(needs[i].build, needs[i].backend, b).executable;
    } catch (const std::exception& e) {
      needs[i].error = e.what();
    }
  });
  for (auto& j : jobs) {
    if (j.rec.status != "pending") continue;
    const std::string key =
        rtl_build_key(j.build, parse_cosim_backend(j.spec.backend), o.coverage, o.cache);
    const auto it =
        std::find_if(needs.begin(), needs.end(), [&](const Need& n) { return n.key == key; });
    if (!it->error.empty()) {
      j.rec.status = "error";
      j.rec.message = "RTL build failed: " + it->error;
      save_record(j);
      continue;
    }
    j.executable = it->executable;
  }
}

// A field of a result file, or `fallback` when it is absent or null.
template <typename T>
T field(const nlohmann::json& j, const char* key, T fallback) {
  if (!j.is_object() || !j.contains(key) || j.at(key).is_null()) return fallback;
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    return fallback;
  }
}

// Runs one job's co-simulation as a child process; fills its record from the child's JSON.
// The co-simulation child's command line for one run: its unit, stream, stimulus, outputs.
std::vector<std::string> cosim_child_args(const Job& job, const RegressOptions& o,
                                          const RunSettings& settings, const fs::path& dir,
                                          const fs::path& result_path) {
  std::vector<std::string> args = {job.executable,
                                   "--unit",
                                   job.unit_path,
                                   "--config",
                                   job.spec.config,
                                   "--stream",
                                   job.rec.stream,
                                   "--seed",
                                   std::to_string(job.spec.seed),
                                   "--gap-pct",
                                   std::to_string(settings.gap_pct),
                                   "--max-gap",
                                   std::to_string(settings.max_gap),
                                   "--stall-pct",
                                   std::to_string(settings.stall_pct),
                                   "--save-dir",
                                   (dir / "failing").string()};
  if (settings.watchdog > 0)
    args.insert(args.end(), {"--watchdog", std::to_string(settings.watchdog)});
  if (!settings.fault.empty()) args.insert(args.end(), {"--fault", settings.fault});
  args.insert(args.end(), {"--replay-prefix", cosim_replay_prefix(job.spec.backend, o.cache,
                                                                  o.netlist, o.netlist_cache)});
  if (o.coverage) {
    // Written by the run itself, pass or fail; a resumed run must not keep an earlier attempt's.
    const fs::path dat = dir / "coverage.dat";
    fs::remove(dat);
    args.insert(args.end(), {"--coverage", dat.string()});
  }
  args.insert(args.end(), {"--json", result_path.string()});
  return args;
}

// A mismatching C++ run is re-run on a traced build to draw the failing window (--waves).
void record_waves(const Job& job, const RegressOptions& o, const RunSettings& settings,
                  std::vector<std::string> args, RunRecord& rec) {
  const fs::path dir(rec.dir);
  const fs::path fst = dir / "waves.fst";
  RtlBuildOptions traced = build_options(o);
  traced.coverage = false;  // the traced re-run only draws the window; its coverage is the run's
  args[0] = ensure_rtl_build(job.build, CosimBackend::kCppTrace, traced).executable;
  const auto cov = std::find(args.begin(), args.end(), "--coverage");
  if (cov != args.end()) args.erase(cov, cov + 2);
  args.back() = (dir / "waves.json").string();
  args.push_back("--waves");
  args.push_back(fst.string());
  run_process(args, (dir / "waves.log").string(), settings.timeout);
  if (fs::exists(fst)) rec.waves = fst.string();
}

void run_job(Job& job, const RegressOptions& o, const RunSettings& settings) {
  RunRecord& rec = job.rec;
  const fs::path dir(rec.dir);
  const fs::path result_path = dir / "cosim.json";
  fs::remove(result_path);  // a resumed run must not read the result of an earlier attempt
  rec.log = (dir / "cosim.log").string();
  const std::vector<std::string> args = cosim_child_args(job, o, settings, dir, result_path);
  // The children are SystemC programs too: keep their logs free of its banner; their replay
  // lines name the stream, which carries its unit.
  const auto t0 = std::chrono::steady_clock::now();
  const ProcessResult r = run_process(args, rec.log, settings.timeout);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (r.timed_out) {
    rec.status = "timeout";
    rec.seconds = wall;
    rec.message =
        "killed after " + number_text(settings.timeout) + " s (--timeout); log: " + rec.log;
    rec.replay = replay_command(job, settings, o);
    return;
  }
  nlohmann::json j;
  try {
    std::ifstream is(result_path);
    if (is) j = nlohmann::json::parse(is);
  } catch (const nlohmann::json::exception&) {
    j = nlohmann::json();
  }
  rec.cycles = field(j, "cycles", uint64_t{0});
  rec.seconds = field(j, "seconds", 0.0);
  rec.cycles_per_second = field(j, "cycles_per_second", 0.0);
  rec.replay = field(j, "replay", std::string());
  // A run that shaded nothing compared nothing: it is not a pass (issue 23; the co-simulation
  // exits 1 for it, with no mismatch to name).
  if ((r.exit_code == 0 || r.exit_code == 1) && field(j, "passed", false) &&
      (rec.cycles == 0 || field(j, "pixels", uint64_t{0}) == 0)) {
    rec.status = "error";
    rec.message = "the run shaded " + std::to_string(field(j, "pixels", uint64_t{0})) +
                  " pixels in " + std::to_string(rec.cycles) +
                  " cycles: nothing was compared (an empty image?), so it does not count as a pass";
    return;
  }
  if (r.exit_code == 0 && field(j, "passed", false)) {
    rec.status = "pass";
    return;
  }
  if (r.exit_code == 1 && j.is_object()) {
    const nlohmann::json first = field(j, "first_mismatch", nlohmann::json::object());
    rec.status = field(first, "kind", std::string()) == "hang" ? "hang" : "mismatch";
    rec.message = field(first, "message", std::string("mismatch (the result names none)"));
    if (o.waves && job.spec.backend == "cpp") record_waves(job, o, settings, args, rec);
    return;
  }
  rec.status = "error";
  if (rec.replay.empty()) rec.replay = replay_command(job, settings, o);
  // The last non-empty line of the log says why; the whole log is kept beside the results.
  std::ifstream log(rec.log);
  std::string line, last;
  while (std::getline(log, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  rec.message = "co-simulation exited with " + std::to_string(r.exit_code) + ": " + last +
                " (log: " + rec.log + ")";
}

// Runs the pending jobs; each writes its record the moment it ends, so a killed regression keeps
// every finished run.
void run_jobs(std::vector<Job>& jobs, const RegressOptions& o, const RunSettings& settings,
              int workers) {
  std::atomic<size_t> done{0};
  std::mutex print_mutex;
  parallel_for(jobs.size(), workers, [&](size_t i) {
    Job& j = jobs[i];
    if (j.rec.status == "pending") {
      if (InterruptGuard::requested()) {
        j.rec.status = "interrupted";
        j.rec.message = "not run: the regression got signal " +
                        std::to_string(InterruptGuard::signal_number()) +
                        " before it started (--resume runs it)";
      } else {
        try {
          run_job(j, o, settings);
        } catch (const std::exception& e) {
          j.rec.status = "error";
          j.rec.message = e.what();
        }
        // A run that failed after the signal (which reaches the simulator too) was stopped by
        // it, not by the RTL.
        if (j.rec.status != "pass" && InterruptGuard::requested()) {
          j.rec.message = "stopped by signal " + std::to_string(InterruptGuard::signal_number()) +
                          " (--resume runs it again): " + j.rec.message;
          j.rec.status = "interrupted";
        }
      }
      try {
        save_record(j);
      } catch (const std::exception& e) {
        j.rec.status = "error";
        j.rec.message += std::string(" (and its record could not be written: ") + e.what() + ")";
      }
    }
    const size_t n = ++done;
    const RunRecord& r = j.rec;
    std::lock_guard<std::mutex> lock(print_mutex);
    std::cout << "[" << n << "/" << jobs.size() << "] " << r.spec.id() << ": " << r.status << ", "
              << r.cycles << " cycles, " << fixed_text(r.seconds, 2) << " s";
    if (r.status != "pass")
      std::cout << "\n    " << r.message << (r.replay.empty() ? "" : "\n    replay: " + r.replay);
    if (!r.waves.empty()) std::cout << "\n    waves: " << r.waves;
    std::cout << std::endl;
  });
}

void list_named_builds() {
  for (const auto& c : load_named_builds(named_builds_path())) {
    std::string backends;
    for (const auto& b : c.backends) backends += (backends.empty() ? "" : ",") + b;
    std::cout << std::left << std::setw(18) << c.name << std::setw(13) << backends
              << c.unit.to_string() << (c.faults.any() ? "  (injected fault)" : "") << '\n';
  }
}

// What one regress process runs: the selected runs (and, with --resume, the results already
// there), where results go and the settings every run uses.
struct Selection {
  std::vector<std::string> scenes;  // a new plan: its scenes and whole job list
  std::vector<RunSpec> all;
  std::vector<RunSpec> selected;
  std::vector<RunRecord> earlier;  // --resume: results already there
  fs::path out;
  fs::path base;  // --resume: where the plan's relative paths start
  RunSettings settings;
};

// --resume DIR: the runs DIR's plans name that have no result there (or ended in an error).
Selection select_resumed(const RegressOptions& o) {
  if (!o.scenes.empty() || !o.configs.empty() || !o.config_files.empty() || !o.shard.empty() ||
      !o.emit_jobs.empty() || !o.random.empty()) {
    throw std::invalid_argument(
        "--resume " + o.resume + " takes its runs and settings from " + o.resume +
        "/plans/; give no scenes, --configs, --config, --random, --shard or --emit-jobs with it");
  }
  Selection sel;
  sel.out = o.resume;
  const LoadedPlans plans = load_plans(sel.out);
  sel.settings = plans.settings;
  sel.base = plans.base;
  for (const auto& spec : plans.selected) {
    const fs::path record = run_dir(sel.out, spec) / "run.json";
    if (fs::exists(record)) {
      try {
        RunRecord r = read_run_record(record.string());
        // An error may be the machine's, an interrupted run never finished: run them again.
        if (r.status != "error" && r.status != "interrupted") {
          sel.earlier.push_back(r);
          continue;
        }
      } catch (const std::exception& e) {
        std::cout << "regress: " << e.what() << ": running it again" << std::endl;
      }
    }
    sel.selected.push_back(spec);
  }
  std::cout << "regress: resuming " << sel.out.string() << ": " << sel.earlier.size()
            << " run(s) already there, " << sel.selected.size() << " to run" << std::endl;
  return sel;
}

// Scenes x configurations x backends, and the runs of this process's shard of it.
Selection select_planned(const RegressOptions& o) {
  Selection sel;
  sel.out = o.out_dir;
  sel.settings = RunSettings{o.gap_pct, o.max_gap, o.stall_pct, o.timeout, o.watchdog, o.fault};
  if (!o.random_only) sel.scenes = o.scenes.empty() ? default_scenes() : o.scenes;
  sel.all = full_run_list(o, sel.scenes);
  if (!o.random.empty() && std::none_of(sel.all.begin(), sel.all.end(), [](const RunSpec& r) {
        return is_random_scene(r.scene);
      })) {
    throw std::invalid_argument(
        "--random: no configuration to run it on: a random stream needs a unit without a scene, "
        "a named build (--configs, --config NAME) or a UnitConfig FILE.json (own and default are "
        "derived from a scene)");
  }
  const Shard shard = o.shard.empty() ? Shard{} : parse_shard(o.shard);
  for (size_t i = 0; i < sel.all.size(); ++i) {
    if (static_cast<int>(i % static_cast<size_t>(shard.count)) == shard.index - 1)
      sel.selected.push_back(sel.all[i]);
  }
  return sel;
}

std::string join(const std::vector<std::string>& words) {
  std::string s;
  for (const auto& w : words) s += (s.empty() ? "" : ", ") + w;
  return s;
}

// The plan, written into OUT/plans/ before anything runs, and what it holds.
void write_and_announce_plan(const RegressOptions& o, const Selection& sel) {
  const Shard shard = o.shard.empty() ? Shard{} : parse_shard(o.shard);
  const std::string plan_name = !o.shard.empty() ? "shard-" + std::to_string(shard.index) + "-of-" +
                                                       std::to_string(shard.count)
                                : sel.all.size() == 1 ? "run-" + sel.all.front().id()
                                                      : "all";
  write_plan(sel.out, plan_name, sel.settings, o.shard, sel.all, sel.selected);
  const bool own = o.configs.empty() && o.config_files.empty();
  std::cout << "regress: seed " << o.seed << ", " << sel.scenes.size() << " scene(s) x "
            << (own ? std::string("its own configuration")
                    : std::to_string(o.configs.size() + o.config_files.size()) +
                          " configuration(s)")
            << " x " << o.backends.size() << " backend(s)"
            << (o.random.empty() ? ""
                                 : "; random scenario(s) " + join(o.random) +
                                       " on each named or file configuration")
            << (o.shard.empty()
                    ? ""
                    : "; shard " + o.shard + ": " + std::to_string(sel.selected.size()) + " of " +
                          std::to_string(sel.all.size()) + " run(s)")
            << std::endl;
}

void print_settings(const Selection& sel, bool coverage) {
  const RunSettings& s = sel.settings;
  std::cout << "regress: stimulus gap " << s.gap_pct << "% (max " << s.max_gap
            << "), back-pressure " << s.stall_pct << "%; per-run timeout "
            << (s.timeout > 0 ? number_text(s.timeout) + " s" : std::string("none"))
            << (coverage ? "; covered builds (line, toggle, user cover points)" : "")
            << "; results in " << (sel.out / "runs").string() << std::endl;
}

// Every run's record, the earlier ones (--resume) first, in job-list order.
std::vector<RunRecord> collect_records(const std::vector<RunRecord>& earlier,
                                       const std::vector<Job>& jobs) {
  std::vector<RunRecord> records = earlier;
  for (const auto& j : jobs) records.push_back(j.rec);
  sort_records(records);
  check_backends_agree(records);
  return records;
}

// The table, the counts and the --junit / --json files.
RunCounts report_runs(const std::vector<RunRecord>& records, const RegressOptions& o, double wall,
                      int workers) {
  print_run_table(records);
  const RunCounts c = count_runs(records);
  std::cout << "\nregress: " << c.passed << " passed, " << c.mismatched << " mismatched, "
            << c.hangs << " hung, " << c.timeouts << " timed out, " << c.errors << " error(s), "
            << (c.interrupted > 0 ? std::to_string(c.interrupted) + " interrupted, " : "")
            << c.skipped << " skipped (the scene does not fit the configuration) in "
            << fixed_text(wall, 1) << " s with " << workers << " job(s)\n";
  for (const auto& r : records) {
    if (r.status == "skipped")
      std::cout << "  skipped " << r.scene_name << " x " << r.spec.config << ": " << r.message
                << '\n';
  }
  if (!o.junit_path.empty()) write_junit_report(o.junit_path, records);
  return c;
}

std::string percent(int hit, int total) {
  return total ? fixed_text(100.0 * hit / total, 1) + " %" : std::string("-");
}

// The coverage figures regress --json and the summary.json of OUT/coverage carry: totals over rtl/,
// per file, the files no run elaborated, and every user cover point with its count.
nlohmann::json coverage_json(const CoverageSummary& sum, size_t runs) {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& f : sum.files) {
    files.push_back({{"file", fs::relative(f.path, source_dir()).string()},
                     {"lines", f.lines},
                     {"lines_hit", f.lines_hit},
                     {"toggles", f.toggles},
                     {"toggles_hit", f.toggles_hit},
                     {"elaborated", f.elaborated}});
  }
  nlohmann::json not_elaborated = nlohmann::json::array();
  for (const auto& f : sum.files_without_points)
    not_elaborated.push_back(fs::relative(f, source_dir()).string());
  nlohmann::json packages = nlohmann::json::array();
  for (const auto& f : sum.packages) packages.push_back(fs::relative(f, source_dir()).string());
  nlohmann::json points = nlohmann::json::array();
  int hit = 0;
  for (const auto& u : sum.user) {
    hit += u.count > 0;
    points.push_back({{"name", u.name}, {"count", u.count}});
  }
  return {{"runs", runs},
          {"rtl_lines", sum.lines},
          {"rtl_lines_hit", sum.lines_hit},
          {"rtl_line_pct", sum.line_pct()},
          {"rtl_toggles", sum.toggles},
          {"rtl_toggles_hit", sum.toggles_hit},
          {"rtl_toggle_pct", sum.toggle_pct()},
          {"user_points", sum.user.size()},
          {"user_points_hit", hit},
          {"files", files},
          {"files_without_points", not_elaborated},
          {"packages", packages},
          {"user_cover_points", points}};
}

// --coverage: merges the runs' coverage files into OUT/coverage/ (merged.dat, coverage.info for
// lcov, annotated sources), prints line and toggle coverage per file, the uncovered lines of
// rtl/, the user cover points and the exclusions. Returns whether rtl/ line coverage meets
// --coverage-min (true without one).
bool report_coverage(const std::vector<RunRecord>& records, const fs::path& out,
                     const RegressOptions& o, nlohmann::json* summary) {
  std::vector<std::string> dats;
  std::vector<std::string>
      without;  // runs that ran and left no coverage (killed, crashed, plain build)
  for (const auto& r : records) {
    const fs::path dat = fs::path(r.dir) / "coverage.dat";
    if (!r.dir.empty() && fs::exists(dat)) {
      dats.push_back(dat.string());
    } else if (r.status != "skipped") {
      without.push_back(r.spec.id() + " (" + r.status + ")");
    }
  }
  for (const auto& w : without)
    std::cout << "regress: coverage: no coverage file from run " << w << '\n';
  const fs::path dir = out / "coverage";
  fs::create_directories(dir);
  const fs::path rtl_dir = fs::path(source_dir()) / "rtl";
  const std::vector<std::string> rtl_files = rtl_source_files();
  const std::vector<CoverageExclusion> exclusions = list_exclusions(rtl_files);
  {
    std::ofstream ex(dir / "exclusions.txt");
    for (const auto& e : exclusions) {
      ex << fs::relative(e.file, source_dir()).string() << ':' << e.first_line << '-' << e.last_line
         << ": " << e.reason << '\n';
    }
  }
  if (dats.empty()) {
    std::cout << "regress: coverage: FAIL: no run wrote a coverage file\n";
    return false;
  }
  const fs::path merged = dir / "merged.dat", info = dir / "coverage.info",
                 annotated = dir / "annotated";
  merge_coverage(dats, merged.string(), info.string(), annotated.string());
  const CoverageSummary sum = summarize_coverage(merged.string(), rtl_dir.string(), rtl_files);

  std::cout << "\nregress: coverage of " << dats.size() << " run(s), merged into "
            << merged.string() << '\n'
            << "  " << std::left << std::setw(28) << "file" << std::right << std::setw(8) << "lines"
            << std::setw(10) << "line %" << std::setw(10) << "toggles" << std::setw(10)
            << "toggle %" << '\n';
  for (const auto& f : sum.files) {
    std::cout << "  " << std::left << std::setw(28) << fs::relative(f.path, source_dir()).string()
              << std::right << std::setw(8)
              << (std::to_string(f.lines_hit) + "/" + std::to_string(f.lines)) << std::setw(10)
              << percent(f.lines_hit, f.lines) << std::setw(10)
              << (std::to_string(f.toggles_hit) + "/" + std::to_string(f.toggles)) << std::setw(10)
              << percent(f.toggles_hit, f.toggles)
              << (f.elaborated ? "" : "  (no run elaborated it: its code lines count, none hit)")
              << '\n';
  }
  std::cout << "  " << std::left << std::setw(28) << "rtl/ (total)" << std::right << std::setw(8)
            << (std::to_string(sum.lines_hit) + "/" + std::to_string(sum.lines)) << std::setw(10)
            << percent(sum.lines_hit, sum.lines) << std::setw(10)
            << (std::to_string(sum.toggles_hit) + "/" + std::to_string(sum.toggles))
            << std::setw(10) << percent(sum.toggles_hit, sum.toggles) << '\n';
  for (const auto& f : sum.packages) {
    std::cout << "  no points (a package: constants and constant functions, nothing to run): "
              << fs::relative(f, source_dir()).string() << '\n';
  }
  for (const auto& f : sum.files) {
    if (!f.elaborated || f.uncovered_lines.empty() || fs::path(f.path).parent_path() != rtl_dir)
      continue;
    std::ifstream src(f.path);
    std::vector<std::string> text;
    for (std::string l; std::getline(src, l);) text.push_back(l);
    for (int l : f.uncovered_lines) {
      const std::string code = l >= 1 && static_cast<size_t>(l) <= text.size() ? text[l - 1] : "";
      std::cout << "  uncovered " << fs::relative(f.path, source_dir()).string() << ':' << l << ": "
                << code.substr(code.find_first_not_of(" \t") == std::string::npos
                                   ? 0
                                   : code.find_first_not_of(" \t"))
                << '\n';
    }
  }
  int user_hit = 0;
  for (const auto& u : sum.user) user_hit += u.count > 0;
  std::cout << "  user cover points: " << user_hit << " of " << sum.user.size() << " hit\n";
  for (const auto& u : sum.user) {
    std::cout << "    " << (u.count > 0 ? "hit    " : "MISSED ") << std::left << std::setw(30)
              << u.name << std::right << std::setw(10) << u.count << "  "
              << fs::relative(u.file, source_dir()).string() << ':' << u.line << '\n';
  }
  std::cout << "  exclusions (" << exclusions.size()
            << ", the RTL's coverage_off pragmas): " << (dir / "exclusions.txt").string() << '\n'
            << "  lcov: " << info.string()
            << "; annotated sources (%000000: never run): " << annotated.string() << '\n';
  *summary = coverage_json(sum, dats.size());
  std::ofstream(dir / "summary.json") << summary->dump(2) << '\n';
  if (o.coverage_min < 0) return true;
  const bool met = sum.lines > 0 && sum.line_pct() >= o.coverage_min;
  std::cout << "regress: coverage: rtl/ line coverage " << fixed_text(sum.line_pct(), 2) << " % "
            << (met ? ">= " : "is below ") << "--coverage-min " << number_text(o.coverage_min)
            << " %" << (met ? "" : ": FAIL") << '\n';
  return met;
}

}  // namespace

int run_regress(const RegressOptions& o) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  if (o.list) {
    list_named_builds();
    return 0;
  }
  for (const auto& b : o.backends) {
    if (b != "cpp" && b != "systemc")
      throw std::invalid_argument("--backends: '" + b + "': expected cpp or systemc");
  }
  const int workers =
      std::max(1, o.jobs > 0 ? o.jobs : static_cast<int>(std::thread::hardware_concurrency()));

  // Select configurations and scenes; a new plan is written down (or handed out as job lines).
  const Selection sel = o.resume.empty() ? select_planned(o) : select_resumed(o);
  if (!o.emit_jobs.empty()) {
    emit_jobs(o, sel.settings, sel.out, sel.all, sel.selected);
    return 0;
  }
  if (o.resume.empty()) write_and_announce_plan(o, sel);
  print_settings(sel, o.coverage);

  // Host setup, build, run: each run's record is on disk the moment it ends.
  RtlPrefetch prefetch(build_options(o), workers);
  std::unique_ptr<NetlistSource> netlists;
  if (o.netlist) netlists = std::make_unique<NetlistSource>(o, workers);
  std::vector<Job> jobs =
      plan_jobs(sel.selected, sel.out, sel.base, prefetch, netlists.get(), o, sel.settings);
  if (netlists) resolve_netlists(jobs, *netlists);
  const auto t0 = std::chrono::steady_clock::now();
  const InterruptGuard interrupt;  // Ctrl-C: no new runs; the rest are recorded as interrupted
  build_all(jobs, o, workers);
  run_jobs(jobs, o, sel.settings, workers);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Collect, report, exit code.
  const std::vector<RunRecord> records = collect_records(sel.earlier, jobs);
  const RunCounts c = report_runs(records, o, wall, workers);
  nlohmann::json coverage = nullptr;
  const bool coverage_met = !o.coverage || report_coverage(records, sel.out, o, &coverage);
  if (!o.json_path.empty()) {
    write_json_report(o.json_path, records,
                      {{"seed", o.seed}, {"wall_seconds", wall}, {"coverage", coverage}});
  }

  if (InterruptGuard::requested()) {
    std::cout << "regress: interrupted by signal " << InterruptGuard::signal_number() << ": "
              << c.interrupted << " run(s) recorded as interrupted; run them with: " << self_path()
              << " regress --resume " << shell_word(sel.out.string()) << std::endl;
    return 128 + InterruptGuard::signal_number();
  }
  if (c.passed == 0 && !c.failed()) {
    std::cout << "regress: FAIL: no run was executed\n";
    return 1;
  }
  return c.failed() || !coverage_met ? 1 : 0;
}

}  // namespace shadesim
