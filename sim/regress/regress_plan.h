// A regression's plan: which runs a regress process was asked for (scenes x configurations x
// backends, seeds, shards), the settings every process of it shares, the plan files written into
// OUT/plans/ and read back by --resume, and --emit-jobs' one command per run.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/regress/regress.h"
#include "sim/regress/regress_results.h"
#include "sim/regress/regress_stimulus.h"

namespace shadesim {

struct Shard {
  int index = 1, count = 1;  // 1-based, as Slurm's array task ids are
};

// "I/N" (--shard); std::invalid_argument naming the expected form otherwise.
Shard parse_shard(const std::string& text);

// The stimulus and run limits a plan fixes; every process running part of it uses the same.
struct RunSettings {
  int gap_pct = kRegressStimulus.gap_pct, max_gap = kRegressStimulus.max_gap,
      stall_pct = kRegressStimulus.stall_pct;
  double timeout = 1800;
  uint64_t watchdog = 0;
  std::string fault;  // SITE@Y or empty (sim/harness/fault_site.h)
};

nlohmann::json settings_json(const RunSettings& s);

// The shipped scenes: ./scenes, else this checkout's scenes/.
std::vector<std::string> default_scenes();

// The whole job list, before any host work: scenes x configurations x backends. Each scene and
// configuration gets the next seed (both backends the same one), so a run's seed depends only on
// its place in this list, never on what another run found.
std::vector<RunSpec> full_run_list(const RegressOptions& o, const std::vector<std::string>& scenes);

// What a regress process was asked to run, written into OUT/plans/ before it runs anything:
// merge compares it with the results to name what is missing; --resume runs the rest of it.
void write_plan(const std::filesystem::path& out, const std::string& name,
                const RunSettings& settings, const std::string& shard,
                const std::vector<RunSpec>& all, const std::vector<RunSpec>& selected);

struct LoadedPlans {
  RunSettings settings;
  std::vector<RunSpec> selected;
  std::filesystem::path base;  // the folder the plans' relative paths are relative to
};

// --resume DIR: the runs DIR's plans selected, with their settings (which must agree).
LoadedPlans load_plans(const std::filesystem::path& dir);

// One self-contained command per run: it plans exactly that run (one scene, one configuration,
// one backend, its seed) into the same OUT/runs/<id>/ the whole regression would use.
void emit_job_lines(const RegressOptions& o, const RunSettings& settings,
                    const std::filesystem::path& out, const std::vector<RunSpec>& all,
                    const std::vector<RunSpec>& selected);

// What one regress process runs: the selected runs (and, with --resume, the results already
// there), where results go and the settings every run uses.
struct Selection {
  std::vector<std::string> scenes;  // a new plan: its scenes and whole job list
  std::vector<RunSpec> all;
  std::vector<RunSpec> selected;
  std::vector<RunRecord> earlier;  // --resume: results already there
  std::filesystem::path out;
  std::filesystem::path base;  // --resume: where the plan's relative paths start
  RunSettings settings;
};

// Where a run's results go: OUT/runs/<id>/.
std::filesystem::path run_dir(const std::filesystem::path& out, const RunSpec& s);

// --resume DIR: the runs DIR's plans name that have no result there (or ended in an error).
Selection select_resumed(const RegressOptions& o);

// Scenes x configurations x backends, and the runs of this process's shard of it.
Selection select_planned(const RegressOptions& o);

// The plan, written into OUT/plans/ before anything runs, and what it holds.
void write_and_announce_plan(const RegressOptions& o, const Selection& sel);

// One line of the stimulus, timeout and coverage settings.
void print_settings(const Selection& sel, bool coverage);

// A number as a person writes it: 1800, 0.5.
std::string number_text(double v);

// This shadesim, as a path that works from the current folder on every host with the same
// checkout: relative when it is below the current folder, absolute otherwise.
std::string self_path();

}  // namespace shadesim
