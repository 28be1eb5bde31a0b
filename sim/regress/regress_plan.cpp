// A regression's plan (sim/regress/regress_plan.h).
#include "sim/regress/regress_plan.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "model/text_file.h"
#include "sim/eda/common/build_paths.h"
#include "sim/eda/common/shell.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/engines/unit_choice.h"
#include "sim/harness/rtl_config.h"

namespace shadesim {

namespace fs = std::filesystem;

// A named namespace, not an anonymous one: sim/ is compiled as unity files (CMakeLists.txt).
namespace regress_plan_impl {
std::string join(const std::vector<std::string>& words) {
  std::string s;
  for (const auto& w : words) s += (s.empty() ? "" : ", ") + w;
  return s;
}
}  // namespace regress_plan_impl

fs::path run_dir(const fs::path& out, const RunSpec& s) { return out / "runs" / s.id(); }

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

nlohmann::json settings_json(const RunSettings& s) {
  nlohmann::json j = {{"gap_pct", s.gap_pct},
                      {"max_gap", s.max_gap},
                      {"stall_pct", s.stall_pct},
                      {"timeout", s.timeout},
                      {"watchdog", s.watchdog}};
  if (!s.fault.empty()) j["fault"] = s.fault;  // plans without it stay as they were
  return j;
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

// One self-contained command per run: it plans exactly that run (one scene, one configuration,
// one backend, its seed) into the same OUT/runs/<id>/ the whole regression would use.
void emit_job_lines(const RegressOptions& o, const RunSettings& settings, const fs::path& out,
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

std::string number_text(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

std::string self_path() {
  const fs::path self = self_executable("--emit-jobs");
  std::error_code ec;
  const fs::path rel = fs::relative(self, fs::current_path(), ec);
  if (!ec && !rel.empty() && *rel.begin() != "..") return rel.string();
  return self.string();
}

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
                                 : "; random scenario(s) " + regress_plan_impl::join(o.random) +
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

}  // namespace shadesim
